"""One seed per trial, many named generators; a stream not declared is an error."""

from __future__ import annotations

import numpy as np
import pytest

from field_models.seeding import STREAMS, Stream, StreamBatch, TrialRngs, stream_key


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


def test_a_batch_of_streams_draws_exactly_what_each_trial_stream_draws() -> None:
    trials = np.array([0, 1, 5, 1000, 2**40])
    batch = StreamBatch.for_trials(9, trials, "movement")
    first, second = batch.take(3), batch.take(4, rows=np.array([1, 3]))
    for row, trial in enumerate(trials.tolist()):
        stream = TrialRngs.for_trial(9, trial)["movement"]
        assert stream.key == stream_key(9, trial, "movement") == int(batch.keys[row])
        np.testing.assert_array_equal(stream.random(3), first[row])
        if row in (1, 3):  # the single draw path and the array path agree bit for bit
            drawn = [stream.random() for _ in range(2)]
            np.testing.assert_array_equal([*drawn, *stream.random(2)], second[row // 2])


def test_stream_draws_look_uniform_and_normal_and_streams_differ() -> None:
    stream = TrialRngs.for_trial(0, 0)["placement"]
    u = stream.random(200_000)
    assert u.min() >= 0.0 and u.max() < 1.0
    assert abs(u.mean() - 0.5) < 0.005 and abs(u.var() - 1 / 12) < 0.002
    counts = np.bincount((u * 10).astype(int), minlength=10)
    assert counts.min() > 19_000 and counts.max() < 21_000
    z = stream.standard_normal(100_001)
    assert abs(z.mean()) < 0.02 and abs(z.std() - 1.0) < 0.02
    keys = {stream_key(s, t, n) for s in range(3) for t in range(3) for n in STREAMS}
    assert len(keys) == 9 * len(STREAMS)
    assert {stream.integers(3) for _ in range(200)} == {0, 1, 2}


def test_positions_advance_with_every_draw() -> None:
    a, b = Stream(stream_key(1, 2, "policy")), Stream(stream_key(1, 2, "policy"))
    a.uniform(-1.0, 1.0)
    a.random((2, 3))
    assert a.position == 7
    assert a.random() == b.random(8)[7]
