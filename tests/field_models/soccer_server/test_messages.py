"""Soccer Server text messages: round trips, Figure 4, malformed input (spec §3.7, §2.6)."""

from __future__ import annotations

import contextlib

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from field_models.protocol import PlayerRef
from field_models.soccer_server.hearing import HearInfo
from field_models.soccer_server.messages import (
    MessageParseError,
    parse_hear,
    parse_see,
    parse_see_general,
    parse_sexpr,
    render_hear,
    render_see,
)
from field_models.soccer_server.sensing import Bodies, SeeInfo, SeenObject, observe
from field_models.soccer_server.sensing_params import SENSING_19, SENSING_1996, SensingParams

# The paper's Figure 4 (Stone & Veloso 1996), as the client received it.
FIGURE_4_SEES = [
    "(see 124 ((goal r) 20.1 34) ((flag r t) 47.5 -4) ((flag p r t) 30.3 -24) "
    "((flag p r c) 10.1 -20) ((ball) 11 0) ((player usa 2) 21 19) ((player usa 3) 21 -11) "
    "((player brazil 1) 17 35) ((line r) 40 -26))",
    "(see 129 ((goal r) 16 43) ((flag r t) 42 -6) ((flag p r t) 25 -30) ((flag p r c) 5 -40) "
    "((ball) 6 1) ((player usa 2) 16.3 24) ((player usa 3) 15.3 -17) ((line r) 32.8 -27))",
    "(see 134 ((flag r t) 40 -9) ((flag p r t) 23.3 -35) ((ball) 3.7 2) ((player usa 2) 14.4 24) "
    "((player usa 3) 13.3 -22) ((line r) 28.2 -30))",
    "(see 139 ((flag r t) 38.1 -11) ((flag p r t) 22 -39) ((ball) 1.9 0) ((player usa 2) 12.8 27) "
    "((player usa 3) 11.6 -27) ((line r) 25.5 -31))",
    "(see 144 ((flag r t) 38.1 -11) ((flag p r t) 22 -39) ((ball) 8.1 42) ((player usa 2) 12.8 27) "
    "((player usa 3) 11.6 -27) ((line r) 25.5 -31))",
    "(see 149 ((goal r) 13.6 9) ((ball) 13.5 5 0) ((player usa 2) 12.8 -14) "
    "((player brazil 1) 11 18) ((line r) 14 -73))",
]
FIGURE_4_HEARS = [
    "(hear 138 18 shoot the ball)",
    "(hear 141 self shooting now)",
    "(hear 150 referee goal_l_1)",
    "(hear 150 referee kick_off_r)",
]

PLAYERS = (PlayerRef("left", 1), PlayerRef("left", 2), PlayerRef("right", 7))
PROTOCOLS = [3, 4, 5, 6, 7, 8, 19]


# ----------------------------------------------------------------------------- Figure 4


@pytest.mark.parametrize("text", FIGURE_4_SEES)
def test_figure_4_see_lines_parse_and_render_back(text: str) -> None:
    info = parse_see(text)
    assert render_see(info, protocol=3) == text


def test_figure_4_see_contents() -> None:
    first = parse_see(FIGURE_4_SEES[0])
    assert first.time == 124
    assert len(first.objects) == 9
    assert first.find("g r") == SeenObject("g r", 20.1, 34)
    assert first.find("b") == SeenObject("b", 11.0, 0)
    players = [o for o in first.objects if o.name == "p"]
    assert [(p.team, p.unum, p.distance, p.direction) for p in players] == [
        ("usa", 2, 21.0, 19),
        ("usa", 3, 21.0, -11),
        ("brazil", 1, 17.0, 35),
    ]
    assert first.objects[-1] == SeenObject("l r", 40.0, -26)
    last = parse_see(FIGURE_4_SEES[-1])
    # "((ball) 13.5 5 0)": three numbers = distance, direction, distance change.
    assert last.find("b") == SeenObject("b", 13.5, 5, 0.0)
    assert last.objects[-1] == SeenObject("l r", 14.0, -73)


def test_figure_4_hear_lines() -> None:
    heard = [parse_hear(t) for t in FIGURE_4_HEARS]
    assert heard[0] == HearInfo(138, "player", "shoot the ball", 18)
    assert heard[1] == HearInfo(141, "self", "shooting now")
    assert heard[2] == HearInfo(150, "referee", "goal_l_1")
    assert heard[3] == HearInfo(150, "referee", "kick_off_r")
    assert [render_hear(h, protocol=3) for h in heard] == FIGURE_4_HEARS


# ----------------------------------------------------------------------------- round trips


def random_see(seed: int, params: SensingParams, observer: int = 1) -> SeeInfo:
    g = np.random.default_rng(seed)
    n = len(PLAYERS) + 1
    return observe(
        observer,
        Bodies(
            g.uniform(-58, 58, n).tolist(),
            g.uniform(-38, 38, n).tolist(),
            g.uniform(-2, 2, n).tolist(),
            g.uniform(-2, 2, n).tolist(),
            g.uniform(-np.pi, np.pi, n).tolist(),
        ),
        PLAYERS,
        int(g.integers(0, 6000)),
        params,
        g,
    )


@pytest.mark.parametrize("protocol", PROTOCOLS)
@pytest.mark.parametrize("base", [SENSING_19, SENSING_1996], ids=["19", "1996"])
def test_see_render_parse_round_trip(protocol: int, base: SensingParams) -> None:
    params = base.replace(protocol_version=protocol)
    seen = 0
    for seed in range(150):
        info = random_see(seed, params, observer=1 + seed % 3)
        text = render_see(info, protocol)
        assert parse_see(text) == info, text
        seen += len(info.objects)
    assert seen > 300  # the states really showed things


def test_low_quality_see_round_trips() -> None:
    params = SENSING_19.replace(view_quality="low")
    for seed in range(30):
        info = random_see(seed, params)
        assert parse_see(render_see(info)) == info


def test_short_and_long_names() -> None:
    info = SeeInfo(
        3,
        (
            SeenObject("f p l b", 12.0, -3),
            SeenObject("B", 1.2, 170),
            SeenObject("p", 33.1, 4, team="right"),
            SeenObject("p", 55.0, -8),
            SeenObject("P", 2.0, -120),
        ),
    )
    modern = '(see 3 ((f p l b) 12 -3) ((B) 1.2 170) ((p "right") 33.1 4) ((p) 55 -8) ((P) 2 -120))'
    old = (
        "(see 3 ((flag p l b) 12 -3) ((Ball) 1.2 170) ((player right) 33.1 4) ((player) 55 -8) "
        "((Player) 2 -120))"
    )
    assert render_see(info, 8) == modern
    assert render_see(info, 5) == old
    assert parse_see(modern) == info == parse_see(old)


def test_fast_and_general_see_parsers_agree_on_spacing_variants() -> None:
    text = FIGURE_4_SEES[0]
    spaced = text.replace(") (", ")\n  (").replace("((", "( (").replace(" 21 ", "  21\t")
    assert parse_see_general(spaced) == parse_see(spaced) == parse_see(text)


def test_real_server_extras_are_accepted() -> None:
    text = (
        '(see 0 ((p "opp" 5 goalie) 4.5 10 0.09 1.2 30 40 60 k) ((p "opp" 6) 20 1 0 0 0 0 t) '
        "((f c) 11.1 -27 -0 0))\0"
    )
    info = parse_see(text)
    assert info.objects[0] == SeenObject("p", 4.5, 10, 0.09, 1.2, "opp", 5, 30, 40)
    assert info.objects[1].unum == 6
    assert info.objects[2] == SeenObject("f c", 11.1, -27, 0.0, 0.0)


@pytest.mark.parametrize(
    "info",
    [
        HearInfo(5, "player", "pass 7", -30),
        HearInfo(5, "self", "go now"),
        HearInfo(5, "referee", "play_on"),
        HearInfo(5, "online_coach_left", "formation"),
    ],
)
@pytest.mark.parametrize("protocol", [3, 7])
def test_hear_round_trip_old_forms(info: HearInfo, protocol: int) -> None:
    text = render_hear(info, protocol)
    assert parse_hear(text) == info


def test_hear_forms_by_protocol() -> None:
    msg = HearInfo(9, "player", "pass 7", 12, "our", 4)
    assert render_hear(msg, 19) == '(hear 9 12 our 4 "pass 7")'
    assert render_hear(HearInfo(9, "player", "x", -3, "opp"), 19) == '(hear 9 -3 opp "x")'
    assert render_hear(HearInfo(9, "player", None, None, "our", 4), 19) == "(hear 9 our 4)"
    assert render_hear(HearInfo(9, "player", None, None, "opp"), 19) == "(hear 9 opp)"
    assert render_hear(HearInfo(9, "player", "pass 7", 12), 7) == '(hear 9 12 "pass 7")'
    assert render_hear(HearInfo(9, "self", "hi"), 8) == '(hear 9 self "hi")'
    for info in (
        msg,
        HearInfo(9, "player", "x", -3, "opp"),
        HearInfo(9, "player", None, None, "our", 4),
        HearInfo(9, "player", None, None, "opp"),
    ):
        assert parse_hear(render_hear(info, 19)) == info
    with pytest.raises(ValueError, match="protocol 8"):
        render_hear(HearInfo(9, "player", None, None, "our", 4), 6)


def test_old_hear_keeps_parentheses_in_the_message() -> None:
    assert parse_hear("(hear 3 -20 pass (to) 7)") == HearInfo(3, "player", "pass (to) 7", -20)


# ----------------------------------------------------------------------------- malformed input


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("", "expected '('"),
        ("see 1 ((b) 1 2)", "expected '('"),
        ("(see 1 ((b) 1 2)", "missing ')'"),
        ("(see 1 ((b) 1 2)))", "after the closing"),
        ("(see x ((b) 1 2))", "time"),
        ("(see -1 ((b) 1 2))", "time"),
        ("(see 1 ((b) 1 2x))", "direction"),
        ("(see 1 ((b) 1 180.5))", "outside"),
        ("(see 1 ((b) -1 2))", "distance"),
        ("(see 1 ((b) nan 2))", "distance"),
        ("(see 1 ((b) 1e999 2))", "finite"),
        ("(see 1 ((b) 1 200))", "outside"),
        ("(see 1 ((q r) 1 2))", "unknown object"),
        ("(see 1 ((f z 99) 1 2))", "unknown object"),
        ("(see 1 ((b)))", "expected '((name) numbers...)'"),
        ("(see 1 ((b) 1 2 3 4 5))", "1 to 4 numbers"),
        ('(see 1 ((p "a) 1 2))', "unterminated"),
        ("(see 1 (b 1 2))", "object"),
        ("(see 1 ((p t 0) 1 2))", "uniform number"),
        ("(hear 1 referee)", "empty message"),
        ("(hear 1)", "missing sender"),
        ("(hear 1 500 hi)", "outside"),
        ('(hear 1 3 "hi)', "quoted"),
        ("(hear 1 self )", "empty"),
        ("(hear x self hi)", "time"),
    ],
)
def test_malformed_messages_raise_a_clear_error(text: str, fragment: str) -> None:
    parsers = {"(see": parse_see, "(hear": parse_hear}
    parser = next((p for k, p in parsers.items() if text.startswith(k)), parse_see)
    with pytest.raises(MessageParseError) as err:
        parser(text)
    assert fragment in str(err.value)
    assert f"in message {text!r}" in str(err.value)  # the offending text is shown
    assert isinstance(err.value, ValueError)


def test_error_names_the_position() -> None:
    with pytest.raises(MessageParseError) as err:
        parse_sexpr("(see 1 ((b) 1 2)))")
    assert err.value.position == 17
    assert "position 17" in str(err.value)
    with pytest.raises(MessageParseError, match="deeper"):
        parse_sexpr("(" * 50 + ")" * 50)


ALPHABET = st.sampled_from(list('()" \t0123456789.-+eEabcdfglprtseknhou_\0\n'))
VALID = (
    FIGURE_4_SEES
    + FIGURE_4_HEARS
    + [
        '(see 0 ((f c) 11.1 -27 0 0) ((p "left" 2) 5 0 0 -2.3 -30 -30) ((l r) 62.8 90))',
        '(hear 9 12 our 4 "pass 7")',
        '(see 3 ((b) 11.180339887498949 -26.56505117707799 0.1 -0.25) ((p "left" 2) 5.5 1.5))',
    ]
)


def _parse_any(text: str) -> None:
    for parser in (parse_see, parse_hear):
        with contextlib.suppress(MessageParseError):
            parser(text)
    # The see fast path and the general parser agree: same record, or both refuse.
    fast = general = None
    with contextlib.suppress(MessageParseError):
        fast = parse_see(text)
    with contextlib.suppress(MessageParseError):
        general = parse_see_general(text)
    assert fast == general


@settings(max_examples=600, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.text(ALPHABET, max_size=80) | st.text(max_size=60))
def test_fuzz_random_text_never_crashes(text: str) -> None:
    _parse_any(text)  # anything but MessageParseError fails the test


@settings(max_examples=800, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.sampled_from(VALID),
    st.lists(
        st.tuples(st.integers(0, 400), st.integers(0, 3), st.text(ALPHABET, max_size=3)),
        min_size=1,
        max_size=4,
    ),
)
def test_fuzz_mutated_messages_never_crash(base: str, edits: list[tuple[int, int, str]]) -> None:
    text = base
    for pos, cut, insert in edits:
        pos %= len(text) + 1
        text = text[:pos] + insert + text[pos + cut :]
    _parse_any(text)
