"""Cheap construction of the frozen, slotted dataclasses the robot engine makes every frame.

A frozen dataclass's ``__init__`` stores each field through ``object.__setattr__`` (the class's
own ``__setattr__`` refuses), a Python-level call per field; the host builds about 130 such
records per camera frame with 12 robots (issue 21's profile: percept building is the largest
per-frame cost). :func:`positional_maker` returns a constructor that fills the same slots through
the slots' own descriptors instead. The object is the same: same class, same field values, equal
and hashing equal to one built by ``__init__``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any, TypeVar

T = TypeVar("T")


def positional_maker(cls: type[T]) -> Callable[..., T]:
    """A constructor of `cls` taking every field positionally, in declaration order.

    Only for frozen dataclasses with slots and no ``__post_init__`` (nothing is skipped then
    but the frozen check); all fields must be given (defaults are not applied).

    Raises:
        TypeError: `cls` is not such a dataclass.
    """
    params = getattr(cls, "__dataclass_params__", None)
    if params is None or not params.frozen or "__slots__" not in cls.__dict__:
        raise TypeError(f"{cls.__name__} is not a frozen dataclass with slots")
    if hasattr(cls, "__post_init__"):
        raise TypeError(f"{cls.__name__} has a __post_init__ that a positional maker would skip")
    names = [f.name for f in dataclasses.fields(cls)]  # type: ignore[arg-type]
    scope: dict[str, Any] = {"_new": object.__new__, "_cls": cls}
    for k, name in enumerate(names):
        scope[f"_set{k}"] = cls.__dict__[name].__set__
    args = ", ".join(f"a{k}" for k in range(len(names)))
    body = "".join(f"    _set{k}(o, a{k})\n" for k in range(len(names)))
    source = f"def make({args}):\n    o = _new(_cls)\n{body}    return o\n"
    exec(source, scope)  # a straight-line function: no loop over the fields per call
    make: Callable[..., T] = scope["make"]
    make.__doc__ = f"{cls.__name__}({', '.join(names)}), built without the frozen check."
    return make
