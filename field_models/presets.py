"""Loading frozen, typed config records from TOML preset files, with errors that name the key.

A preset file is data; the records it fills are frozen dataclasses whose field names carry their
units (`mass_kg`, `latency_s`). Constraints live in the field's metadata:

* ``positive``: the number must be > 0;
* ``non_negative``: >= 0;
* ``probability``: in [0, 1].

An option is typed ``Literal["a", "b"]``: the value must be one of the literal's values.

A wrong file raises :class:`PresetError` naming the file, the dotted key and what was expected.
Unknown keys are errors too: a misspelt key must not silently fall back to a default.
"""

from __future__ import annotations

import dataclasses
import tomllib
import types
import typing
from pathlib import Path
from typing import Any, TypeVar

PRESET_DIR = Path(__file__).parent / "presets"
"""Folder holding the preset files shipped with the package."""

T = TypeVar("T")


class PresetError(ValueError):
    """A preset file is missing, unreadable or holds a wrong value."""


def positive(doc: str = "") -> dict[str, Any]:
    """Field metadata for a number that must be > 0."""
    return {"check": "positive", "doc": doc}


def non_negative(doc: str = "") -> dict[str, Any]:
    """Field metadata for a number that must be >= 0."""
    return {"check": "non_negative", "doc": doc}


def probability(doc: str = "") -> dict[str, Any]:
    """Field metadata for a number in [0, 1]."""
    return {"check": "probability", "doc": doc}


_CHECKS = {
    "positive": (lambda v: v > 0, "a positive number"),
    "non_negative": (lambda v: v >= 0, "a number >= 0"),
    "probability": (lambda v: 0 <= v <= 1, "a probability in [0, 1]"),
}


def read_toml(path: Path) -> dict[str, Any]:
    """Read a TOML file, turning any failure into a PresetError that names the file."""
    try:
        with path.open("rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise PresetError(f"{path}: preset file not found") from None
    except tomllib.TOMLDecodeError as exc:
        raise PresetError(f"{path}: not valid TOML ({exc})") from None


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
        return Path(name_or_path)
    path = PRESET_DIR / prefix / f"{name_or_path}.toml"
    if not path.exists():
        known = ", ".join(sorted(p.stem for p in (PRESET_DIR / prefix).glob("*.toml")))
        raise PresetError(f"unknown preset {name_or_path!r} (known: {known})")
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
    return cls(**values)


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
            raise PresetError(f"{file}: key '{key}': expected one of {shown}; got {value!r}")
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
        return float(value)
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
    return f"{type(value).__name__} {value!r}"


def _check(fld: dataclasses.Field[Any], value: Any, *, file: Path | str, key: str) -> None:
    check = fld.metadata.get("check")
    if check is None:
        return
    ok, expected = _CHECKS[check]
    if not ok(value):
        raise PresetError(f"{file}: key '{key}': expected {expected}, got {value!r}")
