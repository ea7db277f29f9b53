"""Results tables: valid CSV whatever the reason says, and a resume after a kill at any byte."""

from __future__ import annotations

import csv
import dataclasses

import pytest

import robotsoccer.runs.pool as pool
from robotsoccer.runs.pool import ResumeError, read_results, run_trials
from robotsoccer.runs.runner import TrialResult, TrialSpec
from robotsoccer.runs.table import TableWriter, iter_results

NASTY = (
    "ball past the defender, heading between the posts",
    'the "keeper" said: no',
    "two\nlines, and a comma",
    'all of it: ",\n"\r\n and a lone \r too',
    "",
    "ünïcödé → ok",
)
"""Reasons that broke the old table (commas, quotes, line ends) or may break a CSV reader."""


def results(n: int) -> list[TrialResult]:
    label = ("GOAL", "SAVE")
    data = (("travel_units", 0.5),)
    return [
        TrialResult(i, label[i % 2], NASTY[i % len(NASTY)], 10 + i, 0.1 * i, (0.1 * i, -3.0), data)
        for i in range(n)
    ]


def test_a_plain_row_is_written_as_before_and_any_row_reads_back() -> None:
    plain = TrialResult(7, "SAVE", "ball moving back", 18, 1.8, (12.2, -0.5), (("t_s", 0.8),))
    assert plain.csv_row() == "7,SAVE,18,1.8,12.2 -0.5,t_s=0.8,ball moving back"  # unchanged
    for result in results(len(NASTY)):
        assert TrialResult.from_csv_row(result.csv_row()) == result


def hostile(spec, indices):  # type: ignore[no-untyped-def]
    """The trials as they are, each reason made hostile."""
    return [
        dataclasses.replace(r, reason=f"{NASTY[r.index % 4]} | {r.reason}")
        for r in REAL_CHUNK(spec, indices)
    ]


REAL_CHUNK = pool.run_chunk

KINDS = {
    "shootout (robots)": TrialSpec(drill="shootout", field_model="robot_physics", seed=2),
    "intercept (server)": TrialSpec(drill="intercept", field_model="soccer_server", seed=2),
    "pass (server)": TrialSpec(drill="pass", field_model="soccer_server", seed=2),
    "setplay (server)": TrialSpec(drill="setplay", field_model="soccer_server", seed=2),
    "match (server)": TrialSpec(drill="match", field_model="soccer_server", seed=2).with_options(
        left="baseline", right="baseline", half_time_s=1.0
    ),
}
"""Every drill's table: each writes other data and measures."""


@pytest.mark.parametrize("kind", list(KINDS))
def test_every_kind_of_results_table_reads_with_dictreader(tmp_path, monkeypatch, kind) -> None:
    monkeypatch.setattr(pool, "run_chunk", hostile)
    spec, path = KINDS[kind], tmp_path / "results.csv"
    n = 2 if kind.startswith("match") else 4
    ran = run_trials(spec, n, workers=1, results_path=path, progress=False, chunk_size=1)
    with path.open(newline="", encoding="utf-8") as table:
        reader = csv.DictReader(table)
        rows = list(reader)
    assert tuple(reader.fieldnames or ()) == TrialResult.CSV_COLUMNS
    assert len(rows) == n
    for row, result in zip(rows, ran, strict=True):
        assert None not in row and None not in row.values()  # no field too many or too few
        assert row["reason"] == result.reason and int(row["index"]) == result.index
        assert row["measures"] == " ".join(f"{k}={v!r}" for k, v in result.measures)
    back = read_results(path)  # (compared as rows: the pass drill records NaNs)
    assert [back[r.index].csv_row() for r in ran] == [r.csv_row() for r in ran]


def table_bytes(tmp_path, rows: list[TrialResult]) -> bytes:
    path = tmp_path / "whole.csv"
    writer = TableWriter(path, append=False)
    writer.write(rows)
    writer.close()
    return path.read_bytes()


def test_a_table_cut_at_any_byte_resumes_to_the_same_table(tmp_path) -> None:
    rows = results(8)
    whole = table_bytes(tmp_path, rows)
    header = len(TrialResult.CSV_HEADER) + 1
    ends = [header]  # where each row ends, in bytes
    for row in rows:
        ends.append(ends[-1] + len((row.csv_row() + "\n").encode()))
    assert ends[-1] == len(whole)
    path = tmp_path / "cut.csv"
    for cut in range(len(whole) + 1):
        path.write_bytes(whole[:cut])
        warnings: list[str] = []
        kept = list(iter_results(path, warnings.append, repair=True))
        complete = sum(end <= cut for end in ends[1:])
        assert kept == rows[:complete], cut
        assert len(warnings) == (cut not in (0, *ends)), cut  # only a cut row is news
        boundary = max([0] + [end for end in ends if end <= cut])
        assert path.read_bytes() == whole[:boundary], cut
        writer = TableWriter(path, append=True)  # what the resumed run appends
        writer.write(rows[complete:])
        writer.close()
        assert path.read_bytes() == whole, cut


def test_an_empty_or_header_only_table_resumes_as_empty(tmp_path) -> None:
    spec = TrialSpec(drill="intercept", field_model="soccer_server", seed=5)
    reference = run_trials(spec, 6, workers=1, results_path=tmp_path / "ref.csv", progress=False)
    for name, text in (("empty", ""), ("header", TrialResult.CSV_HEADER + "\n"),
                       ("half a header", "index,lab")):  # fmt: skip
        path = tmp_path / f"{name}.csv"
        run_trials(spec, 1, workers=1, results_path=path, progress=False)  # its manifest
        path.write_text(text)
        again = run_trials(spec, 6, workers=1, results_path=path, resume=True, progress=False)
        assert again == reference, name
        assert path.read_bytes() == (tmp_path / "ref.csv").read_bytes(), name


def test_repeated_or_damaged_rows_are_refused_naming_the_line(tmp_path) -> None:
    rows = results(4)
    whole = table_bytes(tmp_path, rows).decode()
    lines = whole.split("\n")
    path = tmp_path / "t.csv"
    repeated = whole + rows[1].csv_row() + "\n"
    path.write_text(repeated)
    number = repeated.count("\n")  # the repeat is the last line
    with pytest.raises(ResumeError, match=f"t.csv: line {number} repeats trial 1"):
        read_results(path)
    old_style = whole + "9,SAVE,3,0.3,,,a reason, with a comma\n"  # the old, unquoted writer
    path.write_text(old_style)
    number = old_style.count("\n")
    with pytest.raises(ResumeError, match=f"line {number} is not a result row .8 fields, not 7"):
        read_results(path)
    path.write_text("\n".join([*lines[:2], "garbage", *lines[2:]]))
    with pytest.raises(ResumeError, match="line 3 is not a result row"):
        read_results(path)
    path.write_text(whole.replace("index,label", "index,labels"))
    with pytest.raises(ResumeError, match="not a results table"):
        read_results(path)
    path.write_text(whole + "-1,SAVE,3,0.3,,,x\n")
    with pytest.raises(ResumeError, match="index '-1'"):
        read_results(path)
