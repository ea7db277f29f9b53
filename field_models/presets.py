"""Loading frozen, typed config records from TOML preset files, with errors that name the key.

A preset file is data; the records it fills are frozen dataclasses whose field names carry their
units (`mass_kg`, `latency_s`). **Every number of a record states its range beside the field**,
in the field's metadata (:class:`Bounds`), made by one of:

* :func:`positive`: > 0, from a millionth of a stated maximum (or a stated minimum) to it;
* :func:`non_negative`: >= 0 and at most a stated maximum;
* :func:`probability`: in [0, 1];
* :func:`bounded`: in a stated closed interval (a signed value such as a power or an angle).

A number must be finite (``inf`` and ``nan`` are refused) unless its bounds say ``inf_ok``: a
limit a preset may switch off (the 1990s servers had no acceleration cap). The ranges are
generous sanity bounds, not physics: they keep an absurd value (a 10 m robot on a 2.74 m
table, a 2.4e7 Hz physics step, a 1e300 ms cycle, a 5e-324 kg mass) from reaching a
simulation that would abort in C, cast a NaN to an integer or loop without end. A record
checks its own ranges when it is built (:func:`check_ranges`, called from each record's
``__post_init__``), so a copy made with ``replace`` is checked too; the loader names the file
and the key.

An option is typed ``Literal["a", "b"]``: the value must be one of the literal's values.

A wrong file raises :class:`PresetError` naming the file, the dotted key and what was expected,
in one line. Unknown keys are errors too: a misspelt key must not silently fall back to a
default. Files are read as UTF-8 text of at most :data:`MAX_PRESET_BYTES`.
"""

from __future__ import annotations

import dataclasses
import math
import re
import tomllib
import types
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

PRESET_DIR = Path(__file__).parent / "presets"
"""Folder holding the preset files shipped with the package."""
_PRESET_NAME = re.compile(r"[A-Za-z0-9_.-]{1,100}")
MAX_PRESET_BYTES = 1 << 20
"""The largest preset or server configuration file read [bytes]: a real one is a few KiB, and
the cap keeps ``/dev/zero`` or a wrong file from filling the memory."""

T = TypeVar("T")


class PresetError(ValueError):
    """A preset file is missing, unreadable or holds a wrong value."""


class RecordError(ValueError):
    """A record value outside its allowed set; `key` names the offending field.

    Raised by a record's own checks (:func:`check_ranges`, cross-field rules); the loader turns
    it into a :class:`PresetError` that names the file and the dotted key.
    """

    def __init__(self, key: str, message: str) -> None:
        super().__init__(f"{key}: {message}")
        self.key = key
        self.message = message


@dataclass(frozen=True, slots=True)
class Bounds:
    """The closed range [``low``, ``high``] a record's number must lie in.

    Attributes:
        low: The smallest value.
        high: The largest value.
        inf_ok: ``+inf`` is accepted too: the limit is switched off.
        expected: What an error message says was expected.
    """

    low: float
    high: float
    inf_ok: bool
    expected: str

    def admits(self, value: float) -> bool:
        """Whether `value` lies in the range (NaN never does)."""
        if math.isinf(value):
            return self.inf_ok and value > 0
        return self.low <= value <= self.high  # False for NaN


def _bounds(low: float, high: float, inf_ok: bool, expected: str) -> Bounds:
    if not low < high or math.isinf(low) or math.isinf(high):  # NaN fails low < high
        raise ValueError(f"bad bounds [{low!r}, {high!r}]")  # a bug in a record, not a file
    suffix = ", or inf (no limit)" if inf_ok else ""
    return Bounds(low, high, inf_ok, expected + suffix)


POSITIVE_FLOOR = 1e-6
"""A positive number's default lowest value, as a share of its highest."""


def positive(
    doc: str = "", *, high: float, low: float | None = None, inf_ok: bool = False
) -> dict[str, Any]:
    """Field metadata for a positive number in [`low`, `high`].

    `low` defaults to a millionth of `high`: a positive value far below any real one (a
    5e-324 kg mass, a 5e-324 Hz rate) is as absurd as a huge one, and its reciprocal or its
    products underflow (Chipmunk refuses a body whose moment of inertia comes out 0).
    """
    floor = high * POSITIVE_FLOOR if low is None else low
    expected = f"a positive number in [{_num(floor)}, {_num(high)}]"
    return {"bounds": _bounds(floor, high, inf_ok, expected), "doc": doc}


def non_negative(doc: str = "", *, high: float) -> dict[str, Any]:
    """Field metadata for a number >= 0 and <= `high`."""
    expected = f"a number >= 0 and <= {_num(high)}"
    return {"bounds": _bounds(0.0, high, False, expected), "doc": doc}


def probability(doc: str = "") -> dict[str, Any]:
    """Field metadata for a number in [0, 1]."""
    return {"bounds": _bounds(0.0, 1.0, False, "a probability in [0, 1]"), "doc": doc}


def bounded(low: float, high: float, doc: str = "") -> dict[str, Any]:
    """Field metadata for a number in [`low`, `high`] (a signed value: a power, an angle)."""
    expected = f"a number in [{_num(low)}, {_num(high)}]"
    return {"bounds": _bounds(low, high, False, expected), "doc": doc}


def bounds_of(fld: dataclasses.Field[Any]) -> Bounds | None:
    """The range stated beside a record's field; None for a field that is not a number."""
    bounds = fld.metadata.get("bounds")
    return bounds if isinstance(bounds, Bounds) else None


def _num(value: float) -> str:
    """A bound as a message shows it: ``100``, ``0.5``, ``3.14159``, ``1e+06``."""
    return f"{value:g}"


def _shown(value: Any) -> str:
    """A value for a one-line message: its repr, cut short (a 400-digit number stays short)."""
    text = repr(value)
    if len(text) <= 32:
        return text
    if isinstance(value, int):
        return f"an integer of {len(text.lstrip('-'))} digits"
    return f"{text[:24]}... ({len(text)} characters)"


def range_problem(bounds: Bounds | None, value: Any) -> str | None:
    """What is wrong with `value` for a field with `bounds`; None when it is fine.

    Numbers without bounds must still be finite; non-numbers (bool, str, None, records) pass.
    """
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    if bounds is None:
        finite = isinstance(value, int) or math.isfinite(value)
        return None if finite else f"expected a finite number, got {_shown(value)}"
    if isinstance(value, int) and not bounds.low - 1 <= value <= bounds.high + 1:
        return f"expected {bounds.expected}, got {_shown(value)}"  # no float() of a huge int
    if not bounds.admits(value):
        return f"expected {bounds.expected}, got {_shown(value)}"
    return None


def check_ranges(record: Any) -> None:
    """Check every number of a dataclass `record` against the bounds beside its field.

    Called from the records' ``__post_init__``: a record out of range cannot be built, by a
    loader or by ``replace``.

    Raises:
        RecordError: naming the first field out of range and what was expected.
    """
    for fld in dataclasses.fields(record):
        problem = range_problem(bounds_of(fld), getattr(record, fld.name))
        if problem is not None:
            raise RecordError(fld.name, problem)


def read_text(path: Path, what: str = "preset file") -> str:
    """A UTF-8 text file of at most :data:`MAX_PRESET_BYTES`, or a PresetError naming it.

    Args:
        path: The file.
        what: What the file is, for messages (``preset file``).
    """
    try:
        with path.open("rb") as fh:
            data = fh.read(MAX_PRESET_BYTES + 1)
    except FileNotFoundError:
        raise PresetError(f"{path}: {what} not found") from None
    except OSError as exc:
        raise PresetError(f"{path}: cannot read the {what} ({exc.strerror or exc})") from None
    if len(data) > MAX_PRESET_BYTES:
        raise PresetError(f"{path}: larger than {MAX_PRESET_BYTES >> 10} KiB, not a {what}")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise PresetError(f"{path}: not UTF-8 text (byte {exc.start}): not a {what}") from None


def read_toml(path: Path) -> dict[str, Any]:
    """Read a TOML file, turning any failure into a PresetError that names the file."""
    text = read_text(path)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise PresetError(f"{path}: not valid TOML ({exc})") from None
    except ValueError:  # Python's limit on the digits of an integer it converts
        raise PresetError(f"{path}: not valid TOML (a number with too many digits)") from None
    except RecursionError:  # tomllib parses nested arrays and tables recursively
        raise PresetError(f"{path}: not valid TOML (nested too deeply)") from None


def read_preset(path: Path, prefix: str, _seen: tuple[Path, ...] = ()) -> dict[str, Any]:
    """Read a preset file, resolving ``base = "<preset>"``: the base's tables, then this file's.

    A variant preset names its base and states only what differs, so a one-key change is not a
    copy of the whole file. Tables merge key by key (recursively); ``base`` itself is consumed.

    Raises:
        PresetError: for an unreadable file, a base that is not a string, or a cycle of bases.
    """
    table = read_toml(path)
    base = table.pop("base", None)
    if base is None:
        return table
    if not isinstance(base, str):
        raise PresetError(f"{path}: key 'base': expected a preset name, got {_kind(base)}")
    base_path = preset_path(base, prefix)
    if base_path.resolve() in (*_seen, path.resolve()):
        raise PresetError(f"{path}: key 'base': {base!r} leads back to this file (a cycle)")
    merged = read_preset(base_path, prefix, (*_seen, path.resolve()))
    merged.pop("name", None)  # a variant is its own preset, named after its file by default
    return _merge(merged, table)


def _merge(base: dict[str, Any], override: dict[str, Any]) -> dict[str, Any]:
    out = dict(base)
    for key, value in override.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = _merge(out[key], value)
        else:
            out[key] = value
    return out


def preset_path(name_or_path: str, prefix: str) -> Path:
    """Resolve a preset name (``small_size_1997``) or a path to a ``.toml`` file.

    Args:
        name_or_path: A shipped preset's name, or a path to a preset file.
        prefix: Sub-folder of the shipped presets for this field model.
    """
    if name_or_path.endswith(".toml") or "/" in name_or_path:
        if "\0" in name_or_path:  # no such file can exist; Path would raise a bare ValueError
            raise PresetError(f"{name_or_path!r}: preset file not found")
        return Path(name_or_path)
    path = PRESET_DIR / prefix / f"{name_or_path}.toml"
    if not _PRESET_NAME.fullmatch(name_or_path) or not path.exists():
        known = ", ".join(sorted(p.stem for p in (PRESET_DIR / prefix).glob("*.toml")))
        raise PresetError(f"unknown preset {_shown(name_or_path)} (known: {known})")
    return path


def load_record(cls: type[T], table: Any, *, file: Path | str, key: str = "") -> T:
    """Build a frozen dataclass `cls` from a TOML table, checking keys, types and ranges.

    Args:
        cls: The dataclass type to fill.
        table: The parsed TOML table for it.
        file: The preset file, named in errors.
        key: Dotted key of `table` inside the file, named in errors.

    Raises:
        PresetError: naming the file, the key and what was expected.
    """
    where = key or "<top level>"
    if not isinstance(table, dict):
        raise PresetError(f"{file}: key '{where}': expected a table, got {type(table).__name__}")
    hints = typing.get_type_hints(cls)
    fields = {f.name: f for f in dataclasses.fields(cls)}  # type: ignore[arg-type]
    unknown = sorted(set(table) - set(fields))
    if unknown:
        raise PresetError(f"{file}: key '{_join(key, unknown[0])}': unknown key for {cls.__name__}")
    values: dict[str, Any] = {}
    for name, fld in fields.items():
        dotted = _join(key, name)
        if name not in table:
            if fld.default is dataclasses.MISSING and fld.default_factory is dataclasses.MISSING:
                raise PresetError(f"{file}: key '{dotted}': missing (required by {cls.__name__})")
            continue
        values[name] = _convert(hints[name], table[name], file=file, key=dotted)
        _check(fld, values[name], file=file, key=dotted)
    try:
        return cls(**values)
    except RecordError as exc:  # the record's cross-field rules (e.g. minpower <= maxpower)
        raise PresetError(f"{file}: key '{_join(key, exc.key)}': {exc.message}") from None


def load_field(cls: type, name: str, value: Any, *, file: Path | str, key: str) -> Any:
    """One field `name` of dataclass `cls` from a value: its type and range checks.

    For loaders that fill a record from another format (e.g. a server's own configuration)
    and name the key as that format spells it.

    Raises:
        PresetError: naming the file, `key` and what was expected.
    """
    fld = {f.name: f for f in dataclasses.fields(cls)}[name]
    converted = convert_value(typing.get_type_hints(cls)[name], value, file=file, key=key)
    _check(fld, converted, file=file, key=key)
    return converted


def convert_value(hint: Any, value: Any, *, file: Path | str, key: str) -> Any:
    """A TOML value checked against the type `hint` (numbers, strings, options, tables).

    Raises:
        PresetError: naming the file, the key and what was expected.
    """
    return _convert(hint, value, file=file, key=key)


def _join(key: str, name: str) -> str:
    return f"{key}.{name}" if key else name


def _convert(hint: Any, value: Any, *, file: Path | str, key: str) -> Any:
    origin = typing.get_origin(hint)
    if origin is typing.Literal:
        allowed = typing.get_args(hint)
        if isinstance(value, bool) or value not in allowed:
            shown = ", ".join(str(a) for a in allowed)
            raise PresetError(f"{file}: key '{key}': expected one of {shown}; got {_shown(value)}")
        return value
    if origin in (typing.Union, types.UnionType):
        options = [a for a in typing.get_args(hint) if a is not type(None)]
        if len(options) == 1:
            return _convert(options[0], value, file=file, key=key)
    if dataclasses.is_dataclass(hint) and isinstance(hint, type):
        return load_record(hint, value, file=file, key=key)
    if origin is tuple:
        args = typing.get_args(hint)
        if not isinstance(value, list):
            raise PresetError(f"{file}: key '{key}': expected a list, got {_kind(value)}")
        return tuple(
            _convert(args[0], v, file=file, key=f"{key}[{i}]") for i, v in enumerate(value)
        )
    if hint is float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise PresetError(f"{file}: key '{key}': expected a number, got {_kind(value)}")
        try:
            return float(value)
        except OverflowError:  # an integer of hundreds of digits
            raise PresetError(
                f"{file}: key '{key}': expected a finite number, got {_shown(value)}"
            ) from None
    if hint is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise PresetError(f"{file}: key '{key}': expected an integer, got {_kind(value)}")
        return value
    if hint is bool:
        if not isinstance(value, bool):
            raise PresetError(f"{file}: key '{key}': expected true or false, got {_kind(value)}")
        return value
    if hint is str:
        if not isinstance(value, str):
            raise PresetError(f"{file}: key '{key}': expected a string, got {_kind(value)}")
        return value
    raise TypeError(f"unsupported field type {hint!r} at {key}")  # a bug in a record, not a file


def _kind(value: Any) -> str:
    return f"{type(value).__name__} {_shown(value)}"


def _check(fld: dataclasses.Field[Any], value: Any, *, file: Path | str, key: str) -> None:
    problem = range_problem(bounds_of(fld), value)
    if problem is not None:
        raise PresetError(f"{file}: key '{key}': {problem}")
