"""A spec is resolved once: its field settings, facts and players, shared by every trial."""

from __future__ import annotations

import dataclasses

import pytest

from field_models.registry import field_facts
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import build_trial, run_trial
from robotsoccer.runs.spec import ResolvedSpec, TrialSpec, resolve

INTERCEPT = TrialSpec(drill="intercept", field_model="soccer_server", seed=4)


def test_resolving_adds_the_drills_settings_and_the_fields_facts() -> None:
    resolve.cache_clear()  # an equal spec resolved by an earlier test would be the one kept
    resolved = resolve(INTERCEPT)
    assert isinstance(resolved, ResolvedSpec) and resolved.spec is INTERCEPT
    assert resolved.options == INTERCEPT.field  # the paper's plan needs no other setting
    lead = resolve(INTERCEPT.with_options(decision="lead"))
    assert lead.options.all_landmarks is True  # the drill's own: the lead defender localises
    assert resolved.facts == field_facts("soccer_server", INTERCEPT.preset, resolved.options)
    assert len(resolved.players) == 2
    assert resolve(INTERCEPT) is resolved  # cached: once per spec and process
    with pytest.raises(dataclasses.FrozenInstanceError):
        resolved.players = ()  # type: ignore[misc]


def test_each_trial_gets_a_fresh_drill_on_the_resolved_field() -> None:
    resolved = resolve(INTERCEPT)
    _, first, arena = build_trial(INTERCEPT, 0)
    _, second, _ = build_trial(INTERCEPT, 1)
    assert first is not second and resolved.new_drill() is not first
    assert tuple(arena.players) == resolved.players


def test_a_run_resolves_its_spec_once() -> None:
    spec = dataclasses.replace(INTERCEPT, seed=11)
    resolve.cache_clear()
    results = run_trials(spec, 6, workers=1, progress=False)
    info = resolve.cache_info()
    assert len(results) == 6 and info.misses == 1  # the batched engine: one batch of 6
    assert results == [run_trial(spec, i) for i in range(6)]


def test_a_bad_spec_is_refused_when_resolved() -> None:
    with pytest.raises(ValueError, match="unknown drill"):
        resolve(TrialSpec(drill="nope", field_model="soccer_server"))
