"""A whole match: two teams, a referee, two halves; labels by who won.

**Teams** (:mod:`robotsoccer.skills.team`): ``layered`` — the learned layers: interception
with layer 1's net, passes chosen by layer 2's tree; ``baseline`` — no learned layer: it runs
straight at the ball and passes to the closest teammate. Both localise from landmarks, send
their nearest player to the ball, dribble, shoot and keep a formation; they differ only in the
two learned decisions, so a series measures what the layers are worth in play. Where the
players push the ball (no aimable kick: the robots) both teams play it from behind and meet a
ball rolling at their end as layer 1's goal-mouth drill does, the layered team with its lead
net, the baseline straight (:mod:`robotsoccer.skills.team`, "Pushing"). ``layer3`` — the
layered team whose ball holder, where the layered team would ask the tree, asks TPOT-RL's
table instead (:mod:`robotsoccer.skills.layer3`, option ``tpot``: the table file; ``explore``:
its exploration rate; ``learn``: record its rewards as the trial's data, for training;
``tpot_every``: it decides on every spell on the ball, shot and dribble included, TPOT-RL's own
rule; ``tpot_success``: the tree's least confidence for e = SUCCESS; ``tpot_window``: when its
rewards close, ``choice`` or ``horizon``; ``tpot_guard``: the goal is a shot only within the
teams' shooting range; ``tpot_loss``: the penalty of a ball the opponents gain, which also
closes a reward: the coach relays each new opponent touch).

**Size.** ``players`` per side: by default 11 on an open field (the Soccer Server) and 5 on a
walled table (the robots). Formation homes are in units
(:data:`~robotsoccer.drills.match_setup.FORMATIONS`, ours: 4-4-2 and 1-2-2; 1-1-1 and 1-1 for
small-sided games), mirrored for the right team.

**Referee** (:mod:`robotsoccer.drills.referee`): the Soccer Server's play modes on an open
field, the table's restart rules on a walled one. The match lasts two halves of
``half_time_s`` (default :data:`~robotsoccer.drills.match_options.HALF_TIME_S`, rcssserver's
``half_time``).

**Options**: one typed record, :class:`~robotsoccer.drills.match_options.MatchOptions`.

**Labels** ``LEFT_WIN``, ``DRAW``, ``RIGHT_WIN``. **Measures**: goals, possession share
(ticks in which the team touched the ball last), passes completed (the ball goes from one
player to a teammate: the coach's touch rule), shots (kicks its players meant as shots, one
per spell on the ball), kicks its players tried at all, per side.
"""

from __future__ import annotations

from dataclasses import replace
from functools import partial
from typing import Any

from field_models.arena import Arena, ArenaEvent, CountsCommands, FieldFacts
from field_models.protocol import LEFT, RIGHT, Mind, PlayerRef
from field_models.seeding import TrialRngs
from learning.tpot import Experience, load_table
from robotsoccer.drills.base import Verdict
from robotsoccer.drills.layered import (
    CYCLE_ON_ROBOTS,
    LayeredDrill,
    control_reach,
    load_evaluator,
)
from robotsoccer.drills.match_options import MatchOptions, TeamKind
from robotsoccer.drills.match_setup import FORMATIONS, GOALIE, kickoff_spots, team_setup
from robotsoccer.drills.referee import PLAY_ON, SIDE, Referee
from robotsoccer.replay.frames import GameFrame
from robotsoccer.skills.intercept import (
    Behaviour,
    load_net_function,
    make_policy,
    model_decision,
    trained_domain,
    transfer_distance_factor,
)
from robotsoccer.skills.layer3 import TpotBallPolicy
from robotsoccer.skills.passing import Chooser, PassEvaluator
from robotsoccer.skills.team import TeamMind
from robotsoccer.skills.team_cycle import CycleTeamMind
from robotsoccer.skills.team_setup import TeamSetup

EXPERIENCE_FIELDS = 5
"""Numbers per layer-3 experience in a match's data: side (0 left), number, e, a, reward."""


class MatchDrill(LayeredDrill):
    """A match (module docstring).

    Built from a :class:`~robotsoccer.drills.match_options.MatchOptions` record, or from its
    fields as keywords (the registry's ``make_drill`` and a command line's ``--option
    NAME=VALUE`` give them so); :data:`OPTIONS` names the record, whose fields are the drill's
    option names.

    Args:
        options: The match's options; None: built from `keywords`.
        **keywords: The options' fields by name, where `options` is not given.

    Raises:
        ValueError: A bad option (:class:`~robotsoccer.drills.match_options.MatchOptions`), or
            both a record and keywords.
    """

    name: str = "match"
    labels: tuple[str, ...] = ("LEFT_WIN", "DRAW", "RIGHT_WIN")
    OPTIONS = MatchOptions

    def __init__(self, options: MatchOptions | None = None, /, **keywords: Any) -> None:
        if options is not None and keywords:
            raise ValueError("give the match drill an options record or keywords, not both")
        self.options = o = options if options is not None else MatchOptions(**keywords)
        self.look, self.steady_turns = o.look, o.steady_turns
        self.dead_band = o.dead_band_teams()
        self.kinds = {LEFT: o.left, RIGHT: o.right}
        layered = o.layered()
        self.tpot = o.tpot if o.has(TeamKind.LAYER3) else ""
        self.tpot_tree = o.tpot_tree if self.tpot else ""
        self.learn = o.learn  # layer 3's other options reach it as o.tpot_settings()
        self.policies: dict[str, TpotBallPolicy] = {}
        self._tick = 0
        self.net = o.net if layered else ""
        self.model = o.tree if layered else ""
        self.chooser = Chooser.TREE
        self.size = o.players
        self.half_time_s = o.half_time_s
        self.max_time_s = 2.0 * o.half_time_s
        self.transfer = o.transfer
        self._checked: FieldFacts | None = None
        self.referee: Referee | None = None
        self.minds_by_ref: dict[PlayerRef, TeamMind] = {}
        self._possession = {LEFT: 0, RIGHT: 0}
        self._passes = {LEFT: 0, RIGHT: 0}
        self._events: list[ArenaEvent] = []

    # ------------------------------------------------------------------ who plays

    def team_size(self, facts: FieldFacts | None = None) -> int:
        """Players per side on this field."""
        if self.size:
            return self.size
        return 5 if facts is not None and facts.walled else 11

    def players(self) -> tuple[PlayerRef, ...]:
        """Both teams, left first, at the size asked for (11 a side when the field decides)."""
        return self.players_for(None)

    def players_for(self, facts: FieldFacts | None) -> tuple[PlayerRef, ...]:
        """Both teams, left first, on this field (the runner asks this when it exists)."""
        n = self.team_size(facts)
        return tuple(PlayerRef(t, i) for t in (LEFT, RIGHT) for i in range(1, n + 1))

    def field_settings(self, facts: FieldFacts) -> dict[str, float]:
        """Percepts with every landmark: the players localise themselves."""
        return {"all_landmarks": True}

    def inputs(self) -> tuple[str, ...]:
        """The net and tree files (and layer 3's table and its own tree)."""
        return tuple(f for f in (self.model, self.net, self.tpot, self.tpot_tree) if f)

    # ------------------------------------------------------------------ kick-off

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Kick-off spots and the referee; the left team kicks off."""
        facts = arena.facts
        self._check_origins(facts)
        n = len(arena.players) // 2
        if n not in FORMATIONS:
            raise ValueError(f"no formation for {n} players a side")
        rng = rngs["placement"]
        jitter = {
            ref: (float(rng.uniform(-1.0, 1.0)), float(rng.uniform(-1.0, 1.0)))
            for ref in arena.players
        }
        spots = {team: kickoff_spots(facts, n, team, jitter) for team in (LEFT, RIGHT)}
        ticks = round(self.half_time_s / facts.dt_s)
        if ticks < 1:  # a half of no tick would end the match before its kick-off
            raise ValueError(
                f"half_time_s must be at least one tick ({facts.dt_s:g} s), "
                f"got {self.half_time_s!r}"
            )
        self.referee = Referee(arena, spots, ticks, control_reach(facts))
        self.referee.start(arena)

    # ------------------------------------------------------------------ minds

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """Every player's :class:`~robotsoccer.skills.team.TeamMind`."""
        facts = arena.facts
        n = len(arena.players) // 2
        tree: PassEvaluator | None = load_evaluator(self.model)[0] if self.model else None
        factor = 1.0
        if self.transfer and self.net:
            factor = transfer_distance_factor(self.net, facts)
        minds: dict[PlayerRef, Mind] = {}
        features = load_evaluator(self.tpot_tree)[0] if self.tpot_tree else tree
        for team in (LEFT, RIGHT):
            setup = self.team_setup(facts, n, team)
            layered = self.kinds[team] in (TeamKind.LAYERED, TeamKind.LAYER3)
            ball_policy = None
            if self.kinds[team] is TeamKind.LAYER3 and features is not None:
                ball_policy = self._layer3_policy(setup, features, rngs)
                self.policies[team] = ball_policy
            policy, lead = None, None
            if layered and model_decision(self.net) == "lead":
                lead = load_net_function(self.net, factor)
            elif layered:
                policy = make_policy(Behaviour.NET, rngs["policy"], self.net, factor)
                if policy is not None and self.options.net_domain == "trained":
                    policy = trained_domain(policy, self.net, factor)
            per_cycle = team in self.options.cycle_teams()
            if per_cycle and setup.sees_all_round:
                raise ValueError(CYCLE_ON_ROBOTS)
            make = partial(CycleTeamMind, facts=facts) if per_cycle else TeamMind
            for number in FORMATIONS[n]:
                mind = make(
                    number,
                    setup,
                    interception=policy,
                    lead=lead,
                    evaluator=tree if layered else None,
                    ball_policy=ball_policy,
                )
                self.minds_by_ref[PlayerRef(team, number)] = mind
                minds[PlayerRef(team, number)] = mind
        return minds

    def _layer3_policy(
        self, setup: TeamSetup, tree: PassEvaluator, rngs: TrialRngs
    ) -> TpotBallPolicy:
        """One team's layer 3 (its own copy of the table: a game never changes the file)."""
        table = load_table(self.tpot)
        n = len(FORMATIONS[len(setup.home)])
        if table.positions != n:
            raise ValueError(f"{self.tpot}: a table for {table.positions} positions, not {n}")
        settings = self.options.tpot_settings()
        return TpotBallPolicy(table, setup, tree, rngs["policy"], settings)

    def team_setup(self, facts: FieldFacts, n: int, team: str) -> TeamSetup:
        """One team's plan on this field (module docstring)."""
        plan = self.plan(facts)
        dead_band = team in self.dead_band
        latency = "reckon" if team in self.options.reckoning_teams() else "hold"
        return replace(
            team_setup(facts, plan, n, team),
            steady_turns=self.steady_turns,
            look=self.look,
            dead_band=dead_band,
            turn_latency=latency,
            receiver_half=self.options.receiver_half,
        )

    # ------------------------------------------------------------------ the coach

    def judge(self, arena: Arena) -> Verdict | None:
        """The referee's tick, and the coach's count of possession and passes."""
        referee = self.referee
        if referee is None:
            raise RuntimeError("judge() before setup()")
        before = referee.last_touch
        score = referee.score
        mode = referee.play_mode
        referee.step(arena)
        self._tick = arena.tick
        if self.policies and referee.score != score:
            # The referee's goal call, which rcssserver sends every client (layer 3's rewards).
            scorer = LEFT if referee.score[0] > score[0] else RIGHT
            for team, ball_policy in self.policies.items():
                ball_policy.goal(team == scorer, arena.tick)
        if self.policies and mode == PLAY_ON and referee.play_mode != PLAY_ON:
            # Any other stop (a restart's call, heard by every client) closes the horizon
            # window's rewards; the choice window ignores it (TpotBallPolicy.stopped).
            for ball_policy in self.policies.values():
                ball_policy.stopped(arena.tick)
        holder = referee.last_touch
        if self.policies and holder is not None and holder != before:
            # A new touch (the possession count's rule): the other team lost the ball, which
            # closes its layer 3's rewards when they value possession (TpotBallPolicy.lost).
            for team, ball_policy in self.policies.items():
                if team != holder.team:
                    ball_policy.lost(arena.tick)
        if holder is not None:
            self._possession[holder.team] += 1
            if before is not None and holder != before and holder.team == before.team:
                self._passes[holder.team] += 1
                self._events.append(
                    ArenaEvent(arena.tick, "decision", f"pass {before} -> {holder}", holder)
                )
        return None

    def timeout(self, arena: Arena) -> Verdict:
        """Full time: who won, and the score."""
        referee = self.referee
        assert referee is not None
        left, right = referee.score
        label = "LEFT_WIN" if left > right else "RIGHT_WIN" if right > left else "DRAW"
        names = self.team_names()
        return Verdict(label, f"{names[0]} {left}-{right} {names[1]}")

    def data(self) -> tuple[float, ...]:
        """Layer 3's experiences when learning (:func:`layer3_experiences`), else nothing."""
        if not self.learn:
            return ()
        out: list[float] = []
        for team in (LEFT, RIGHT):
            ball_policy = self.policies.get(team)
            if ball_policy is None:
                continue
            ball_policy.finish(self._tick)
            for e in ball_policy.experiences:
                out += [float(team == RIGHT), e.number, e.feature, e.action, e.reward]
        return tuple(out)

    def measures(self) -> dict[str, float]:
        """Goals, possession share, passes, shots and kicks tried, per side."""
        referee = self.referee
        if referee is None:
            return {}
        touched = sum(self._possession.values())
        out: dict[str, float] = {}
        for i, team in enumerate((LEFT, RIGHT)):
            side = SIDE[team]
            minds = [m for r, m in self.minds_by_ref.items() if r.team == team]
            out[f"goals_{side}"] = float(referee.score[i])
            out[f"possession_{side}"] = self._possession[team] / touched if touched else 0.5
            out[f"passes_{side}"] = float(self._passes[team])
            out[f"shots_{side}"] = float(sum(m.shots for m in minds))
            out[f"pass_kicks_{side}"] = float(sum(m.passes for m in minds))
        return out

    # ------------------------------------------------------------------ recordings

    def game_frame(self, arena: Arena) -> GameFrame:
        """This tick as a match recording keeps it (with the commands where the field counts)."""
        referee = self.referee
        assert referee is not None
        score = (referee.score[0], referee.score[1])
        commands = arena.command_tally() if isinstance(arena, CountsCommands) else None
        return GameFrame(arena.truth(), referee.play_mode, score, commands)

    def drain_events(self) -> list[ArenaEvent]:
        """Referee calls and completed passes since the last call."""
        referee = self.referee
        events = (referee.drain() if referee is not None else []) + self._events
        self._events = []
        events.sort(key=lambda e: e.tick)
        return events

    def team_names(self) -> tuple[str, str]:
        """The teams' names as recordings, game logs and results show them.

        A team's kind, and its side too when both teams are of one kind (``baseline (left)``
        and ``baseline (right)``): a legend or a score line that names one team twice does not
        say who scored.
        """
        left, right = self.kinds[LEFT].value, self.kinds[RIGHT].value
        if left == right:
            return (f"{left} (left)", f"{right} (right)")
        return (left, right)

    def goalies(self) -> tuple[PlayerRef, ...]:
        """Each team's goalkeeper (:data:`~robotsoccer.drills.match_setup.GOALIE`), left, right."""
        return (PlayerRef(LEFT, GOALIE), PlayerRef(RIGHT, GOALIE))


def layer3_experiences(data: tuple[float, ...]) -> list[tuple[str, Experience]]:
    """(team, experience) pairs from a learning match's :meth:`MatchDrill.data`, in order."""
    if len(data) % EXPERIENCE_FIELDS:
        raise ValueError(f"layer-3 data come in fives, got {len(data)} numbers")
    out = []
    for i in range(0, len(data), EXPERIENCE_FIELDS):
        side, number, feature, action, r = data[i : i + EXPERIENCE_FIELDS]
        team = RIGHT if side else LEFT
        out.append((team, Experience(int(number), int(feature), int(action), float(r))))
    return out
