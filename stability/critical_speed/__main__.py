"""Run ``python -m stability.critical_speed`` (see :mod:`stability.critical_speed.command`)."""

import sys

from stability.critical_speed.command import main

if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
