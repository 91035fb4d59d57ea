"""Atomic file output: reproducible multi-page PDFs, single figures and text files.

Every file the toolkit writes goes through this module: it appears only when
it is complete (written to a temporary file in the same directory, then
renamed), and PDFs are byte-reproducible (no creation or modification dates
in the metadata, fixed producer string; matplotlib honours
``SOURCE_DATE_EPOCH``).
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

__all__ = ["atomic_path", "write_pdf", "save_figure", "atomic_write_text", "PDF_METADATA"]

#: metadata of every PDF written (no dates: byte-identical output for identical input)
PDF_METADATA = {"Author": "stability", "Creator": "stability", "Producer": "stability",
                "CreationDate": None, "ModDate": None}


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[str]:
    """Yield a temporary file name next to ``path``; rename it to ``path`` on success.

    On any exception the temporary file is removed and ``path`` is untouched.
    """
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    if not directory.exists():
        raise ValueError(f"output directory {str(directory)!r} does not exist")
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the usual permissions
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _pyplot():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


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
    plt = _pyplot()
    from matplotlib.backends.backend_pdf import PdfPages

    with atomic_path(path) as tmp:
        with PdfPages(tmp, metadata={"Title": title, **PDF_METADATA}) as pdf:
            for i, fig in enumerate(figures, start=1):
                pdf.savefig(fig)
                if close:
                    plt.close(fig)
                if on_page is not None:
                    on_page(i)
    return Path(path)


def save_figure(fig, path: str | os.PathLike[str], *, title: str = "stability figure",
                close: bool = False) -> Path:
    """Save one figure atomically in the format named by the file suffix (PDF reproducible)."""
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    kwargs = {"metadata": {"Title": title, **PDF_METADATA}} if fmt == "pdf" else {}
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=fmt, **kwargs)
    if close:
        _pyplot().close(fig)
    return path


def atomic_write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write text to ``path`` atomically (temporary file in the same directory + rename)."""
    with atomic_path(path) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
    return Path(path)
