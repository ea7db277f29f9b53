"""Experiments that reproduce the paper's results: layer 1 (§5) and layer 2 (§6) end to end.

* :mod:`robotsoccer.experiments.layer1` — collect, train, evaluate, record, one output folder.
* :mod:`robotsoccer.experiments.layer2` — passes collected, the tree trained, Table 2's
  conditions run and reported on top of layer 1's net.
* :mod:`robotsoccer.experiments.plots_layer2` — Table 2 by confidence bin and the reliability
  plot as PNG.
* :mod:`robotsoccer.experiments.report` — markdown tables in the paper's layout, ours beside.
  Its layers: ``report_records`` (counts, rows, sections), ``report_cells`` (cells, paired
  statistics), ``report_tables`` (per-model tables), ``report_differences`` ("Where we differ").
* :mod:`robotsoccer.experiments.plots` — the Figure 7 and Figure 8 curves as PNG (matplotlib Agg).
* :mod:`robotsoccer.experiments.paper` — the paper's numbers as data.

Importing this package loads neither torch nor matplotlib; they load when training or plotting.
"""

from __future__ import annotations
