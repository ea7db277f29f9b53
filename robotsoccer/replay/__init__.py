"""Replaying runs: rerun recordings and paper-style text traces.

:mod:`~robotsoccer.replay.recording` writes and reads rerun files; :mod:`~robotsoccer.replay.trace`
prints a trial as the paper's Figure 4 does.
"""
