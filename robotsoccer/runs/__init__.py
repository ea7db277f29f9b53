"""Running trials: one, many in processes or on Ray, and what made a run's results.

:mod:`~robotsoccer.runs.runner` runs one trial, :mod:`~robotsoccer.runs.pool` many in processes
(Soccer Server interception trials as batches, :mod:`robotsoccer.drills.intercept_batch`),
:mod:`~robotsoccer.runs.ray_backend` the same chunks as Ray tasks, and
:mod:`~robotsoccer.runs.provenance` fingerprints what made them.
"""
