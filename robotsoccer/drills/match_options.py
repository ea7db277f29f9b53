"""The match drill's options as one typed record (:class:`MatchOptions`).

The drill (:mod:`robotsoccer.drills.match`) is built from these options, by keyword
(``MatchDrill(left="layered", net=..., tree=...)``, ``make_drill("match", {...})``, a command
line's ``--option NAME=VALUE``) or from a record (``MatchDrill(MatchOptions(...))``), as the
interception drill is from :class:`~robotsoccer.drills.intercept_options.InterceptOptions`.
Text values (a run spec's or a command line's) are turned into their kinds here, once, and
every option is checked here, so a bad one is refused in one line before any field is built.
What each option does is told in the drill's module docstring; layer 3's options become one
:class:`~robotsoccer.skills.layer3.TpotSettings` (:meth:`MatchOptions.tpot_settings`).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from field_models.protocol import LEFT, RIGHT
from learning.tpot import REWARD_WINDOWS, WINDOW_CHOICE
from robotsoccer.drills.match_setup import FORMATIONS
from robotsoccer.options import bounded, choice, duration, flag
from robotsoccer.skills.layer3 import TpotSettings
from robotsoccer.skills.team_cycle import CLIENT_MODES
from robotsoccer.skills.team_setup import LOOK_MODES, TURN_LATENCIES, check_receiver_half

HALF_TIME_S = 300.0
"""One half [s]: rcssserver's ``half_time`` (3000 cycles)."""
PASS_THRESHOLD = 0.5
"""The layered team's pass threshold (:attr:`TeamMind.pass_threshold`'s default), layer 3's
SUCCESS cut."""


class TeamKind(StrEnum):
    """A team's behaviour (:mod:`robotsoccer.drills.match`)."""

    LAYERED = "layered"
    BASELINE = "baseline"
    LAYER3 = "layer3"


DEAD_BAND_VALUES = ("false", "true", LEFT, RIGHT)
"""What the match's ``dead_band`` option takes (:func:`dead_band_teams`)."""
NET_DOMAINS = ("any", "trained")
"""Where a layered team asks its turn-angle net (:attr:`MatchOptions.net_domain`)."""


def dead_band_teams(value: bool | str) -> frozenset[str]:
    """The teams whose minds use the dead band: True both, ``left``/``right`` one, False none.

    Raises:
        ValueError: Any other value, naming the allowed ones.
    """
    text = str(value).lower() if isinstance(value, bool | str) else ""
    if text not in DEAD_BAND_VALUES:
        known = ", ".join(DEAD_BAND_VALUES)
        raise ValueError(f"dead_band must be one of {known}, got {value!r}")
    if text in (LEFT, RIGHT):
        return frozenset((text,))
    return frozenset((LEFT, RIGHT)) if text == "true" else frozenset()


def one_team(value: str, option: str, modes: tuple[str, str]) -> frozenset[str]:
    """The teams that take an option's second mode: both for it, one for its side, else none.

    `modes` is (the default, the other); ``left`` or ``right`` gives that team the other mode.

    Raises:
        ValueError: Any other value, naming the allowed ones.
    """
    if value not in (*modes, LEFT, RIGHT):
        known = ", ".join((*modes, LEFT, RIGHT))
        raise ValueError(f"{option}: expected one of {known}; got {value!r}")
    if value in (LEFT, RIGHT):
        return frozenset((value,))
    return frozenset((LEFT, RIGHT)) if value == modes[1] else frozenset()


@dataclass(frozen=True, slots=True)
class MatchOptions:
    """The options of one match, checked (text values turned into their kinds).

    Attributes:
        left: The left team's kind.
        right: The right team's kind.
        net: Layer 1's net, for a layered team.
        tree: Layer 2's pass tree, for a layered team.
        players: Players per side (0: 11 on an open field, 5 on a walled one).
        half_time_s: One half [s].
        transfer: Accept a net or tree trained on another field model or preset.
        steady_turns: The minds reckon their turns into the heading between landmark fixes and
            do not turn back within a short hold (:attr:`~robotsoccer.skills.team_setup.TeamSetup.
            steady_turns`); False (default): the 1996 client's turning. True whenever `look` is
            ``neck``, which has the steady turns' rules besides.
        look: How the minds look (:data:`~robotsoccer.skills.team_setup.LOOK_MODES`):
            ``body`` (default, the paper's client) or ``neck``: with the neck and view modes
            (:mod:`robotsoccer.skills.team_look`).
        dead_band: The minds drive on a small heading error, slow to stop at home and hold a
            turn back for a second (:attr:`~robotsoccer.skills.team_setup.TeamSetup.
            dead_band`; issue 28 item 5, the robots' dithering): True for both teams,
            ``left`` or ``right`` for one (to measure what it costs); False (default): as
            before (:func:`dead_band_teams`).
        turn_latency: How the minds treat a percept that does not show their last turn yet
            (:attr:`~robotsoccer.skills.team_setup.TeamSetup.turn_latency`), the motion
            skill's two settings: ``hold`` (default) or ``reckon`` for both teams, or ``left``
            or ``right``: that team reckons, the other holds (to measure what it costs).
        client: How often the minds act on the Soccer Server (issue 28 item 3): ``see``
            (default, the paper's client: one decision per see) or ``cycle`` (a command every
            cycle from a world model, :mod:`robotsoccer.skills.team_cycle`) for both teams, or
            ``left`` or ``right``: that team acts every cycle, the other on sees (to measure
            what it is worth). The robots refuse ``cycle`` (their host already acts every tick).
        receiver_half: What a layered passer tells layer 2's tree of the receiver's half
            (:data:`~robotsoccer.skills.team_setup.RECEIVER_HALVES`): ``unknown`` (default, as
            before: open play has no ``say`` report) or ``estimated`` from the passer's own view
            (:func:`learning.pass_features.estimated_receiver_half`; issue 28 goal 4).
        tpot: Layer 3's table (:func:`learning.tpot.save_table`), for a ``layer3`` team.
        explore: Layer 3's exploration rate epsilon in [0, 1].
        learn: Layer 3 records its rewards: the drill's ``data`` returns them
            (:func:`~robotsoccer.drills.match.layer3_experiences` reads them back).
        tpot_every: Layer 3 decides on every spell on the ball (shoot and keep included),
            not only where the layered team would ask the tree.
        tpot_success: Layer 3's SUCCESS cut on the tree's confidence, in [0, 1].
        tpot_window: When layer 3's rewards close (:data:`learning.tpot.REWARD_WINDOWS`):
            ``choice`` (also at the player's next choice) or ``horizon`` (only at the horizon,
            a goal, play stopping or full time).
        tpot_guard: Layer 3's shot-range guard (needs ``tpot_every``): the goal destination is
            a shot only within the teams' shooting range.
        tpot_loss: Layer 3's loss penalty in [0, 1] (0: the ball's advance alone).
        tpot_tree: Layer 3's own pass tree, for its features e(s, a) alone (empty: the team's
            `tree`). The team's other play keeps `tree`. On ``soccer_server_1996`` the full
            tree, asked with the receiver's half unknown as in open play, answers one constant
            confidence; §6's passer-only tree tells passes apart there (issue 24).
        net_domain: Where a layered team asks its turn-angle net (:data:`NET_DOMAINS`):
            ``any`` (default: every ball coming at its chaser within the trigger distance) or
            ``trained``: only inside the net's training domain, straight elsewhere
            (:class:`~robotsoccer.skills.turn_policies.TrainedDomainPolicy`). A lead net has its
            own domain rule and ignores it.

    Raises:
        ValueError: An unknown team kind, a layered team without its model files, a layer3
            team without its table, an unknown team size, a half <= 0, an unknown look, turn
            latency, client or receiver half, or a layer-3 option out of its range.
    """

    left: TeamKind = TeamKind.LAYERED
    right: TeamKind = TeamKind.BASELINE
    net: str = ""
    tree: str = ""
    players: int = 0
    half_time_s: float = HALF_TIME_S
    transfer: bool = False
    steady_turns: bool = False
    look: str = "body"
    dead_band: bool | str = False
    turn_latency: str = "hold"
    client: str = "see"
    receiver_half: str = "unknown"
    tpot: str = ""
    explore: float = 0.0
    learn: bool = False
    tpot_every: bool = False
    tpot_success: float = PASS_THRESHOLD
    tpot_window: str = WINDOW_CHOICE
    tpot_guard: bool = False
    tpot_loss: float = 0.0
    tpot_tree: str = ""
    net_domain: str = "any"

    def __post_init__(self) -> None:
        # The checks run in this order so that, of several bad options, the same one is named
        # first whatever way the drill was built (the order the drill always checked them in).
        if self.look not in LOOK_MODES:
            raise ValueError(f"look: expected one of {', '.join(LOOK_MODES)}; got {self.look!r}")
        self._set("steady_turns", flag("steady_turns", self.steady_turns) or self.look == "neck")
        dead_band_teams(self.dead_band)
        one_team(self.turn_latency, "turn_latency", TURN_LATENCIES)
        one_team(self.client, "client", CLIENT_MODES)
        check_receiver_half(self.receiver_half)
        self._set("left", choice(TeamKind, self.left, "left"))
        self._set("right", choice(TeamKind, self.right, "right"))
        if self.layered() and not (self.net and self.tree):
            raise ValueError("a layered team needs a net and a tree (options net=... tree=...)")
        if self.has(TeamKind.LAYER3) and not self.tpot:
            raise ValueError("a layer3 team needs its table (option tpot=...)")
        self._check_layer3()
        size = int(self.players)
        if size not in (0, *FORMATIONS):
            known = ", ".join(str(n) for n in FORMATIONS)
            raise ValueError(f"players must be 0 (the field's default) or one of {known}")
        self._set("players", size)
        self._set("half_time_s", duration("half_time_s", self.half_time_s))
        self._set("transfer", flag("transfer", self.transfer))
        if self.net_domain not in NET_DOMAINS:
            known = ", ".join(NET_DOMAINS)
            raise ValueError(f"net_domain: expected one of {known}; got {self.net_domain!r}")

    def _set(self, name: str, value: object) -> None:
        """Store a checked value (the record is frozen once built)."""
        object.__setattr__(self, name, value)

    def _check_layer3(self) -> None:
        """Layer 3's options: the exploration rate, the flags, the cut, window and penalty."""
        self._set("explore", bounded("explore", _number("explore", self.explore), 0.0, 1.0))
        self._set("learn", flag("learn", self.learn))
        self._set("tpot_every", flag("tpot_every", self.tpot_every))
        success = bounded("tpot_success", _number("tpot_success", self.tpot_success), 0.0, 1.0)
        self._set("tpot_success", success)
        if self.tpot_window not in REWARD_WINDOWS:
            known = ", ".join(REWARD_WINDOWS)
            raise ValueError(f"tpot_window must be one of {known}, got {self.tpot_window!r}")
        self._set("tpot_guard", flag("tpot_guard", self.tpot_guard))
        if self.tpot_guard and not self.tpot_every:
            raise ValueError("tpot_guard needs tpot_every (the goal is a shot only then)")
        self._set("tpot_loss", bounded("tpot_loss", _number("tpot_loss", self.tpot_loss), 0.0, 1.0))

    def has(self, kind: TeamKind) -> bool:
        """Either team is of this kind."""
        return kind in (self.left, self.right)

    def layered(self) -> bool:
        """Either team plays the learned layers (``layered`` or ``layer3``)."""
        return self.has(TeamKind.LAYERED) or self.has(TeamKind.LAYER3)

    def dead_band_teams(self) -> frozenset[str]:
        """The teams whose minds use the dead band (:func:`dead_band_teams`)."""
        return dead_band_teams(self.dead_band)

    def reckoning_teams(self) -> frozenset[str]:
        """The teams whose minds reckon their turns in flight (``turn_latency``)."""
        return one_team(self.turn_latency, "turn_latency", TURN_LATENCIES)

    def cycle_teams(self) -> frozenset[str]:
        """The teams whose minds act every cycle (``client``)."""
        return one_team(self.client, "client", CLIENT_MODES)

    def tpot_settings(self) -> TpotSettings:
        """Layer 3's settings for a ``layer3`` team of this match."""
        return TpotSettings(
            threshold=self.tpot_success,
            epsilon=self.explore,
            learn=self.learn,
            every_ball=self.tpot_every,
            window=self.tpot_window,
            shot_guard=self.tpot_guard,
            loss_penalty=self.tpot_loss,
        )


def _number(option: str, value: object) -> float:
    """An option's number; text too (a run spec's), refused in one line when it is not one."""
    try:
        return float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{option} must be a number, got {value!r}") from None
