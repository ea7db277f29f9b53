"""Digest the content of recordings and game logs, to show a change left them identical.

A rerun file is not byte-for-byte reproducible: it carries a wall-clock ``log_time``, the
recording's start time and random ids (chunk and row ids, blueprint container ids). This
script reads every ``.rrd`` under a folder with rerun's reader, drops exactly those, masks ids
written as UUID text, and prints one SHA-256 per file for the data and one for the default
layout (blueprint); every other file (``.rcg`` game logs, tables) is digested byte for byte.
Two trees' digests of the same fixed-seed runs are equal when their content is.

Usage::

    python scripts/recording_digest.py FOLDER [--make]

``--make`` first writes a fixed set of recordings into FOLDER with the code on ``PYTHONPATH``:
two trials each of the intercept and pass drills and a 3 s-a-half match, on both field models
(the match on the Soccer Server also writes its ``.rcg``).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import re
import warnings
from pathlib import Path
from typing import Any

VOLATILE = ("log_time", "RecordingInfo:start_time", "ViewportBlueprint:root_container")
"""Columns that differ between two runs of the same code: wall clock and random ids."""
_UUID = re.compile(
    r"[0-9a-fA-F]{8}-?[0-9a-fA-F]{4}-?[0-9a-fA-F]{4}-?[0-9a-fA-F]{4}-?[0-9a-fA-F]{12}"
    r"|[0-9a-fA-F]{32}"
)


def make_recordings(folder: Path) -> None:
    """Write the fixed set of recordings (see the module docstring) into `folder`."""
    from robotsoccer.runs.runner import TrialSpec, run_trial

    for field in ("robot_physics", "soccer_server"):
        for drill in ("intercept", "pass"):
            out = folder / f"{drill}-{field}"
            spec = TrialSpec(drill=drill, field_model=field, seed=3, record_dir=str(out))
            for index in range(2):
                run_trial(_recorded(spec, index), index)
        match = TrialSpec(
            drill="match", field_model=field, seed=1, record_dir=str(folder / f"match-{field}")
        ).with_options(left="baseline", right="baseline", half_time_s=3.0)
        run_trial(_recorded(match, 0), 0)


def _recorded(spec: Any, index: int) -> Any:
    """`spec` recording trials up to `index` (a runner records the first ``record_trials``)."""
    import dataclasses

    return dataclasses.replace(spec, record_trials=index + 1)


def _store_rows(reader: Any, store: Any) -> list[str]:
    """Every chunk of a store as canonical text: entity path and columns, volatile ones out."""
    import pyarrow as pa

    rows = []
    for chunk in reader.stream(store=store).to_chunks():
        batch = chunk.to_record_batch()
        columns = {}
        for name in batch.schema.names:
            if "RowId" in name or name in VOLATILE:
                continue
            column = batch.column(name)
            if pa.types.is_duration(column.type) or pa.types.is_timestamp(column.type):
                column = column.cast("int64")  # ns durations do not fit datetime.timedelta
            columns[name] = column.to_pylist()
        text = json.dumps([chunk.entity_path, columns], default=str, sort_keys=True)
        rows.append(_UUID.sub("<id>", text))
    return sorted(rows)


def digest(folder: Path) -> dict[str, dict[str, Any]]:
    """Per file under `folder` (relative path): its content digests."""
    from rerun.chunk import RrdReader

    out: dict[str, dict[str, Any]] = {}
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        name = path.relative_to(folder).as_posix()
        if path.suffix != ".rrd":
            out[name] = {"bytes": hashlib.sha256(path.read_bytes()).hexdigest()}
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the reader warns on footer-less files
            reader = RrdReader(str(path))
            data = _store_rows(reader, None)
            blueprints = reader.blueprints()
            layout = _store_rows(reader, blueprints[0]) if blueprints else []
        out[name] = {
            "chunks": len(data),
            "data": hashlib.sha256("\n".join(data).encode()).hexdigest(),
            "blueprint": hashlib.sha256("\n".join(layout).encode()).hexdigest(),
        }
    return out


def main(argv: list[str] | None = None) -> None:
    """Make the recordings if asked, then print the digests as JSON."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", type=Path)
    parser.add_argument("--make", action="store_true", help="write the fixed recordings first")
    args = parser.parse_args(argv)
    if args.make:
        make_recordings(args.folder)
    elif not args.folder.is_dir():
        parser.error(f"{args.folder} is not a folder")
    print(json.dumps(digest(args.folder), indent=1, sort_keys=True))


if __name__ == "__main__":
    main()
