"""The worlds: robot-physics (pymunk) and Soccer Server field models, shared records, presets.

This package imports no other package of the project, and no rerun, torch or scikit-learn
(DESIGN.md §3).
"""
