"""Run ``python -m stability.app`` (see :mod:`stability.app.server`)."""

import sys

from stability.app.server import main

if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
