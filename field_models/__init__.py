"""The worlds, each self-contained behind one interface: the robots and the Soccer Server.

* :mod:`~field_models.protocol` — percepts, actions, truth, pitch, the one angle wrap and the one
  goal-line rule; :mod:`~field_models.commands` — actions as client command text;
* :mod:`~field_models.arena` — the Arena interface and the facts a field tells the code above it;
* :mod:`~field_models.registry` — field models by name; :mod:`~field_models.seeding` — one seed
  per trial, named streams; :mod:`~field_models.presets` — TOML presets with clear errors;
* :mod:`~field_models.checker` — the conformance suite every field model passes;
* :mod:`~field_models.robot_physics`, :mod:`~field_models.soccer_server` — the two models.

This package imports no other package of the project, and no rerun, torch or scikit-learn
(DESIGN.md §3).
"""
