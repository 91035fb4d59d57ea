"""``python -m stability.report``: see :mod:`stability.report.command`."""

import sys

from stability.report.command import main

if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
