"""Issue 28 item 5 on the robots: do new camera frames replace commands not yet carried out?

Runs robot trials through the trial runner's own loop and reads counters that change nothing
(the host's, the link's and the firmware's, plus
:class:`~robotsoccer.skills.reversals.TurnReversals` on each thinking robot's true heading
every 100 ms, the Soccer Server's cycle):

* **host dropped**: body actions of a decision still waiting (not sent) when the robot's next
  decision replaced them -- on the Soccer Server this is the "lost dash" (a turn, then a dash a
  cycle later, replaced by the next see); ``dashes`` counts the Dash actions among them;
* **link superseded**: commands replaced in the link's queue by a newer one to the same robot
  before their packet left;
* **firmware cut short**: drive commands with a duration (TURN, ARC, a dash's FORWARD hold)
  replaced by a newer one before the duration ended; ``turns`` counts the TURN/ARC among them
  (a turn not turned in full). A dash's FORWARD is held for two camera periods by design so that
  the next frame's command replaces it (host docstring): its cuts are expected, not lost work;
* **stale**: commands the firmware dropped as older than the newest it ran;
* **reversals**: turns of more than 10° the other way from the robot's last such turn.

Rates are per robot-minute of thinking robots; shares of the commands the host sent come with
n and a 95% Wilson interval. Nothing here changes a result: the same trials give the same rows.

The match rows come with the team minds' default turning, ``steady_turns`` and ``dead_band``
(the fix of issue 28 item 5, :attr:`~robotsoccer.skills.team_setup.TeamSetup.dead_band`);
``--series N`` adds what the dead band costs: N baseline games of a dead-band team against a
default one per preset, the dead band left in the first half of the games and right in the
rest (seeds 0 ..), with its goal difference and possession share per game (95% intervals).

    python scripts/robot_supersession.py --trials 200 --half-time 30 --out runs/robot-supersession
    python scripts/robot_supersession.py --trials 0 --games 4 --series 40 --out runs/dead-band
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from field_models.protocol import Percept
from robotsoccer.cli.options import LEAD_DRILLS
from robotsoccer.experiments.match import mean_interval
from robotsoccer.runs.runner import DrillOption, TrialLoop, TrialSpec, build_trial
from robotsoccer.skills.reversals import TurnReversals
from robotsoccer.stats import wilson_interval

PRESETS = ("small_size_1997", "small_size_1997_arc")
"""The robot presets measured: the paper's spin-then-drive primitives and the arc."""

SAMPLE_S = 0.1
"""Heading sample period for the reversal count [s]: the Soccer Server's cycle."""


@dataclass
class Counts:
    """Summed counters of some trials."""

    robot_minutes: float = 0.0
    sent: int = 0
    host_dropped: int = 0
    host_dropped_dashes: int = 0
    link_superseded: int = 0
    cut_short: int = 0
    cut_turns: int = 0
    stale: int = 0
    reversals: int = 0

    def add(self, other: Counts) -> None:
        """Add `other`'s counts to these."""
        for f in fields(self):
            setattr(self, f.name, getattr(self, f.name) + getattr(other, f.name))


def instrument(spec: TrialSpec, index: int) -> tuple[str, Counts, dict[str, float]]:
    """Run trial `index` of `spec` as the runner does; its label, counters and measures."""
    rngs, drill, arena = build_trial(spec, index)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    thinking = list(minds)
    host = arena.host  # type: ignore[attr-defined]
    every = max(1, round(SAMPLE_S / arena.facts.dt_s))
    reversals = TurnReversals()
    for ref in thinking:
        reversals.sample(ref, arena.player_state(ref).heading)

    def observe(a: object, percepts: list[Percept]) -> None:
        if arena.tick % every == 0:
            for ref in thinking:
                reversals.sample(ref, arena.player_state(ref).heading)

    verdict = TrialLoop(arena, drill, minds, observe).run()
    link = arena.link  # type: ignore[attr-defined]
    firmware = arena.firmware  # type: ignore[attr-defined]
    counts = Counts(
        robot_minutes=len(thinking) * arena.tick * arena.facts.dt_s / 60.0,
        sent=host._seq,
        host_dropped=host.dropped,
        host_dropped_dashes=host.dropped_dashes,
        link_superseded=link.superseded,
        cut_short=sum(fw.cut_short for fw in firmware),
        cut_turns=sum(fw.cut_turns for fw in firmware),
        stale=sum(fw.stale for fw in firmware),
        reversals=reversals.count,
    )
    return ("" if verdict is None else verdict.label), counts, drill.measures()


def measure(spec: TrialSpec, trials: int) -> tuple[Counts, dict[str, int], float]:
    """Counters summed over trials 0 .. `trials` - 1, the labels' tally, and the wall time [s]."""
    total, labels = Counts(), dict[str, int]()
    start = time.perf_counter()
    for index in range(trials):
        label, counts, _ = instrument(spec, index)
        total.add(counts)
        labels[label] = labels.get(label, 0) + 1
    return total, labels, time.perf_counter() - start


def row(name: str, c: Counts, labels: dict[str, int]) -> str:
    """One table row: rates per robot-minute, shares with intervals, a drill's saves."""

    def rate(x: int) -> str:
        return f"{x / c.robot_minutes:.2f}" if c.robot_minutes else "-"

    def share(x: int) -> str:
        lo, hi = wilson_interval(x, c.sent)
        return f"{100 * x / max(c.sent, 1):.1f} [{100 * lo:.1f}, {100 * hi:.1f}]"

    return (
        f"| {name} | {c.robot_minutes:.2f} | {c.sent} | {rate(c.host_dropped)} "
        f"({rate(c.host_dropped_dashes)} dashes) | {rate(c.link_superseded)} | "
        f"{rate(c.cut_turns)} | {share(c.cut_turns)} | {rate(c.cut_short - c.cut_turns)} | "
        f"{rate(c.stale)} | {rate(c.reversals)} | {saves(labels)} |"
    )


def saves(labels: dict[str, int]) -> str:
    """An interception drill's saves, % with n and a 95% Wilson interval; '-' for matches."""
    if "SAVE" not in labels and "GOAL" not in labels:
        return "-"
    n = sum(labels.values())
    lo, hi = wilson_interval(labels.get("SAVE", 0), n)
    return f"{100 * labels.get('SAVE', 0) / n:.1f} [{100 * lo:.1f}, {100 * hi:.1f}] (n={n})"


HEADER = (
    "| run | robot-min | commands sent | host dropped /robot-min | link superseded /robot-min "
    "| turns cut short /robot-min | turns cut short, % of sent [95%] | holds cut short "
    "/robot-min | stale /robot-min | reversals /robot-min | saves % [95%] |\n|" + "---|" * 11
)


def series(preset: str, games: int, half_time_s: float) -> tuple[str, dict[str, object]]:
    """`games` baseline games, a dead-band team against a default one (module docstring).

    Returns a markdown row (the dead-band team's goal difference, goals each and possession
    share per game with 95% intervals, and the robots' reversals per robot-minute) and its data.
    """
    differences, banded, default, possession = [], [], [], []
    total = Counts()
    for index in range(games):
        side = "left" if index < (games + 1) // 2 else "right"
        options: tuple[tuple[str, DrillOption], ...] = (
            ("left", "baseline"),
            ("right", "baseline"),
            ("half_time_s", half_time_s),
            ("dead_band", side),
        )
        spec = TrialSpec("match", "robot_physics", preset, drill_options=options)
        _, counts, measures = instrument(spec, index)
        total.add(counts)
        mine, theirs = ("l", "r") if side == "left" else ("r", "l")
        banded.append(measures[f"goals_{mine}"])
        default.append(measures[f"goals_{theirs}"])
        differences.append(banded[-1] - default[-1])
        possession.append(100.0 * measures[f"possession_{mine}"])

    def cell(values: list[float], sign: str = "") -> str:
        m = mean_interval(values)
        return f"{m.value:{sign}.2f} [{m.low:{sign}.2f}, {m.high:{sign}.2f}]"

    rate = total.reversals / total.robot_minutes if total.robot_minutes else 0.0
    line = (
        f"| `{preset}` | {games} | {cell(differences, '+')} | {cell(banded)} | {cell(default)} | "
        f"{cell(possession)} | {rate:.1f} |"
    )
    data = {
        "games": games,
        "goal_difference": differences,
        "goals_dead_band": banded,
        "goals_default": default,
        "possession_dead_band_pct": possession,
        **asdict(total),
    }
    return line, data


SERIES_HEADER = (
    "| preset | games | dead band − default goals/game [95%] | dead-band goals/game | "
    "default goals/game | dead-band possession % [95%] | reversals /robot-min (both teams) |"
    "\n|" + "---|" * 7
)


def main() -> None:
    """Run the drills and the match; write a markdown table and the counts as JSON."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=200, help="interception trials per row")
    parser.add_argument("--half-time", type=float, default=30.0, help="match half [s]")
    parser.add_argument("--games", type=int, default=1, help="matches (seeds 0 ..)")
    parser.add_argument("--series", type=int, default=0, help="dead band v default games")
    parser.add_argument(
        "--lead-net",
        default="runs/learn-lead-seed0/models/robot_physics/lead_net.npz",
        help="the lead study's robot lead net ('none': no lead net row)",
    )
    parser.add_argument("--out", type=Path, default=Path("runs/robot-supersession"))
    args = parser.parse_args()
    if args.trials < 0 or args.games < 1 or args.series < 0 or not args.half_time > 0.0:
        parser.error("--trials and --series must be >= 0, --games >= 1, --half-time > 0")
    with_net = bool(args.trials) and args.lead_net != "none"
    if with_net and not Path(args.lead_net).is_file():
        parser.error(f"no lead net at {args.lead_net}")
    # The lead study's robot drill (shots across the goal mouth; `robotsoccer learn lead`).
    drill = (*LEAD_DRILLS["robot_physics"][1], ("decision", "lead"))
    net = (("behaviour", "net"), ("model", str(args.lead_net)))
    runs: list[tuple[str, TrialSpec, int]] = []
    for behaviour, options, presets in (
        ("straight", (("behaviour", "straight"),), PRESETS if args.trials else ()),
        ("lead net", net, PRESETS[1:] if with_net else ()),  # the net learned on `_arc`
    ):
        for preset in presets:
            runs.append(
                (
                    f"lead drill, {behaviour}, `{preset}`",
                    TrialSpec(
                        "intercept", "robot_physics", preset, drill_options=(*drill, *options)
                    ),
                    args.trials,
                )
            )
    match: tuple[tuple[str, DrillOption], ...] = (
        ("left", "baseline"),
        ("right", "baseline"),
        ("half_time_s", float(args.half_time)),
    )
    steady = (*match, ("steady_turns", True))
    banded = (*match, ("dead_band", True))
    for preset in PRESETS:
        for how, options in (("", match), (", steady turns", steady), (", dead band", banded)):
            runs.append(
                (
                    f"match baseline v baseline 5 v 5{how}, `{preset}`",
                    TrialSpec("match", "robot_physics", preset, drill_options=options),
                    args.games,
                )
            )
    args.out.mkdir(parents=True, exist_ok=True)
    lines, data = [HEADER], {}
    for name, spec, n in runs:
        counts, labels, wall = measure(spec, n)
        lines.append(row(name, counts, labels))
        data[name] = {"trials": n, "labels": labels, "wall_s": wall, **asdict(counts)}
        print(lines[-1], f"({n} trials, {wall:.0f} s)", flush=True)
    if args.series:
        lines += ["", SERIES_HEADER]
        for preset in PRESETS:
            start = time.perf_counter()
            line, data[f"series {preset}"] = series(preset, args.series, float(args.half_time))
            lines.append(line)
            print(line, f"({time.perf_counter() - start:.0f} s)", flush=True)
    (args.out / "table.md").write_text("\n".join(lines) + "\n")
    (args.out / "counts.json").write_text(json.dumps(data, indent=2) + "\n")


if __name__ == "__main__":
    main()
