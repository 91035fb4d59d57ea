"""Atomic file output: reproducible multi-page PDFs (matplotlib ``PdfPages``) and text files.

Every report of the toolkit goes through :func:`write_pdf`: the same figures
give a byte-identical file (no creation or modification dates in the
metadata, fixed producer string, ``SOURCE_DATE_EPOCH`` respected by
matplotlib), and the file appears only when it is complete (written to a
temporary file in the same directory, then renamed).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Callable, Iterable

__all__ = ["write_pdf", "atomic_write_text"]


def write_pdf(figures: Iterable, path: str | os.PathLike[str], *, title: str = "stability report",
              close: bool = True, on_page: Callable[[int], None] | None = None) -> Path:
    """Write matplotlib figures as pages of one PDF, atomically and reproducibly.

    Parameters
    ----------
    figures : iterable of matplotlib.figure.Figure
        Pages in order (a generator is fine: pages are rendered one by one).
    path : path-like
        Output file.  Nothing is written at ``path`` if any page fails.
    title : str
        PDF title metadata.
    close : bool
        Close each figure after it is saved.
    on_page : callable, optional
        Called with the page number after each page (progress reporting).
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.backends.backend_pdf import PdfPages

    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    if not directory.exists():
        raise ValueError(f"output directory {str(directory)!r} does not exist")
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    meta = {"Title": title, "Author": "stability", "Creator": "stability", "Producer": "stability",
            "CreationDate": None, "ModDate": None}
    try:
        with PdfPages(tmp, metadata=meta) as pdf:
            for i, fig in enumerate(figures, start=1):
                pdf.savefig(fig)
                if close:
                    plt.close(fig)
                if on_page is not None:
                    on_page(i)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def atomic_write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write text to ``path`` atomically (temporary file in the same directory + rename)."""
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path
