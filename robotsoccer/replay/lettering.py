"""Large stroke letters drawn on the field: a trial's outcome, a match's score and clock.

rerun 0.41 draws labels in one small UI font with no size setting, so text that must read at a
glance is drawn as line strips in the field frame [m] (:func:`text_strokes`).
"""

from __future__ import annotations

import numpy as np

# Capital letters as strokes on a 4 × 6 grid (x right, y up), for the outcome drawn large on
# the field (rerun 0.41 draws labels in one small UI font with no size setting). Each glyph is
# its strokes separated by spaces, each stroke its points as digit pairs "xy".
_GLYPHS: dict[str, str] = {
    "A": "0004264440 0343",
    "B": "00063645443303 3342413000",
    "C": "4536160501103041",
    "D": "00062644422000",
    "E": "46060040 0333",
    "F": "460600 0333",
    "G": "45361605011030414323",
    "H": "0006 4046 0343",
    "I": "1636 2620 1030",
    "J": "4641301001",
    "K": "0006 4602 1340",
    "L": "060040",
    "M": "0006234640",
    "N": "00064046",
    "O": "100105163645413010",
    "P": "00063645443303",
    "Q": "100105163645413010 2240",
    "R": "00063645443303 2340",
    "S": "453616050413334241301001",
    "T": "0646 2620",
    "U": "060110304146",
    "V": "062046",
    "W": "0610233046",
    "X": "0046 0640",
    "Y": "062346 2320",
    "Z": "06460040",
    "-": "1333",
    # Digits and the colon, for the score of a match (match_recording.py).
    "0": "100105163645413010",
    "1": "152620 1030",
    "2": "05163645440040",
    "3": "0516364544334241301001 1333",
    "4": "30360242",
    "5": "4606033342413000",
    "6": "4536160501103041423303",
    "7": "064610",
    "8": "13040516364544331302011030414233",
    "9": "0110304145361605041343",
    ":": "2122 2425",
}
_GLYPH_WIDTH, _GLYPH_HEIGHT = 4, 6  # the grid
_GLYPH_ADVANCE = _GLYPH_WIDTH + 2  # from one letter to the next: a letter and a gap


def text_width(text: str, height_m: float) -> float:
    """Width of `text` in the stroke letters of :func:`text_strokes` of height `height_m` [m]."""
    if not text:
        return 0.0
    return ((len(text) - 1) * _GLYPH_ADVANCE + _GLYPH_WIDTH) * height_m / _GLYPH_HEIGHT


def text_strokes(
    text: str, *, height_m: float, centre_x_m: float, base_y_m: float
) -> list[np.ndarray]:
    """`text` in large stroke letters, centred on x = centre_x_m above y = base_y_m [m].

    Capital letters, digits, ``-`` and ``:`` are drawn (lower case as capitals); other
    characters leave a gap. Used for the outcome and a match's score, which must read at a
    glance.

    Returns:
        One (K, 2) line strip per stroke, in the field frame.
    """
    unit = height_m / _GLYPH_HEIGHT
    x0 = centre_x_m - 0.5 * text_width(text, height_m)
    strips: list[np.ndarray] = []
    for i, char in enumerate(text.upper()):
        for stroke in _GLYPHS.get(char, "").split():
            xy = np.array([int(d) for d in stroke], dtype=np.float64).reshape(-1, 2) * unit
            xy[:, 0] += x0 + i * _GLYPH_ADVANCE * unit
            xy[:, 1] += base_y_m
            strips.append(xy)
    return strips
