"""The results table on disk: one CSV row per trial, written and read with the ``csv`` module.

* Rows are :meth:`~robotsoccer.runs.runner.TrialResult.csv_fields` written by
  :func:`~robotsoccer.runs.runner.csv_record`: a reason holding commas, quotes or line ends is
  quoted and stays one field, so any CSV reader (``csv.DictReader``, pandas) reads the table.
* :class:`TableWriter` appends finished results and flushes them at once, so a killed run
  keeps every row it finished, at worst plus one row cut short.
* :func:`iter_results` reads a table back for a resumed run. An empty (0-byte) or header-only
  table holds no results. A last row cut short (no line end, or a quoted field still open at the
  end of the file) is what a kill leaves: it is dropped with a warning (and with ``repair``, cut
  off the file so appending goes on cleanly). Anything else that is not a result row, and a
  trial index seen twice, is refused with one line naming the file and the line.
"""

from __future__ import annotations

import csv
import os
import sys
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import BinaryIO

from robotsoccer.runs.runner import TrialResult, csv_record

TORN_LIMIT = 1 << 20
"""The most bytes a row cut short by a kill may hold [bytes]; a longer unfinished tail is not
what a killed write leaves (rows are at most a few kB), so it is refused, never dropped."""


class ResumeError(ValueError):
    """A results table cannot be resumed: another run made it, or it is damaged.

    A ValueError, so the CLI reports it as one line.
    """


class TableWriter:
    """Appends results to a table as they finish, each batch flushed at once.

    Args:
        path: The table.
        append: Keep the rows already there (a resumed run whose table :func:`iter_results`
            has checked); otherwise, or when the file is absent or empty, start it afresh
            with the header.
    """

    def __init__(self, path: Path, *, append: bool) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        fresh = not append or not path.exists() or path.stat().st_size == 0
        # newline="": the csv module writes its own line ends, inside quoted fields too
        self._file = path.open("w" if fresh else "a", encoding="utf-8", newline="")
        if fresh:
            self._file.write(csv_record(TrialResult.CSV_COLUMNS))
            self._file.flush()

    def write(self, results: Iterable[TrialResult]) -> None:
        """Append `results` and flush them to the file."""
        for result in results:
            self._file.write(csv_record(result.csv_fields()))
        self._file.flush()

    def close(self) -> None:
        """Close the file."""
        self._file.close()


def read_results(path: Path, warn: Callable[[str], None] | None = None) -> dict[int, TrialResult]:
    """Results already in a table, by index (:func:`iter_results`); an absent file holds none."""
    return {result.index: result for result in iter_results(path, warn)}


def iter_results(
    path: Path, warn: Callable[[str], None] | None = None, *, repair: bool = False
) -> Iterator[TrialResult]:
    """The results in a table, one at a time (a resumed run of any size reads it in passing).

    Args:
        path: The table; absent, empty or header-only, it holds no results.
        warn: Told about a last row cut short (default: a line on stderr).
        repair: Also cut such a row off the file. Only a run that holds the table's folder
            (:mod:`robotsoccer.runs.folders`) may: in a table being written, the last row may
            simply not be finished yet.

    Raises:
        ResumeError: The file does not start with the results header, a complete row does not
            parse, or a trial index appears twice (the message names the line).
    """
    if not path.exists():
        return
    warn = warn or _warn
    seen = _Seen()
    with path.open("rb") as raw:
        lines = _Lines(raw)
        reader = csv.reader(lines, strict=True)
        header = True
        while True:
            start, number = lines.offset, lines.number + 1
            try:
                fields = next(reader)
            except StopIteration:
                return
            except (csv.Error, UnicodeDecodeError) as exc:
                if not lines.at_end:
                    raise ResumeError(_not_a_row(path, number, exc)) from None
                fields = None  # a quoted field still open at the end: cut short
            if fields is None or not lines.ended:
                _cut_short(path, start, number, lines.offset, warn, repair)
                return
            if header:
                if tuple(fields) != TrialResult.CSV_COLUMNS:
                    raise ResumeError(
                        f"{path}: not a results table of this version (header {','.join(fields)!r})"
                    )
                header = False
                continue
            try:
                result = TrialResult.from_csv_fields(fields)
            except ValueError as exc:
                raise ResumeError(_not_a_row(path, number, exc)) from None
            if seen.add(result.index):
                raise ResumeError(f"{path}: line {number} repeats trial {result.index}")
            yield result


def _not_a_row(path: Path, number: int, why: Exception) -> str:
    return f"{path}: line {number} is not a result row ({why})"


def _cut_short(
    path: Path, start: int, number: int, size: int, warn: Callable[[str], None], repair: bool
) -> None:
    """Handle the unfinished record from byte `start` (line `number`) to the end, `size`."""
    if size - start > TORN_LIMIT:
        raise ResumeError(f"{path}: line {number} is not a result row (it runs unfinished to the "
                          f"end of the file, {size - start} bytes)")  # fmt: skip
    if repair:
        os.truncate(path, start)
        warn(f"{path}: dropped a last row cut short by an interrupted write (line {number})")
    else:
        warn(f"{path}: ignored a last row cut short (line {number}): interrupted or unfinished")


class _Lines:
    """A binary file's lines, decoded for ``csv.reader``, counting lines and bytes read.

    Lines are read as bytes so that the byte offset where each record starts is known (a row
    cut short is cut off there); ``csv.reader`` pulls lines one record at a time, never ahead.
    """

    def __init__(self, raw: BinaryIO) -> None:
        self.raw = raw
        self.offset = 0
        """Bytes read so far."""
        self.number = 0
        """Lines read so far."""
        self.ended = True
        """Whether the last line read ended with its line end."""
        self.at_end = False
        """Whether the end of the file was reached."""

    def __iter__(self) -> _Lines:
        return self

    def __next__(self) -> str:
        line = self.raw.readline()
        if not line:
            self.at_end = True
            raise StopIteration
        self.offset += len(line)
        self.number += 1
        self.ended = line.endswith(b"\n")
        # a write cut short may end inside a multi-byte character: that line is dropped anyway
        return line.decode("utf-8", errors="strict" if self.ended else "replace")


class _Seen:
    """Trial indices seen so far: one bit each up to a bound, a set beyond it."""

    DENSE = 1 << 28
    """Indices below this live in the bitmap (at most 32 MB), the rare others in a set."""

    def __init__(self) -> None:
        self.bits = bytearray()
        self.sparse: set[int] = set()

    def add(self, index: int) -> bool:
        """Mark `index` seen; return whether it had been seen before."""
        if index >= self.DENSE:
            before = index in self.sparse
            self.sparse.add(index)
            return before
        byte, bit = divmod(index, 8)
        if byte >= len(self.bits):
            self.bits.extend(bytes(max(byte + 1 - len(self.bits), len(self.bits))))
        before = bool(self.bits[byte] >> bit & 1)
        self.bits[byte] |= 1 << bit
        return before


def _warn(message: str) -> None:
    print(f"warning: {message}", file=sys.stderr)
