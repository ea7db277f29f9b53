"""``robotsoccer serve``: runs, stops by itself, records an .rcg the readers take back."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotsoccer.cli import main
from robotsoccer.replay.rcg_read import read_rcg


def test_serve_runs_for_a_while_and_records_the_game(tmp_path: Path) -> None:
    argv = ["serve", "--port", "0", "--trainer-port", "0", "--olcoach-port", "0"]
    argv += ["--seconds", "0.35", "--play-on", "--quiet", "--record", str(tmp_path)]
    assert main(argv) == 0
    logs = sorted(tmp_path.glob("*.rcg"))
    assert len(logs) == 1 and (tmp_path / f"{logs[0].name}.rrd").exists()
    game = read_rcg(logs[0])
    assert game.frames and game.frames[0].tick == 1
    assert game.server_params["ball_decay"] == "0.94" and game.server_params["synch_mode"] == "0"


def test_serve_refuses_a_bad_port_in_one_line(capsys) -> None:
    with pytest.raises(SystemExit) as exit_:
        main(["serve", "--port", "70000"])
    assert exit_.value.code == 2 and "0..65535" in capsys.readouterr().err
