"""The system that runs: camera, host, link, firmware, drills, trial runner, recordings, CLI."""

__version__ = "0.1.0"
