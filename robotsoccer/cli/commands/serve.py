"""``robotsoccer serve``: the Soccer Server model on UDP in rcssserver's protocol.

The one command that names a field model's own modules (it serves that model), so
``tests/test_boundaries.py`` lets it.
"""

from __future__ import annotations

import argparse
import time
from typing import TYPE_CHECKING

from field_models.arena import FieldOptions

if TYPE_CHECKING:
    pass


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
