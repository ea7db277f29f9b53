"""The pass drill's and the set play's options records: by keyword or as a record, one drill."""

from __future__ import annotations

import dataclasses

import pytest

from robotsoccer.drills import drill_options, make_drill
from robotsoccer.drills.layered_options import PassOptions, SetPlayOptions
from robotsoccer.drills.passing import PassDrill
from robotsoccer.drills.setplay import SetPlayDrill
from robotsoccer.skills.intercept import Behaviour
from robotsoccer.skills.passing import Chooser


def test_the_registry_names_the_records_fields_in_the_old_keyword_order() -> None:
    # The order the constructors' keywords had, so option lists and their help read as before.
    assert drill_options("pass") == (
        "chooser",
        "model",
        "interceptor",
        "net",
        "defenders",
        "max_time_s",
        "transfer",
        "receiver_half",
        "client",
    )
    assert drill_options("setplay") == (
        "chooser",
        "model",
        "interceptor",
        "net",
        "max_time_s",
        "transfer",
        "pass_speed_mps",
        "defenders",
        "client",
        "look",
    )
    assert drill_options("pass") == tuple(f.name for f in dataclasses.fields(PassOptions))


def test_pass_text_values_become_their_kinds() -> None:
    given = {"chooser": "closest", "interceptor": "still", "max_time_s": "8", "transfer": "true"}
    drill = make_drill("pass", given)
    assert isinstance(drill, PassDrill)
    assert drill.chooser is Chooser.CLOSEST and drill.interceptor is Behaviour.STILL
    assert drill.max_time_s == 8.0 and drill.transfer is True
    assert drill.options == PassOptions(**given)  # type: ignore[arg-type]
    assert not drill.defenders_still and drill.use_reports


def test_pass_modes_reach_the_drill() -> None:
    drill = PassDrill(PassOptions(defenders="still", receiver_half="ignore"))
    assert drill.defenders_still and not drill.use_reports


def test_setplay_text_values_become_their_kinds() -> None:
    given = {"chooser": "random", "pass_speed_mps": "1.5", "defenders": "straight"}
    drill = make_drill("setplay", given)
    assert isinstance(drill, SetPlayDrill)
    assert drill.chooser is Chooser.RANDOM and drill.pass_speed_mps == 1.5
    assert drill.defenders is Behaviour.STRAIGHT
    assert drill.max_time_s == 60.0  # until set-up sets the plan's limit
    assert SetPlayDrill(SetPlayOptions(max_time_s=5)).max_time_s == 5.0
    assert SetPlayDrill().defenders == "same"


@pytest.mark.parametrize("drill", [PassDrill, SetPlayDrill])
def test_a_record_and_keywords_together_are_refused(drill: type[PassDrill]) -> None:
    with pytest.raises(ValueError, match="not both"):
        drill(drill.OPTIONS(), chooser="random")


@pytest.mark.parametrize(
    ("name", "given", "message"),
    [
        ("pass", {"chooser": "tree"}, "needs a model file"),
        ("pass", {"chooser": "nope"}, "chooser"),
        ("pass", {"defenders": "few"}, "unknown defenders 'few'"),
        ("pass", {"receiver_half": "half"}, "unknown receiver_half 'half'"),
        ("pass", {"max_time_s": 0}, "max_time_s"),
        # Of two bad options the first checked is named, as the keyword constructor did.
        ("pass", {"chooser": "tree", "defenders": "few"}, "needs a model file"),
        ("setplay", {"chooser": "boost"}, "needs a model file"),
        ("setplay", {"max_time_s": -1}, "max_time_s"),
        ("setplay", {"defenders": "nope"}, "nope"),
        ("setplay", {"nope": 1}, "has no option 'nope'"),
    ],
)
def test_bad_options_are_one_line_errors(name: str, given: dict[str, object], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        make_drill(name, given)
