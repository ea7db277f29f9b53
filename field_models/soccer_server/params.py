"""Soccer Server dynamics parameters and the preset loader (specs/soccer_server.md §1, §2, §7).

:class:`DynamicsParams` holds the ``server.conf`` values the dynamics use, under their server
names with a unit suffix. Units: metres and radians; speeds and accelerations stay *per cycle*
(``_m_per_cycle``, ``_m_per_cycle2``) because the cycle is the model's integer tick and the
server's equations are written per cycle (§0); the model's accessors convert to m/s. Angles are
given in the preset in degrees (``maxmoment_deg``) and converted to radians once, on load.

:class:`ServerPreset` bundles the dynamics with the sensing record
(:class:`~field_models.soccer_server.sensing_params.SensingParams`) and is loaded by
:func:`load_server_preset` from ``field_models/presets/soccer_server/<name>.toml``, from a TOML
file, or from a real server's own configuration (a ``server.conf`` file or a
``(server_param ...)`` message, :mod:`~field_models.soccer_server.server_conf`). A wrong file
raises :class:`~field_models.presets.PresetError` naming the file and the key.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

from field_models.presets import (
    PresetError,
    RecordError,
    bounded,
    check_ranges,
    convert_value,
    load_record,
    non_negative,
    positive,
    preset_path,
    probability,
    read_preset,
)
from field_models.protocol import Pitch
from field_models.soccer_server.sensing_params import SensingParams

NoiseModel = Literal["box", "polar"]
"""Movement and kick noise: per-axis uniform (≤ 11.x) or polar (≥ 12) (§1.3, §2.3)."""
Era = Literal["1996", "19"]
"""Which servers a preset stands for: the paper's (1996) or rcssserver 19."""
DEFAULT_PRESET = "soccer_server_1996"


class ParamError(RecordError):
    """A record value outside its allowed set; `key` names the offending field."""


MAX_RAND = 1.0
"""The largest noise factor (``ball_rand``, ``player_rand``, ``kick_rand``) [-]: at 1 the
noise is as large as the motion it perturbs."""
MAX_POWER = 10_000.0
"""The largest |power| of a dash or kick range [power units] (the servers use 100)."""
TWO_PI = 2.0 * math.pi
"""The largest |angle| of a turn moment or dash direction range [rad]."""


@dataclass(frozen=True, slots=True)
class DynamicsParams:
    """What moves the ball and the players, and how the referee reacts (spec §1, §2, §4, §6).

    Attributes:
        simulator_step_ms: ``simulator_step``: cycle length [ms].
        pitch_length_m: Goal line to goal line [m]. pitch_width_m: touchline to touchline [m].
        goal_width_m: ``goal_width`` [m]. goal_depth_m: goal depth (drawing only) [m].
        goal_post_radius_m: the server's compiled-in goal-post radius (0.06 m): widens the
            goal-line test by one post radius (§6); posts as obstacles (§1.4) are not modelled.
            0 for the post-less 1990s.
        center_circle_radius_m: kick-off clear distance for the non-kicking team [m].
        ball_size_m, player_size_m: ``ball_size``, ``player_size``: radii [m].
        ball_decay, player_decay: ``ball_decay``, ``player_decay``: velocity factor per cycle.
        ball_rand, player_rand: movement-noise factors; ``player_rand`` also scales turn noise.
        ball_speed_max_m_per_cycle, player_speed_max_m_per_cycle: speed caps [m/cycle].
        ball_accel_max_m_per_cycle2, player_accel_max_m_per_cycle2: acceleration caps
            [m/cycle²]; ``inf`` where the era had none.
        inertia_moment_cycle_per_m: ``inertia_moment``: turn damping per unit speed [cycle/m].
        dash_power_rate_m_per_cycle2: ``dash_power_rate`` [m/cycle² per power unit].
        kick_power_rate_m_per_cycle2: ``kick_power_rate`` [m/cycle² per power unit].
        kickable_margin_m: ``kickable_margin`` [m].
        kick_reduction: apply the distance/angle kick-effectiveness reduction ([CL 4.03], §2.3).
        kick_rand: ``kick_rand``: kick-noise factor (0 = off, the paper's era).
        noise_model: ``"box"`` (≤ 11.x) or ``"polar"`` (≥ 12) movement and kick noise (§1.3, §2.3).
        minpower, maxpower: kick power range (``minpower``/``maxpower``) [power units].
        min_dash_power, max_dash_power: dash power range [power units].
        minmoment_rad, maxmoment_rad: turn moment and kick direction range, in the server's
            (clockwise-on-our-field) sign convention [rad]; preset keys ``*_deg``.
        side_dash_rate: ``side_dash_rate``: dash power factor at ±90° (§2.1, rcssserver >= 13).
        back_dash_rate: ``back_dash_rate``: dash power factor at 180°.
        dash_angle_step_rad: ``dash_angle_step``: dash directions are rounded to multiples of
            it; 0 = any direction [rad]; preset key ``dash_angle_step_deg``.
        min_dash_angle_rad, max_dash_angle_rad: ``min_dash_angle``/``max_dash_angle``: dash
            direction range in the server's sign [rad]; 0 and 0 for servers without a dash
            direction (every dash runs straight); preset keys ``*_deg``.
        after_goal_wait_cycles: cycles between ``goal_l_N`` and the kick-off (50 today;
            0 in the paper's Figure 4, where both messages carry the same time).
        referee: goal detection and the after-goal sequence on (``server::coach`` off); off, the
            coach alone decides (the play mode then changes only by ``change_mode``).
        swept_ball_collisions: also catch a ball that passes *through* a player within a cycle
            (closest approach of the two straight paths closer than the sum of radii), which the
            real server misses because it checks overlaps only at the end of the cycle (§4:
            "a fast ball may pass through a player"). Off in both shipped presets (the real
            server); on, the pair is moved back to the moment of closest approach and resolved
            as a collision. Not supported by batch mode.
        minneckang_rad, maxneckang_rad: ``minneckang``/``maxneckang``: the neck angle's range
            relative to the body, server sign [rad] (±90° since 5.00; §2.2); preset keys
            ``*_deg``.
        minneckmoment_rad, maxneckmoment_rad: ``minneckmoment``/``maxneckmoment``: the range of
            one ``turn_neck`` moment, server sign [rad] (±180°); preset keys ``*_deg``.
    """

    simulator_step_ms: int = field(
        metadata=positive("server.conf simulator_step", high=10_000, low=1)
    )
    pitch_length_m: float = field(metadata=positive(high=1000))
    pitch_width_m: float = field(metadata=positive(high=1000))
    goal_width_m: float = field(metadata=positive("server.conf goal_width", high=1000))
    goal_depth_m: float = field(metadata=positive(high=100))
    goal_post_radius_m: float = field(metadata=non_negative("compiled in: 0.06 m today", high=10))
    center_circle_radius_m: float = field(metadata=non_negative(high=1000))
    ball_size_m: float = field(metadata=positive("server.conf ball_size", high=10))
    ball_decay: float = field(metadata=probability("server.conf ball_decay"))
    ball_rand: float = field(metadata=non_negative("server.conf ball_rand", high=MAX_RAND))
    ball_speed_max_m_per_cycle: float = field(
        metadata=positive("server.conf ball_speed_max", high=1000)
    )
    ball_accel_max_m_per_cycle2: float = field(
        metadata=positive("server.conf ball_accel_max; inf: no cap", high=1000, inf_ok=True)
    )
    player_size_m: float = field(metadata=positive("server.conf player_size", high=10))
    player_decay: float = field(metadata=probability("server.conf player_decay"))
    player_rand: float = field(metadata=non_negative("server.conf player_rand", high=MAX_RAND))
    player_speed_max_m_per_cycle: float = field(
        metadata=positive("server.conf player_speed_max", high=1000)
    )
    player_accel_max_m_per_cycle2: float = field(
        metadata=positive("server.conf player_accel_max; inf: no cap", high=1000, inf_ok=True)
    )
    inertia_moment_cycle_per_m: float = field(
        metadata=non_negative("server.conf inertia_moment", high=1000)
    )
    dash_power_rate_m_per_cycle2: float = field(
        metadata=non_negative("server.conf dash_power_rate", high=10)
    )
    kick_power_rate_m_per_cycle2: float = field(
        metadata=non_negative("server.conf kick_power_rate", high=10)
    )
    kickable_margin_m: float = field(metadata=positive("server.conf kickable_margin", high=100))
    kick_reduction: bool
    kick_rand: float = field(metadata=non_negative("server.conf kick_rand", high=MAX_RAND))
    noise_model: NoiseModel
    minpower: float = field(metadata=bounded(-MAX_POWER, MAX_POWER, "server.conf minpower"))
    maxpower: float = field(metadata=positive("server.conf maxpower", high=MAX_POWER))
    min_dash_power: float = field(
        metadata=bounded(-MAX_POWER, MAX_POWER, "server.conf min_dash_power")
    )
    max_dash_power: float = field(
        metadata=bounded(-MAX_POWER, MAX_POWER, "server.conf max_dash_power")
    )
    minmoment_rad: float = field(metadata=bounded(-TWO_PI, TWO_PI, "server.conf minmoment"))
    maxmoment_rad: float = field(metadata=bounded(-TWO_PI, TWO_PI, "server.conf maxmoment"))
    side_dash_rate: float = field(metadata=non_negative("server.conf side_dash_rate", high=10))
    back_dash_rate: float = field(metadata=non_negative("server.conf back_dash_rate", high=10))
    dash_angle_step_rad: float = field(
        metadata=non_negative("server.conf dash_angle_step", high=TWO_PI)
    )
    min_dash_angle_rad: float = field(
        metadata=bounded(-TWO_PI, TWO_PI, "server.conf min_dash_angle")
    )
    max_dash_angle_rad: float = field(
        metadata=bounded(-TWO_PI, TWO_PI, "server.conf max_dash_angle")
    )
    after_goal_wait_cycles: int = field(metadata=non_negative(high=100_000))
    referee: bool = True
    swept_ball_collisions: bool = False
    minneckang_rad: float = field(
        default=-0.5 * math.pi, metadata=bounded(-TWO_PI, TWO_PI, "server.conf minneckang")
    )
    maxneckang_rad: float = field(
        default=0.5 * math.pi, metadata=bounded(-TWO_PI, TWO_PI, "server.conf maxneckang")
    )
    minneckmoment_rad: float = field(
        default=-math.pi, metadata=bounded(-TWO_PI, TWO_PI, "server.conf minneckmoment")
    )
    maxneckmoment_rad: float = field(
        default=math.pi, metadata=bounded(-TWO_PI, TWO_PI, "server.conf maxneckmoment")
    )

    def __post_init__(self) -> None:
        check_ranges(self)
        _ordered("minpower", self.minpower, self.maxpower)
        _ordered("min_dash_power", self.min_dash_power, self.max_dash_power)
        _ordered("minmoment_rad", self.minmoment_rad, self.maxmoment_rad)
        _ordered("min_dash_angle_rad", self.min_dash_angle_rad, self.max_dash_angle_rad)
        _ordered("minneckang_rad", self.minneckang_rad, self.maxneckang_rad)
        _ordered("minneckmoment_rad", self.minneckmoment_rad, self.maxneckmoment_rad)
        if self.goal_width_m >= self.pitch_width_m:
            raise ParamError("goal_width_m", "expected less than pitch_width_m")
        if self.pitch_width_m > self.pitch_length_m:  # drills measure in length / 105
            raise ParamError("pitch_width_m", "expected at most pitch_length_m")

    @property
    def dt_s(self) -> float:
        """Length of one cycle [s]."""
        return self.simulator_step_ms / 1000.0

    @property
    def kickable_area_m(self) -> float:
        """Largest centre distance at which a kick reaches the ball [m] (§2.3)."""
        return self.player_size_m + self.ball_size_m + self.kickable_margin_m

    def pitch(self) -> Pitch:
        """The field geometry coaches and recordings see."""
        return Pitch(
            length_m=self.pitch_length_m,
            width_m=self.pitch_width_m,
            goal_width_m=self.goal_width_m,
            goal_depth_m=self.goal_depth_m,
            ball_radius_m=self.ball_size_m,
            player_radius_m=self.player_size_m,
            goal_post_radius_m=self.goal_post_radius_m,
        )

    def replace(self, **changes: Any) -> DynamicsParams:
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)


def _ordered(key: str, low: float, high: float) -> None:
    if low > high:
        raise ParamError(key, f"expected <= its maximum, got {low!r} > {high!r}")


@dataclass(frozen=True, slots=True)
class ServerPreset:
    """A Soccer Server configuration: its dynamics and its sensing, from one preset file.

    Attributes:
        name: Preset name (the file's stem unless the file sets ``name``).
        era: ``"1996"`` (the paper's servers, 1998 values where 1996 ones are unknown) or
            ``"19"`` (rcssserver 19.0.0 defaults).
        dynamics: Movement, commands, collisions, referee.
        sensing: See and hear parameters.
        source: The file it came from.
    """

    name: str
    era: Era
    dynamics: DynamicsParams
    sensing: SensingParams
    source: str = ""

    def replace_dynamics(self, **changes: Any) -> ServerPreset:
        """A copy whose dynamics have some fields changed (e.g. ``ball_rand=0.0``)."""
        return dataclasses.replace(self, dynamics=self.dynamics.replace(**changes))

    def replace_sensing(self, **changes: Any) -> ServerPreset:
        """A copy whose sensing has some fields changed (e.g. ``perfect=True``)."""
        return dataclasses.replace(self, sensing=self.sensing.replace(**changes))


def is_server_conf(name_or_path: str) -> bool:
    """Whether a preset argument is a real server's configuration (``.conf``, ``server_param``)."""
    return name_or_path.lstrip().startswith("(server_param") or name_or_path.endswith(".conf")


def load_server_preset(name_or_path: str = DEFAULT_PRESET) -> ServerPreset:
    """Load a Soccer Server preset by name (``soccer_server_1996``, ``rcssserver_19``) or path.

    Keys ending in ``_deg`` fill the record's ``_rad`` field of the same stem, converted once.
    A file may start from another preset with ``base = "<name>"`` and state only what differs.
    A real server's configuration (a ``server.conf`` file, a ``(server_param ...)`` message)
    is read by :func:`field_models.soccer_server.server_conf.load_preset`, which takes either.

    Raises:
        PresetError: naming the file and the key when the file is missing or wrong.
    """
    if is_server_conf(name_or_path):
        raise PresetError(
            f"{name_or_path[:60]}: a real server's configuration, not a preset file: "
            "load it with server_conf.load_preset"
        )
    path = preset_path(name_or_path, "soccer_server")
    table = read_preset(path, "soccer_server")
    unknown = sorted(set(table) - {"name", "era", "dynamics", "sensing"})
    if unknown:
        raise PresetError(f"{path}: key '{unknown[0]}': unknown key for ServerPreset")
    name = _top_string(table, "name", path, default=Path(path).stem)
    if "era" not in table:
        raise PresetError(f"{path}: key 'era': missing (required by ServerPreset)")
    era = convert_value(Era, table["era"], file=path, key="era")
    dynamics = _load_table(DynamicsParams, table, "dynamics", path)
    sensing = _load_table(SensingParams, table, "sensing", path)
    if sensing.simulator_step_ms != dynamics.simulator_step_ms:
        raise PresetError(
            f"{path}: key 'sensing.simulator_step_ms': expected dynamics.simulator_step_ms "
            f"({dynamics.simulator_step_ms}), got {sensing.simulator_step_ms}"
        )
    return ServerPreset(name=name, era=era, dynamics=dynamics, sensing=sensing, source=str(path))


def _top_string(table: dict[str, Any], key: str, path: Path, default: str) -> str:
    if key not in table:
        return default
    value = table[key]
    if not isinstance(value, str):
        raise PresetError(f"{path}: key '{key}': expected a string, got {type(value).__name__}")
    return value


def _load_table(cls: Any, table: dict[str, Any], key: str, path: Path) -> Any:
    """Load one sub-table into `cls` (the record's own checks become PresetErrors)."""
    if key not in table:
        raise PresetError(f"{path}: key '{key}': missing (required by ServerPreset)")
    sub = degrees_to_radians(cls, table[key], file=path, key=key)
    return load_record(cls, sub, file=path, key=key)


def degrees_to_radians(cls: Any, table: Any, *, file: Path | str, key: str) -> Any:
    """Rename ``x_deg`` keys to the record's ``x_rad`` fields, converting the value once.

    A ``_deg`` key whose ``_rad`` field does not exist is left alone (the record may hold
    degrees on purpose, or the key is unknown and :func:`load_record` says so).
    """
    if not isinstance(table, dict):
        return table  # load_record reports the wrong type
    names = {f.name for f in dataclasses.fields(cls)}
    out = dict(table)
    for name, value in table.items():
        target = name[: -len("_deg")] + "_rad"
        if not name.endswith("_deg") or name in names or target not in names:
            continue
        dotted = f"{key}.{name}"
        if target in table:
            raise PresetError(f"{file}: key '{dotted}': give either {name} or {target}, not both")
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise PresetError(
                f"{file}: key '{dotted}': expected a number, got {type(value).__name__} {value!r}"
            )
        del out[name]
        try:
            out[target] = math.radians(value)
        except OverflowError:  # an integer of hundreds of digits
            raise PresetError(f"{file}: key '{dotted}': expected a finite number") from None
    return out
