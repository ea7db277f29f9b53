"""Synch-mode cycles per second of a served Soccer Server over UDP, beside the in-process arena.

1 trainer + 2 player clients (the project's minimal client) against ``serve``'s game in synch
mode, and the same two chasing minds on the in-process Soccer Server arena; the ratio is
wire / in-process. Prints JSON; medians of 3 repeats. The measuring code is
`field_models/rcssserver/bench.py`, shared with `robotsoccer bench` (``rcssserver.*``).
"""

from __future__ import annotations

import json

from field_models.rcssserver.bench import benchmarks

if __name__ == "__main__":
    print(json.dumps(benchmarks(quick=False), indent=2))
