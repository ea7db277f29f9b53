"""The conformance suite (field_models.checker) on every registered field model and preset."""

from __future__ import annotations

import dataclasses

import pytest

from field_models.arena import BallLaw
from field_models.checker import CHECKS, ConformanceError, check_facts
from field_models.registry import (
    DEFAULT_OPTIONS,
    FIELD_MODELS,
    conformance_limits,
    entry,
    field_facts,
    shipped_presets,
)

CASES = [(model, preset) for model in FIELD_MODELS for preset in shipped_presets(model)]


@pytest.mark.parametrize("check", CHECKS, ids=lambda c: c.__name__)
@pytest.mark.parametrize(("model", "preset"), CASES, ids=str)
def test_every_field_model_conforms(check, model: str, preset: str) -> None:
    skip_unavailable(model, preset)
    why = conformance_limits(model, preset).get(check.__name__)
    if why is not None:
        pytest.skip(f"{model} {preset}: {check.__name__}: {why}")
    check(model, preset)


def skip_unavailable(model: str, preset: str) -> None:
    """Skip, saying why, a preset whose server is not on this machine (a real rcssserver).

    The ``rcssserver`` model's ``binary`` preset runs when ``RCSSSERVER`` names an executable.
    """
    module = entry(model)
    reason = getattr(module, "unavailable", None)
    why = reason(module.load(preset, DEFAULT_OPTIONS)) if reason is not None else None
    if why is not None:
        pytest.skip(f"{model} {preset}: {why}")


def test_a_broken_promise_is_reported_with_the_model_name(monkeypatch) -> None:
    facts = field_facts("robot_physics")
    speeding = BallLaw("constant", facts.dt_s, decel_mps2=-1.0)  # a ball that speeds up
    broken = dataclasses.replace(facts, ball=speeding)
    monkeypatch.setattr("field_models.checker.field_facts", lambda *args: broken)
    with pytest.raises(ConformanceError, match="robot_physics: a free ball must slow down"):
        check_facts("robot_physics")


def test_only_a_real_server_is_excused_a_promise() -> None:
    """The served preset keeps every promise; binary is excused determinism, and fading."""
    assert conformance_limits("rcssserver", "served") == {}
    assert set(conformance_limits("rcssserver", "binary")) == {"check_determinism", "identity"}
    for model in FIELD_MODELS:
        if model != "rcssserver":
            assert all(conformance_limits(model, p) == {} for p in shipped_presets(model))
