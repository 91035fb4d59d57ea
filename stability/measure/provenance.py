"""The provenance table of a chair derived from a measurement sheet, as TOML comments the chair file starts with.

Each derived field with its value, standard uncertainty, the readings it used and its formula in words
(:class:`stability.measure.sheet.ProvenanceRow`), then the notes (docs/measure.md shows one).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from stability.measure.sheet import SheetResult

__all__ = ["provenance_comment"]


def provenance_comment(result: SheetResult, source: str = "") -> str:
    """The provenance table as TOML comment lines (field = value +- std <- readings: formula).

    Parameters
    ----------
    result : SheetResult
        An evaluated sheet.
    source : str, optional
        Name of the sheet file, shown in the first line; default none.

    Returns
    -------
    str
        Comment lines starting with ``#``, ending with a newline, then one
        ``# note:`` line per note.
    """
    lines = [f"# derived by python -m stability.measure{' from ' + source if source else ''}",
             "# field = value +- standard uncertainty (first order); readings used; formula"]
    for row in result.provenance:
        lines.append(f"#   {row.field} = {row.value:.6g} +- {row.std:.2g}  <- {', '.join(row.readings) or '-'}")
        lines.append(f"#       {row.formula}")
    for note in result.notes:
        lines.append(f"# note: {note}")
    return "\n".join(lines) + "\n"
