"""The layer-2 pass tree: C4.5 pruning numbers, agreement with scikit-learn, files, rendering."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest
from sklearn.tree import DecisionTreeClassifier

from learning.c45 import pessimistic_errors, upper_error_rate
from learning.features import ModelFileError
from learning.pass_tree import LABELS, PassTree
from learning.pass_tree_file import TREE_FORMAT, load_pass_tree, save_pass_tree
from learning.pass_tree_grow import fit_pass_tree

SCHEMA = "pass-attributes/test"
N_FEATURES = 12
NAMES = tuple(
    f"f{i} count" if i == 7 else f"f{i} distance" for i in range(N_FEATURES)
)  # f7 takes whole values, like the paper's "opponents ang6" counts


def _rule_data(
    n: int, rng: np.random.Generator, noise: float = 0.1
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]]:
    """SUCCESS iff f3 < 0.5; otherwise FAILURE when f7 >= 2 else MISS; `noise` of labels wrong."""
    x = rng.normal(size=(n, N_FEATURES))
    x[:, 3] = rng.random(n)
    x[:, 7] = rng.integers(0, 4, n)
    y = np.where(x[:, 3] < 0.5, 0, np.where(x[:, 7] >= 2, 1, 2))
    wrong = rng.random(n) < noise
    y[wrong] = (y[wrong] + rng.integers(1, 3, int(wrong.sum()))) % 3  # always another label
    unknown = rng.random(x.shape) < 0.1
    unknown[:, 0] = False  # one attribute never unknown in training (NaN then follows the majority)
    x[unknown] = np.nan
    return x, y.astype(np.intp)


@pytest.fixture(scope="module")
def rule_data() -> tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]]:
    return _rule_data(3000, np.random.default_rng(7))


@pytest.fixture(scope="module")
def held_out() -> tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]]:
    x, y = _rule_data(2000, np.random.default_rng(8))
    x[np.random.default_rng(9).random(x.shape[0]) < 0.1, 0] = np.nan  # unseen NaN column
    return x, y


@pytest.fixture(scope="module")
def tree(rule_data: tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]]) -> PassTree:
    x, y = rule_data
    return fit_pass_tree(x, [LABELS[i] for i in y], NAMES, schema=SCHEMA, seed=3)


# ----------------------------------------------------------------------------- C4.5 numbers


@pytest.mark.parametrize(
    ("cases", "errors", "rate"),
    [(6, 0, 0.206), (9, 0, 0.143), (16, 1, 0.157)],  # Quinlan 1993 ch. 4, congressional voting
)
def test_upper_error_rate_matches_quinlans_numbers(cases: int, errors: int, rate: float) -> None:
    assert upper_error_rate(cases, errors) == pytest.approx(rate, abs=5e-4)


def test_pessimistic_errors_follow_c45_addErrs_branches() -> None:
    assert pessimistic_errors(1, 0) == pytest.approx(0.75)  # 1 - 0.25^(1/1)
    zero, one = pessimistic_errors(10, 0), pessimistic_errors(10, 1)
    assert pessimistic_errors(10, 0.5) == pytest.approx(0.5 * (zero + one))  # linear in E < 1
    assert pessimistic_errors(2, 1.6) == pytest.approx(1.6 + 0.67 * 0.4)  # E + 0.5 >= N
    assert pessimistic_errors(0, 0) == 0.0
    # Smaller CF is more pessimistic.
    assert pessimistic_errors(20, 3, 0.1) > pessimistic_errors(20, 3, 0.25)
    with pytest.raises(ValueError, match="confidence"):
        pessimistic_errors(10, 1, 0.0)


@pytest.mark.parametrize(
    ("labels", "min_cases", "prunes"),
    [
        # 15 F | 1 S: leaf 16/1 predicts 2.51 errors, the split 15/0 + 1/0 only 1.32 + 0.75.
        (["FAILURE"] * 15 + ["SUCCESS"], 1, False),
        # 14 F | S F: the split predicts 1.32 + 1.80 = 3.12 errors, the leaf 16/1 only 2.51.
        (["FAILURE"] * 14 + ["SUCCESS", "FAILURE"], 2, True),
    ],
)
def test_a_split_is_pruned_exactly_when_c45_would(
    labels: list[str], min_cases: int, prunes: bool
) -> None:
    x = np.arange(16.0)[:, None]
    grown = fit_pass_tree(x, labels, ["a"], schema=SCHEMA, min_cases=min_cases, prune=False)
    assert grown.n_nodes == 3
    left, right = grown.counts[1], grown.counts[2]
    as_leaf = pessimistic_errors(16, 1)
    split = sum(pessimistic_errors(c.sum(), c.sum() - c.max()) for c in (left, right))
    assert bool(as_leaf <= split + 0.1) is prunes
    pruned = fit_pass_tree(x, labels, ["a"], schema=SCHEMA, min_cases=min_cases)
    assert pruned.n_nodes == (1 if prunes else 3)
    assert pruned.counts[0].tolist() == grown.counts[0].tolist()


def _kept_splits_are_worth_it(tree: PassTree, confidence: float) -> None:
    """Every kept test must beat its node as a leaf by more than C4.5's 0.1 margin."""

    def estimate(node: int) -> float:
        counts = tree.counts[node]
        as_leaf = pessimistic_errors(counts.sum(), counts.sum() - counts.max(), confidence)
        if tree.feature[node] < 0:
            return as_leaf
        subtree = estimate(int(tree.left[node])) + estimate(int(tree.right[node]))
        assert as_leaf > subtree + 0.1, f"node {node} should have been pruned"
        return subtree

    estimate(0)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_pruning_on_noise_never_grows_and_stronger_cf_collapses(seed: int) -> None:
    rng = np.random.default_rng(seed)
    x = rng.normal(size=(800, 10))
    x[rng.random(x.shape) < 0.1] = np.nan
    y = rng.choice(3, size=800, p=(0.6, 0.3, 0.1))
    names = [f"a{i}" for i in range(10)]
    grown = fit_pass_tree(x, y, names, schema=SCHEMA, seed=seed, prune=False)
    sizes = [
        fit_pass_tree(x, y, names, schema=SCHEMA, seed=seed, confidence=cf).n_nodes
        for cf in (0.25, 0.1, 0.01)
    ]
    assert grown.n_nodes > 50  # scikit-learn memorises the noise
    assert grown.n_nodes >= sizes[0] >= sizes[1] >= sizes[2]
    assert sizes[2] <= 3  # nothing to learn: a pessimistic enough CF leaves (almost) one leaf
    pruned = fit_pass_tree(x, y, names, schema=SCHEMA, seed=seed)
    assert pruned.n_nodes < grown.n_nodes
    _kept_splits_are_worth_it(pruned, 0.25)


def test_release8_charge_stops_splits_a_threshold_cannot_pay_for() -> None:
    # 40 cases, one attribute with 40 distinct values, labels that alternate in runs of 3: the
    # best cut gains a little, less than log2(39) / 40 = 0.13 bits, so release 8 would not split.
    x = np.arange(40.0)[:, None]
    y = ["SUCCESS" if (i // 3) % 2 else "FAILURE" for i in range(40)]
    grown = fit_pass_tree(x, y, ["a"], schema=SCHEMA, prune=False)
    assert grown.n_nodes > 3
    assert fit_pass_tree(x, y, ["a"], schema=SCHEMA).n_nodes == 1
    # A clean cut pays for its threshold many times over and stays.
    clean = ["SUCCESS"] * 20 + ["FAILURE"] * 20
    assert fit_pass_tree(x, clean, ["a"], schema=SCHEMA).n_nodes == 3


def test_success_confidence_is_the_laplace_share_at_the_leaf() -> None:
    x = np.arange(12.0)[:, None]
    y = ["SUCCESS"] * 6 + ["FAILURE"] * 6
    tree = fit_pass_tree(x, y, ["a"], schema=SCHEMA)
    assert tree.n_nodes == 3
    assert tree.success_confidence(np.array([0.0])) == pytest.approx((6 + 1) / (6 + 3))
    assert tree.success_confidence(np.array([11.0])) == pytest.approx(1 / (6 + 3))


# ----------------------------------------------------------------------------- learning


def test_known_rule_is_found_first(
    tree: PassTree,
    rule_data: tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]],
    held_out: tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]],
) -> None:
    x, y = rule_data
    assert tree.feature_names[int(tree.feature[0])] == "f3 distance"
    assert tree.threshold[0] == pytest.approx(0.5, abs=0.02)
    assert tree.counts[0].sum() == x.shape[0]
    assert int(tree.settings["n_nodes_unpruned"]) > tree.n_nodes
    _kept_splits_are_worth_it(tree, 0.25)
    # 10% of labels are wrong and 10% of f3 unknown: the held-out error cannot go much lower
    # than the noise, and a tree that learned the rule does not go much higher.
    hx, hy = held_out
    assert 0.08 < tree.training_error(hx, hy) < 0.22
    assert tree.training_error(x, y) <= tree.training_error(hx, hy)
    clear = np.full(N_FEATURES, np.nan)
    clear[3] = 0.1
    assert LABELS[int(tree.predict(clear))] == "SUCCESS"


def test_unpruned_tree_predicts_as_sklearn_does(
    rule_data: tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]],
    held_out: tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]],
) -> None:
    x, y = rule_data
    ours = fit_pass_tree(x, y, NAMES, schema=SCHEMA, seed=3, prune=False)
    theirs = DecisionTreeClassifier(criterion="entropy", min_samples_leaf=2, random_state=3)
    theirs.fit(x, y)
    assert ours.n_nodes == theirs.tree_.node_count
    hx, _ = held_out
    assert np.isnan(hx).any(axis=1).mean() > 0.5
    expected = theirs.predict_proba(hx)
    batch = ours.predict_proba(hx)
    assert batch.shape == (hx.shape[0], 3)
    np.testing.assert_allclose(batch, expected, rtol=0, atol=1e-12)
    rows = np.array([ours.predict_proba(row) for row in hx])
    np.testing.assert_array_equal(rows, batch)
    np.testing.assert_array_equal(ours.leaf_index(hx), [ours.leaf_index(r) for r in hx])


def test_one_row_and_batch_shapes(tree: PassTree) -> None:
    row = np.zeros(N_FEATURES)
    assert tree.predict_proba(row).shape == (3,)
    assert tree.predict_proba(row).sum() == pytest.approx(1.0)
    assert tree.predict(row).shape == ()
    assert tree.predict(np.zeros((4, N_FEATURES))).shape == (4,)
    probs = tree.predict_proba(row)
    probs[:] = 0.0  # a caller's copy: the tree is unchanged
    assert tree.predict_proba(row).sum() == pytest.approx(1.0)
    with pytest.raises(ValueError, match="n_features"):
        tree.predict_proba(np.zeros(N_FEATURES + 1))


@pytest.mark.parametrize(
    ("y", "kwargs", "message"),
    [
        (["SUCCESS", "WIN"], {}, "WIN"),
        (["SUCCESS"], {}, "labels"),
        (["SUCCESS", "MISS"], {"confidence": 1.0}, "confidence"),
        (["SUCCESS", "MISS"], {"min_cases": 0}, "min_cases"),
    ],
)
def test_bad_fit_arguments_are_refused(y: list[str], kwargs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        fit_pass_tree(np.zeros((2, 1)), y, ["a"], schema=SCHEMA, **kwargs)


def test_infinite_values_are_refused() -> None:
    with pytest.raises(ValueError, match="infinite"):
        fit_pass_tree(np.array([[0.0], [np.inf]]), ["SUCCESS", "MISS"], ["a"], schema=SCHEMA)


# ----------------------------------------------------------------------------- rendering

LEAF = re.compile(
    r"^(?: {4})*\S.* (?:<=|>) -?\d+(?:\.\d{1,3})?(?: \[or unknown\])? : [SFM] \(\d+\.\d/\d+\.\d\)$"
)
TEST = re.compile(r"^(?: {4})*\S.* (?:<=|>) -?\d+(?:\.\d{1,3})?(?: \[or unknown\])? :$")
KNOWN = re.compile(r"^(?: {4})*\S.* is (?:known|unknown) :(?: [SFM] \(\d+\.\d/\d+\.\d\))?$")


def test_render_reads_like_figure_14(tree: PassTree) -> None:
    lines = tree.render().splitlines()
    assert lines[0].startswith("f3 distance ")
    assert sum(1 for line in lines if line.startswith("f3 distance ")) == 2
    for line in lines:
        assert LEAF.match(line) or TEST.match(line) or KNOWN.match(line), line
    leaf_lines = [line for line in lines if line.endswith(")")]
    assert len(leaf_lines) == tree.n_leaves
    cases = sum(float(re.findall(r"\((\S+)/", line)[0]) for line in leaf_lines)
    assert cases == tree.counts[0].sum()
    # f7 is a count: C4.5 shows its cut as a training value (f7 <= 1), not the midpoint 1.5.
    count_tests = [line for line in lines if re.search(r"f7 count (<=|>)", line)]
    assert count_tests
    assert all(re.search(r"f7 count (<=|>) [0-3](?: |$)", line) for line in count_tests)


def test_render_marks_unknowns_and_cuts_depth(tree: PassTree) -> None:
    lines = tree.render().splitlines()
    root_side = 0 if tree.missing_left[0] else 1
    root_lines = [line for line in lines if line.startswith("f3 distance ")]
    marked = [("[or unknown]" in line) for line in root_lines]
    assert marked.count(True) == 1
    assert ("<=" in root_lines[marked.index(True)]) is (root_side == 0)
    short = tree.render(max_depth=1).splitlines()
    assert all(line.startswith("f3 distance ") or line == "    ..." for line in short)
    assert "    ..." in short
    assert tree.render(max_depth=0) == "..."


def test_render_of_a_single_leaf() -> None:
    leaf = fit_pass_tree(np.zeros((4, 1)), ["MISS"] * 3 + ["SUCCESS"], ["a"], schema=SCHEMA)
    assert leaf.n_nodes == leaf.n_leaves == 1
    assert leaf.render() == "M (4.0/1.0)"


# ----------------------------------------------------------------------------- files


def test_save_load_round_trip(
    tree: PassTree,
    held_out: tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]],
    tmp_path: Path,
) -> None:
    provenance: dict[str, str | int | float] = {
        "field_model": "soccer_server",
        "seed": 11,
        "ball_noise": 0.05,
    }
    path = save_pass_tree(tree, tmp_path / "tree.json", provenance)
    assert not (tmp_path / "tree.json.tmp").exists()
    back, notes = load_pass_tree(path, schema=SCHEMA)
    assert notes == provenance
    hx, _ = held_out
    np.testing.assert_array_equal(back.predict_proba(hx), tree.predict_proba(hx))
    for name in ("feature", "threshold", "left", "right", "missing_left", "counts"):
        np.testing.assert_array_equal(getattr(back, name), getattr(tree, name))
    assert back.render() == tree.render()
    assert back.settings == tree.settings
    assert back.feature_names == NAMES
    json.loads(path.read_text(encoding="utf-8"))  # plain JSON, nothing pickled


def test_inference_needs_no_sklearn_nor_the_simulators(tree: PassTree, tmp_path: Path) -> None:
    path = save_pass_tree(tree, tmp_path / "tree.json", {})
    code = (
        "import sys, numpy as np\n"
        "from learning.pass_tree_file import load_pass_tree\n"
        f"tree, _ = load_pass_tree({str(path)!r})\n"
        f"tree.predict_proba(np.zeros({N_FEATURES}))\n"
        "banned = ('sklearn', 'robotsoccer', 'field_models', 'torch', 'pymunk', 'rerun')\n"
        "print(sorted({m.split('.')[0] for m in sys.modules} & set(banned)))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def _edit(doc: dict[str, Any], key: str, value: Any) -> dict[str, Any]:
    return {**doc, key: value}


def _corruptions(doc: dict[str, Any]) -> dict[str, Any]:
    n = len(doc["feature"])
    internal = next(i for i, f in enumerate(doc["feature"]) if f >= 0)
    out_of_range = list(doc["left"])
    out_of_range[internal] = n + 5
    second_parent = list(doc["right"])
    second_parent[internal] = doc["left"][internal]
    bad_counts = [list(c) for c in doc["counts"]]
    bad_counts[0][0] += 1.0
    return {
        "truncated": json.dumps(doc)[:500],
        "garbage": "\x80\x04not json",
        "nan": json.dumps(doc).replace('"threshold": [', '"threshold": [NaN, ', 1),
        "format tag": _edit(doc, "format", "robotsoccer/interception-lookup"),
        "format version": _edit(doc, "format_version", 99),
        "labels": _edit(doc, "labels", ["SUCCESS", "FAILURE"]),
        "array lengths": _edit(doc, "threshold", doc["threshold"][:-1]),
        "node index": _edit(doc, "left", out_of_range),
        "two parents": _edit(doc, "right", second_parent),
        "feature index": _edit(doc, "feature", [len(NAMES), *doc["feature"][1:]]),
        "counts": _edit(doc, "counts", bad_counts),
        "no provenance": {k: v for k, v in doc.items() if k != "provenance"},
        "list": [doc],
    }


@pytest.mark.parametrize(
    "case",
    [
        "truncated",
        "garbage",
        "nan",
        "format tag",
        "format version",
        "labels",
        "array lengths",
        "node index",
        "two parents",
        "feature index",
        "counts",
        "no provenance",
        "list",
    ],
)
def test_bad_files_are_refused_naming_the_file(tree: PassTree, tmp_path: Path, case: str) -> None:
    good = save_pass_tree(tree, tmp_path / "good.json", {"seed": 1})
    doc = json.loads(good.read_text(encoding="utf-8"))
    content = _corruptions(doc)[case]
    path = tmp_path / "bad.json"
    text = content if isinstance(content, str) else json.dumps(content)
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ModelFileError, match=re.escape(str(path))):
        load_pass_tree(path)


def test_wrong_schema_and_missing_file_are_refused(tree: PassTree, tmp_path: Path) -> None:
    path = save_pass_tree(tree, tmp_path / "tree.json", {})
    with pytest.raises(ModelFileError, match=r"tree\.json.*pass-attributes/2"):
        load_pass_tree(path, schema="pass-attributes/2")
    with pytest.raises(ModelFileError, match="not found"):
        load_pass_tree(tmp_path / "absent.json")
    assert TREE_FORMAT in path.read_text(encoding="utf-8")


def test_provenance_must_be_scalars(tree: PassTree, tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="provenance"):
        save_pass_tree(tree, tmp_path / "t.json", {"seed": math.nan})
    with pytest.raises(ValueError, match="provenance"):
        save_pass_tree(tree, tmp_path / "t.json", {"ok": True})
    assert not (tmp_path / "t.json").exists()
