"""The boosted-trees pass evaluator: equal to scikit-learn's, saved as JSON, refused when bad."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from sklearn.ensemble import HistGradientBoostingClassifier

from learning.features import ModelFileError
from learning.pass_boost import fit_pass_boost, load_pass_boost, save_pass_boost
from learning.pass_tree import LABELS

NAMES = [f"a{i}" for i in range(6)]


@pytest.fixture(scope="module")
def data() -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(0)
    x = rng.normal(size=(600, 6))
    x[rng.random(x.shape) < 0.15] = np.nan
    a, b = np.nan_to_num(x[:, 0]), np.nan_to_num(x[:, 1])
    y = np.where(a > 0, "SUCCESS", np.where(b > 0.3, "FAILURE", "MISS"))
    return x, y


def test_probabilities_equal_scikit_learns_in_our_label_order(data) -> None:
    x, y = data
    ours = fit_pass_boost(x, y, NAMES, schema="s", seed=3, max_iter=40)
    theirs = HistGradientBoostingClassifier(max_iter=40, random_state=3).fit(x, y)
    columns = [list(theirs.classes_).index(label) for label in LABELS]
    np.testing.assert_allclose(
        ours.predict_proba(x), theirs.predict_proba(x)[:, columns], atol=1e-12
    )
    assert ours.success_confidence(x[0]) == pytest.approx(ours.predict_proba(x[0])[0])
    assert ours.n_trees == 40 * 3


def test_a_column_never_known_is_left_out(data) -> None:
    x, y = data
    wide = np.column_stack([x, np.full(len(x), np.nan)])
    model = fit_pass_boost(wide, y, [*NAMES, "never"], schema="s", max_iter=10)
    narrow = fit_pass_boost(x, y, NAMES, schema="s", max_iter=10)
    np.testing.assert_allclose(model.predict_proba(wide), narrow.predict_proba(x))
    assert not np.any(model.feature == len(NAMES))


def test_save_and_load_round_trip_and_bad_files_are_refused(data, tmp_path: Path) -> None:
    x, y = data
    model = fit_pass_boost(x, y, NAMES, schema="s", max_iter=10)
    path = save_pass_boost(model, tmp_path / "sub" / "boost.json", {"field_model": "soccer_server"})
    again, provenance = load_pass_boost(path, schema="s")
    np.testing.assert_array_equal(again.predict_proba(x), model.predict_proba(x))
    assert provenance == {"field_model": "soccer_server"}
    with pytest.raises(ModelFileError, match="schema"):
        load_pass_boost(path, schema="other")
    raw = json.loads(path.read_text())
    cases = {
        "cut.json": path.read_text()[:100],
        "tag.json": json.dumps({**raw, "format": "x"}),
        "shape.json": json.dumps({**raw, "left": raw["left"][:-1]}),
        "index.json": json.dumps({**raw, "left": [[10**6] * len(t) for t in raw["left"]]}),
    }
    for name, text in cases.items():
        bad = tmp_path / name
        bad.write_text(text)
        with pytest.raises(ModelFileError, match=name):
            load_pass_boost(bad)


def _strict(token: str) -> None:
    raise AssertionError(f"not strict JSON: {token}")


def test_saved_files_are_strict_json_and_infinite_thresholds_load_back(
    data, tmp_path: Path
) -> None:
    x, y = data
    model = fit_pass_boost(x, y, NAMES, schema="s", max_iter=10)
    assert np.isinf(model.threshold).any()  # scikit-learn splits unknowns off at +inf
    path = save_pass_boost(model, tmp_path / "boost.json", {})
    raw = json.loads(path.read_text(), parse_constant=_strict)
    assert raw["version"] == 2 and "Infinity" not in path.read_text().replace('"Infinity"', "")
    again, _ = load_pass_boost(path)
    np.testing.assert_array_equal(again.threshold, model.threshold)
    # A version-1 file (bare Infinity tokens, as written before) loads to the same model.
    old = {**raw, "version": 1, "threshold": model.threshold.tolist()}
    legacy = tmp_path / "legacy.json"
    legacy.write_text(json.dumps(old))
    assert "Infinity" in legacy.read_text()
    np.testing.assert_array_equal(load_pass_boost(legacy)[0].threshold, model.threshold)
    for name, threshold in (("word.json", "big"), ("nan.json", float("nan"))):
        bad = tmp_path / name
        bad.write_text(
            json.dumps({**raw, "threshold": [[threshold] * len(raw["left"][0])] * len(raw["left"])})
        )
        with pytest.raises(ModelFileError, match=name):
            load_pass_boost(bad)
    with pytest.raises(ValueError):
        save_pass_boost(model, tmp_path / "nan_provenance.json", {"noise": float("nan")})
