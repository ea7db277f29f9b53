"""The match drill's options record: built by keyword or as a record, the same drill."""

from __future__ import annotations

import dataclasses

import pytest

from field_models.registry import field_facts
from robotsoccer.drills import drill_options, make_drill
from robotsoccer.drills.match import MatchDrill
from robotsoccer.drills.match_options import MatchOptions, TeamKind
from robotsoccer.skills.layer3 import TpotSettings


def test_the_registry_names_the_records_fields_in_order() -> None:
    fields = tuple(f.name for f in dataclasses.fields(MatchOptions))
    assert drill_options("match") == fields
    assert fields[:6] == ("left", "right", "net", "tree", "players", "half_time_s")


def test_text_values_become_their_kinds() -> None:
    given = {"left": "baseline", "players": "5", "half_time_s": "30", "look": "neck"}
    options = MatchOptions(**given)  # type: ignore[arg-type]
    assert options.left is TeamKind.BASELINE and options.right is TeamKind.BASELINE
    assert options.players == 5 and options.half_time_s == 30.0
    assert options.steady_turns is True  # look=neck turns with the steady turns' rules


def test_a_record_and_its_keywords_build_the_same_drill() -> None:
    given = {"left": "layer3", "net": "n.npz", "tree": "t.json", "tpot": "q.npz", "explore": "0.2"}
    by_keyword = make_drill("match", given)
    assert isinstance(by_keyword, MatchDrill)
    by_record = MatchDrill(MatchOptions(**given))  # type: ignore[arg-type]
    assert by_keyword.options == by_record.options
    assert by_record.inputs() == ("t.json", "n.npz", "q.npz")


def test_a_baseline_match_keeps_no_model_files() -> None:
    drill = MatchDrill(left="baseline", net="n.npz", tree="t.json", tpot="q.npz")
    assert drill.inputs() == ()


def test_layer_3s_options_become_its_settings() -> None:
    options = MatchOptions(
        left=TeamKind.LAYER3,
        net="n",
        tree="t",
        tpot="q",
        explore=0.3,
        learn=True,
        tpot_every=True,
        tpot_success=0.7,
        tpot_window="horizon",
        tpot_guard=True,
        tpot_loss=0.5,
    )
    assert options.tpot_settings() == TpotSettings(
        threshold=0.7,
        epsilon=0.3,
        learn=True,
        every_ball=True,
        window="horizon",
        shot_guard=True,
        loss_penalty=0.5,
    )


def test_a_record_and_keywords_together_are_refused() -> None:
    with pytest.raises(ValueError, match="not both"):
        MatchDrill(MatchOptions(left=TeamKind.BASELINE), right="baseline")


@pytest.mark.parametrize(
    ("given", "message"),
    [
        ({"look": "eyes", "left": "x"}, "look: expected one of body, neck"),  # first one named
        ({"left": "baseline", "players": 7}, "players must be 0"),
        ({"left": "baseline", "tpot_guard": "true"}, "tpot_guard needs tpot_every"),
        ({"left": "baseline", "tpot_loss": 2}, r"tpot_loss must be a number in \[0, 1\]"),
        ({"left": "baseline", "nope": 1}, "has no option 'nope'"),
        (
            {"left": "baseline", "receiver_half": "heard"},
            "receiver_half: expected one of unknown, estimated; got 'heard'",
        ),
    ],
)
def test_bad_options_are_one_line_errors(given: dict[str, object], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        make_drill("match", given)


def test_net_domain_takes_any_or_trained_and_refuses_the_rest_in_one_line() -> None:
    assert MatchOptions(left=TeamKind.BASELINE).net_domain == "any"
    trained = MatchOptions(left=TeamKind.BASELINE, net_domain="trained")
    assert trained.net_domain == "trained"
    with pytest.raises(ValueError, match=r"^net_domain: expected one of any, trained; got 'x'$"):
        MatchOptions(left=TeamKind.BASELINE, net_domain="x")


def test_the_receiver_half_reaches_both_teams_setups() -> None:
    facts = field_facts("soccer_server", "soccer_server_1996")
    for value in ("unknown", "estimated"):
        drill = MatchDrill(left="baseline", right="baseline", receiver_half=value)
        assert drill.options.receiver_half == value
        assert [drill.team_setup(facts, 11, side).receiver_half for side in ("left", "right")] == [
            value,
            value,
        ]
    assert MatchOptions(left=TeamKind.BASELINE).receiver_half == "unknown"
