"""Test-suite settings shared by every test module.

Property tests (hypothesis) run a fixed sequence of examples under CI (``CI`` set, as
``.ci/run`` does), so a run's verdict depends on the code alone, like the trials'; on a
developer's machine they draw fresh examples each run and so keep exploring.
"""

from __future__ import annotations

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, print_blob=True)
settings.register_profile("explore", print_blob=True)
settings.load_profile("ci" if os.environ.get("CI") else "explore")
