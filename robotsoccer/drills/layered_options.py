"""The options of the drills on both learned layers, one typed record per drill.

:class:`PassOptions` for the pass drill (:mod:`robotsoccer.drills.passing`) and
:class:`SetPlayOptions` for the set play (:mod:`robotsoccer.drills.setplay`). As with the
interception drill's :class:`~robotsoccer.drills.intercept_options.InterceptOptions`, a drill is
built from its options by keyword (``make_drill("pass", {...})``, a command line's ``--option
NAME=VALUE``) or from a record (``PassDrill(PassOptions(...))``). Text values are turned into
their kinds here, once, and every option is checked here, in the order the drills checked them
when they took keywords, so that of several bad options the same one is named first. What each
option does is told in the drill's module.
"""

from __future__ import annotations

from dataclasses import dataclass

from robotsoccer.drills.intercept_options import ClientKind
from robotsoccer.options import choice, duration, flag
from robotsoccer.skills.intercept import Behaviour, check_behaviour, model_decision
from robotsoccer.skills.passing import Chooser
from robotsoccer.skills.team_setup import LOOK_MODES

PASS_DEFENDERS = ("intercept", "still")
"""The pass drill's defender modes (:class:`PassOptions`, ``defenders``)."""

RECEIVER_HALF = ("use", "ignore")
"""What the passer does with the receivers' reported half (:class:`PassOptions`)."""


def _needs_model(chooser: Chooser, model: str) -> None:
    """Refuse a tree or boosted-trees chooser without its model file."""
    if chooser in (Chooser.TREE, Chooser.BOOST) and not model:
        raise ValueError(f"chooser {chooser.value!r} needs a model file (option model=...)")


def _client(client: ClientKind | str, net: str) -> ClientKind:
    """The client checked: a known one, and no lead net on the per-cycle client."""
    kind = choice(ClientKind, client, "client")
    if kind is ClientKind.CYCLE and net and model_decision(net) == "lead":
        raise ValueError("client 'cycle' plays the turn decision: give a TA net or client=see")
    return kind


@dataclass(frozen=True, slots=True)
class PassOptions:
    """The options of one pass drill, checked (text values turned into their kinds).

    Attributes:
        chooser: How the passer picks (``random``, ``tree``, ``boost``, ``closest``,
            ``analytic``).
        model: The tree or boosted-trees file (JSON) for ``tree`` / ``boost``.
        interceptor: Layer 1's behaviour for receivers and defenders (``net``, ``straight``,
            ...).
        net: The interception net (or lookup) file for ``net``/``lookup``.
        defenders: ``intercept`` (default) or ``still`` (Table 2's "no defenders" test).
        max_time_s: Simulated time after which the trial is a MISS [s].
        transfer: Accept a tree or net trained on another field model or preset.
        receiver_half: ``use`` (default) the receivers' reported half of the attributes, or
            ``ignore`` it (unknown), to measure what the reports add.
        client: The receivers' and defenders' layer 1: ``see`` (the paper's client) or
            ``cycle`` (the per-cycle client; :mod:`robotsoccer.drills.passing`'s module
            docstring, "Client").

    Raises:
        ValueError: An unknown chooser, interceptor, defenders mode or client, a missing model
            file name, a time limit that is not positive, a lead net with ``client=cycle``; at
            set-up, ``client=cycle`` on the robots.
    """

    chooser: Chooser = Chooser.RANDOM
    model: str = ""
    interceptor: Behaviour = Behaviour.STRAIGHT
    net: str = ""
    defenders: str = "intercept"
    max_time_s: float = 12.0
    transfer: bool = False
    receiver_half: str = "use"
    client: ClientKind = ClientKind.SEE

    def __post_init__(self) -> None:
        chooser = choice(Chooser, self.chooser, "chooser")
        _needs_model(chooser, self.model)
        self._set("chooser", chooser)
        self._set("interceptor", check_behaviour(self.interceptor, self.net))
        if self.defenders not in PASS_DEFENDERS:
            raise ValueError(f"unknown defenders {self.defenders!r} (known: intercept, still)")
        self._set("max_time_s", duration("max_time_s", self.max_time_s))
        self._set("transfer", flag("transfer", self.transfer))
        if self.receiver_half not in RECEIVER_HALF:
            raise ValueError(f"unknown receiver_half {self.receiver_half!r} (known: use, ignore)")
        self._set("client", _client(self.client, self.net))

    def _set(self, name: str, value: object) -> None:
        """Store a checked value (the record is frozen once built)."""
        object.__setattr__(self, name, value)


@dataclass(frozen=True, slots=True)
class SetPlayOptions:
    """The options of one set play, checked (text values turned into their kinds).

    Attributes:
        chooser: How the passers pick (``tree``, ``random``, ``closest``, ``analytic``).
        model: The pass tree file for ``tree``.
        interceptor: Layer 1's behaviour for receivers, winger and defenders.
        net: The interception net for ``net``.
        max_time_s: The play's time limit [s]; None: 40 arrival times of layer 1's drill.
        transfer: Accept a tree or net trained on another field model or preset.
        pass_speed_mps: The passes' speed [m/s]; None: the field's
            (:func:`~robotsoccer.drills.setplay_kicks.kick_powers`).
        defenders: The defenders' and goalie's interception: ``same`` as the attackers'
            `interceptor` (the paper's set play, §7), or a behaviour of their own
            (``straight``: the field's baseline defenders, whatever the attackers use).
        client: ``see`` (the paper's client) or ``cycle`` (the per-cycle client;
            :mod:`robotsoccer.drills.setplay`'s module docstring, "Client").
        look: How the attackers look: ``body`` (the paper's client, no neck) or ``neck``
            (:mod:`robotsoccer.drills.setplay`'s module docstring, "Looking").

    Raises:
        ValueError: An unknown chooser, interceptor, client or look, a missing model file, a
            limit <= 0, a lead net with ``client=cycle``; at set-up, ``client=cycle`` on the
            robots.
    """

    chooser: Chooser = Chooser.CLOSEST
    model: str = ""
    interceptor: Behaviour = Behaviour.STRAIGHT
    net: str = ""
    max_time_s: float | None = None
    transfer: bool = False
    pass_speed_mps: float | None = None
    defenders: Behaviour | str = "same"
    client: ClientKind = ClientKind.SEE
    look: str = "body"

    def __post_init__(self) -> None:
        chooser = choice(Chooser, self.chooser, "chooser")
        _needs_model(chooser, self.model)
        self._set("chooser", chooser)
        self._set("interceptor", check_behaviour(self.interceptor, self.net))
        if self.max_time_s is not None:
            self._set("max_time_s", duration("max_time_s", self.max_time_s))
        self._set("transfer", flag("transfer", self.transfer))
        if self.pass_speed_mps is not None:
            self._set("pass_speed_mps", float(self.pass_speed_mps))
        if self.defenders != "same":
            self._set("defenders", check_behaviour(self.defenders, self.net))
        self._set("client", _client(self.client, self.net))
        if self.look not in LOOK_MODES:
            raise ValueError(f"unknown look {self.look!r} (known: {', '.join(LOOK_MODES)})")

    def _set(self, name: str, value: object) -> None:
        """Store a checked value (the record is frozen once built)."""
        object.__setattr__(self, name, value)


__all__ = ["PASS_DEFENDERS", "RECEIVER_HALF", "PassOptions", "SetPlayOptions"]
