"""What every environment checks of what it is given: seeds and turn-angle actions.

An environment is an API: a NaN action, an action of the wrong shape or a seed Gymnasium would
not take must be refused with a clear :class:`ValueError`, not played, silently cut to shape,
or left to hang a batch (a NaN turn angle used to reach the Soccer Server's see quantisation
and loop over a 2^64-entry table).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

SEED_LIMIT = 2**64
"""Seeds are whole numbers in [0, 2^64) (Gymnasium's rule), or None."""


def checked_seed(seed: object) -> int | None:
    """`seed` as an int when it follows Gymnasium's rule: None, or a whole number in [0, 2^64).

    >>> checked_seed(7), checked_seed(None)
    (7, None)

    Raises:
        ValueError: A negative, too large, float, bool or string seed.
    """
    if seed is None:
        return None
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer):
        shown = f"{type(seed).__name__} {seed!r}"[:60]
        raise ValueError(f"seed must be None or a whole number in [0, 2**64), got {shown}")
    value = int(seed)
    if not 0 <= value < SEED_LIMIT:
        raise ValueError(f"seed must be a whole number in [0, 2**64), got {str(value)[:40]}")
    return value


def checked_seeds(seeds: object, n: int) -> list[int]:
    """One seed per environment, each as :func:`checked_seed` wants it (None refused).

    Raises:
        ValueError: Not a sequence of `n` whole numbers in [0, 2^64).
    """
    if isinstance(seeds, str | bytes) or not isinstance(seeds, Sequence | np.ndarray):
        raise ValueError(f"seed must be None, a whole number or {n} of them, got {seeds!r:.60}")
    if len(seeds) != n:
        raise ValueError(f"expected {n} seeds, got {len(seeds)}")
    checked = [checked_seed(s) for s in seeds]
    return [_not_none(s) for s in checked]


def _not_none(seed: int | None) -> int:
    if seed is None:
        raise ValueError("seed must be a whole number in [0, 2**64), got None")
    return seed


def checked_turns(actions: object, n: int) -> npt.NDArray[np.float64]:
    """`n` turn angles TA [rad] from an action batch of shape (n, 1) or (n,), all finite.

    The single environment's action (n = 1) may also be a scalar.

    Raises:
        ValueError: Not numbers, another shape (an (8,) array for 4 environments is refused,
            not read as every other element), or a NaN or infinite angle.
    """
    try:
        values = np.asarray(actions, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"actions must be turn angles [rad], got {actions!r:.60}") from None
    accepted = ((n, 1), (n,), ()) if n == 1 else ((n, 1), (n,))
    if values.shape not in accepted:
        shapes = " or ".join(str(s) for s in accepted)
        raise ValueError(f"actions must have shape {shapes}, got {values.shape}")
    if not np.isfinite(values).all():
        raise ValueError("actions must be finite turn angles [rad], got NaN or inf")
    return values.reshape(n)
