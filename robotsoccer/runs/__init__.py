"""Running trials: one, many in processes, and what made a run's results.

:mod:`~robotsoccer.runs.runner` runs one trial, :mod:`~robotsoccer.runs.pool` many in processes,
:mod:`~robotsoccer.runs.provenance` fingerprints what made them.
"""
