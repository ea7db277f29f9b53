"""What runs above the percept/action line: skills, drills, runs, experiments, replay, CLI.

It sees a field only through :class:`field_models.arena.Arena` and its facts, whatever the
field model (DESIGN.md §3).
"""

__version__ = "0.1.0"
