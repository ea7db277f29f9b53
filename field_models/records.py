"""Cheap construction of the frozen, slotted dataclasses both field models make every frame.

A frozen dataclass's ``__init__`` stores each field through ``object.__setattr__`` (the class's
own ``__setattr__`` refuses), a Python-level call per field; the host builds about 130 such
records per camera frame with 12 robots (issue 21's profile: percept building is the largest
per-frame cost). :func:`positional_maker` returns a constructor that stores the same slots with
plain slot stores in a twin class of the same layout, then switches the object's class. The
object is the same: same class, same field values, equal and hashing equal to one built by
``__init__``. The Soccer Server model builds its sees the same way
(:mod:`field_models.soccer_server.percepts_many`).
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
    slots = cls.__dict__["__slots__"]
    if tuple(slots) != tuple(names):
        raise TypeError(f"{cls.__name__}: slots {slots} are not its fields {names}")
    # A plain class with the same slots (so the same memory layout, which lets an object change
    # class): its __init__ stores each field with an ordinary slot store, then the object
    # becomes a `cls` (the frozen check guards `cls`'s own __setattr__ only).
    args = ", ".join(f"a{k}" for k in range(len(names)))
    body = "".join(f"    self.{name} = a{k}\n" for k, name in enumerate(names))
    source = f"def __init__(self, {args}):\n{body}    self.__class__ = _cls\n"
    scope: dict[str, Any] = {"_cls": cls}
    exec(source, scope)  # a straight-line __init__: no loop over the fields per call
    twin = type(f"_{cls.__name__}Maker", (), {"__slots__": slots, "__init__": scope["__init__"]})
    make: Callable[..., T] = twin
    probe = make(*([None] * len(names)))
    if type(probe) is not cls:  # pragma: no cover - the class switch failed silently
        raise TypeError(f"{cls.__name__}: the positional maker does not build one")
    return make
