"""``python -m robotsoccer.cli``: the console script."""

import sys

from robotsoccer.cli import main

sys.exit(main())
