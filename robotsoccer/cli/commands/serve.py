"""``robotsoccer serve``: the Soccer Server model on UDP in rcssserver's protocol.

The one command that names a field model's own modules (it serves that model), so
``tests/test_boundaries.py`` lets it.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from field_models.arena import FieldOptions
from robotsoccer.cli.options import (
    SERVE_FIELD,
    SERVE_PRESET,
    _index,
    _noise,
    _port,
    _positive_float,
    _positive_int,
)
from robotsoccer.cli.shared import Commands


def cmd_serve(args: argparse.Namespace) -> int:
    """Serve the Soccer Server model on UDP until a limit or Ctrl-C (:mod:`robotsoccer.serve`)."""
    from field_models.registry import entry
    from field_models.soccer_server.serving import ServedGame
    from field_models.soccer_server.udp import UdpServer
    from field_models.soccer_server.wire import server_params
    from robotsoccer.serve import GameRecorder, run_serve, stderr_log

    options = FieldOptions(perfect_perception=args.perfect_perception, ball_noise=args.ball_noise)
    preset = entry("soccer_server").load(args.field_preset, options)
    log = (lambda line: None) if args.quiet else stderr_log()
    if args.host != "127.0.0.1":
        log(f"binding {args.host}: reachable from other machines")
    overrides: dict[str, bool | int | float | str] = {
        "port": args.port,
        "coach_port": args.trainer_port,
        "olcoach_port": args.olcoach_port,
        "synch_mode": args.synch,
    }
    start = "play_on" if args.play_on else "before_kick_off"
    game = ServedGame(
        preset, seed=args.seed, synch=args.synch, log=log, overrides=overrides, start_mode=start
    )
    server = UdpServer(
        game,
        host=args.host,
        port=args.port,
        trainer_port=args.trainer_port,
        olcoach_port=args.olcoach_port,
        synch_timeout_s=args.synch_timeout,
        idle_timeout_s=args.idle_timeout,
        log=log,
    )
    recorder = None
    if args.record is not None:
        stem = f"serve_{time.strftime('%Y%m%d-%H%M%S')}_seed{args.seed}"
        params = server_params(preset, overrides)
        recorder = GameRecorder(args.record, stem, game.dt_s, params)
    return run_serve(
        server, game, cycles=args.cycles, seconds=args.seconds, recorder=recorder, log=log
    )


def add_parser(commands: Commands) -> None:
    """``serve``'s options."""
    serve = commands.add(
        "serve",
        "serve the Soccer Server model over UDP in rcssserver's protocol: players, a trainer, "
        "monitors",
    )
    serve.add_argument(
        "--field-preset",
        default=SERVE_PRESET,
        help=f"{SERVE_FIELD} preset name, .toml or server.conf",
    )
    serve.add_argument("--seed", type=_index, default=0, help="seed of the server's noise")
    serve.add_argument(
        "--ball-noise", type=_noise, default=None, help="ball noise (preset's when not given)"
    )
    serve.add_argument(
        "--perfect-perception", action="store_true", help="sees without quantisation or fading"
    )
    serve.add_argument(
        "--host", default="127.0.0.1", help="address to bind (another than 127.0.0.1: on purpose)"
    )
    serve.add_argument("--port", type=_port, default=6000, help="player and monitor port")
    serve.add_argument("--trainer-port", type=_port, default=6001, help="trainer port")
    serve.add_argument("--olcoach-port", type=_port, default=6002, help="online-coach port")
    serve.add_argument(
        "--synch", action="store_true", help="synch mode: a cycle as soon as every client is done"
    )
    serve.add_argument(
        "--synch-timeout", type=_positive_float, default=1.25, help="synch: step anyway after [s]"
    )
    serve.add_argument(
        "--idle-timeout", type=_positive_float, default=30.0, help="drop a client silent for [s]"
    )
    serve.add_argument(
        "--play-on", action="store_true", help="start in play_on (default: before_kick_off)"
    )
    serve.add_argument("--cycles", type=_positive_int, default=None, help="stop after N cycles")
    serve.add_argument("--seconds", type=_positive_float, default=None, help="stop after [s]")
    serve.add_argument(
        "--record",
        type=Path,
        nargs="?",
        const=Path("recordings"),
        default=None,
        metavar="DIR",
        help="write the game as .rcg and .rrd into DIR (recordings/)",
    )
    serve.add_argument("--quiet", action="store_true", help="no log lines")
