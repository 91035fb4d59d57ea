"""Run ``python -m stability.critical_speed`` (see :mod:`stability.critical_speed.command`)."""

import sys

from .command import main

sys.exit(main())
