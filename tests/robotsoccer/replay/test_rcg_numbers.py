"""Numbers in a game log that overflow a double are refused like ``inf`` (issue 30)."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotsoccer.replay.rcg_read import read_rcg

HEAD = "ULG5\n(server_param (goal_width 14.02)(simulator_step 100))\n(playmode 1 play_on)\n"
SHOW = "(show 1 ((b) {b} 0 0 0) ((l 1) 0 0x1 {x} 0 0 0 0 0 (v h 90) (s 1 1 1) (c 0)))\n"


def _read(tmp_path: Path, text: str) -> None:
    path = tmp_path / "game.rcg"
    path.write_text(text)
    read_rcg(path)


def test_finite_numbers_read(tmp_path: Path) -> None:
    _read(tmp_path, HEAD + SHOW.format(b="1e300", x="-3.5"))


@pytest.mark.parametrize(
    "text",
    [
        HEAD + SHOW.format(b="1e999", x="0"),
        HEAD + SHOW.format(b="0", x="0").replace("((b) 0 0 0 0)", "((b) 0 0 0 1e308)"),
        HEAD + SHOW.format(b="0", x="-1e999"),
        HEAD + SHOW.format(b="0", x="1" + "0" * 400),
        HEAD.replace("14.02", "1e999") + SHOW.format(b="0", x="0"),
        HEAD.replace("14.02", "nan") + SHOW.format(b="0", x="0"),
        HEAD.replace("100", "1e999") + SHOW.format(b="0", x="0"),
        HEAD + SHOW.format(b="0", x="0").replace("show 1", "show 1" + "0" * 5000),
        HEAD + "(team 1 a b 1" + "0" * 5000 + " 0)\n",
        HEAD + SHOW.format(b="0", x="0").replace("(l 1)", "(l 1" + "0" * 5000 + ")"),
    ],
)
def test_overflowing_numbers_are_refused_naming_file_and_line(tmp_path: Path, text: str) -> None:
    with pytest.raises(ValueError, match=r"game\.rcg:[0-9]+: ") as err:
        _read(tmp_path, text)
    assert len(str(err.value)) < 300
