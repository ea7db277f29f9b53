"""Every benchmark figure, as `robotsoccer bench --json` prints it."""

from __future__ import annotations

import json
import sys

from robotsoccer.bench import run_benchmarks

if __name__ == "__main__":
    print(json.dumps(run_benchmarks(quick="--quick" in sys.argv), indent=2))
