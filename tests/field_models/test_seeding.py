"""One seed per trial, many named generators; a stream not declared is an error."""

from __future__ import annotations

import pytest

from field_models.seeding import STREAMS, TrialRngs


def test_each_declared_stream_is_one_generator_per_trial() -> None:
    rngs = TrialRngs.for_trial(0, 0)
    assert all(rngs[name] is rngs[name] for name in STREAMS)
    again = TrialRngs.for_trial(0, 0)
    assert all(rngs[n].random() == again[n].random() for n in STREAMS)
    other = TrialRngs.for_trial(0, 1)
    assert rngs["placement"].random() != other["placement"].random()


def test_a_misspelt_random_stream_is_an_error_not_a_fresh_stream() -> None:
    rngs = TrialRngs.for_trial(0, 0)
    with pytest.raises(KeyError, match="unknown random stream 'placment'"):
        rngs["placment"]
