"""``.. stability-validation::``: the validation table, computed when the site is built.

Runs every check of :data:`validation_checks.CHECKS` and renders one table
row per check (what is compared, the source, the reference value, the value
computed now, the criterion, the verdict). A failing check is rendered as
failing and logged as a warning, so a ``-W`` build stops.
"""

from __future__ import annotations

import time
from typing import Any

import validation_checks
from docutils import nodes
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective
from stability_values import table_row

logger = logging.getLogger(__name__)
COLUMNS = ("check", "source", "reference", "computed at build time", "criterion", "result")
WIDTHS = (22, 14, 20, 20, 12, 6)


class StabilityValidation(SphinxDirective):
    has_content = False

    def run(self) -> list[nodes.Node]:
        table = nodes.table(classes=["longtable"])
        group = nodes.tgroup(cols=len(COLUMNS))
        table += group
        for w in WIDTHS:
            group += nodes.colspec(colwidth=w)
        head = nodes.thead()
        head += table_row(list(COLUMNS))
        group += head
        body = nodes.tbody()
        group += body
        start = time.perf_counter()
        failed = 0
        for check, _cheap in validation_checks.CHECKS:
            c = check()
            failed += not c.passed
            body += table_row([c.name, c.source, c.reference, c.computed, c.criterion,
                               "agrees" if c.passed else "FAILS"])
            if not c.passed:
                logger.warning("validation check failed: %s: %s (reference %s)", c.name, c.computed, c.reference,
                               location=self.get_location())
        took = time.perf_counter() - start
        note = nodes.paragraph(text=f"{len(validation_checks.CHECKS)} checks, {failed} failing, computed in "
                                    f"{took:.0f} s when this page was built.")
        return [table, note]


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("stability-validation", StabilityValidation)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
