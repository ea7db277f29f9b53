"""The interception drill's options record: built by keyword or as a record, the same drill."""

from __future__ import annotations

import dataclasses

import pytest

from robotsoccer.drills import drill_options, make_drill
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.intercept_options import Decision, InterceptOptions, Launch, Scaling
from robotsoccer.skills.intercept import Behaviour


def test_the_registry_names_the_records_fields_in_order() -> None:
    fields = tuple(f.name for f in dataclasses.fields(InterceptOptions))
    assert drill_options("intercept") == fields
    assert fields[:3] == ("behaviour", "model", "ta_mode")


def test_text_values_become_their_kinds() -> None:
    options = InterceptOptions(**{"behaviour": "random", "launch": "coach", "scaling": "task"})
    assert options.behaviour is Behaviour.RANDOM
    assert options.launch is Launch.COACH and options.scaling is Scaling.TASK
    assert options.decision is Decision.TURN


def test_a_record_and_its_keywords_build_the_same_drill() -> None:
    given = {"behaviour": "still", "sector_deg": 30, "defender_kick": "true", "kick_power": 80}
    by_keyword = make_drill("intercept", given)
    assert isinstance(by_keyword, InterceptDrill)
    by_record = InterceptDrill(InterceptOptions(**given))  # type: ignore[arg-type]
    assert by_keyword.options == by_record.options
    assert by_record.defender_kick is True and by_record.kick_power == 80.0


def test_a_record_and_keywords_together_are_refused() -> None:
    with pytest.raises(ValueError, match="not both"):
        InterceptDrill(InterceptOptions(), behaviour="still")


@pytest.mark.parametrize(
    ("given", "message"),
    [
        ({"sector_deg": 100}, "sector_deg must be in"),
        ({"lead_time_scale": 2}, "lead_time_scale scales a lead net"),
        ({"nope": 1}, "has no option 'nope'"),
    ],
)
def test_bad_options_are_one_line_errors(given: dict[str, object], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        make_drill("intercept", given)
