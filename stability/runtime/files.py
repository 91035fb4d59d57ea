"""Atomic file output: reproducible multi-page PDFs, single figures and text files.

Every file the toolkit writes goes through this module: it appears only when
it is complete (written to a temporary file in the same directory, then
renamed), and PDFs are byte-reproducible (no creation or modification dates
in the metadata, fixed producer string; matplotlib honours
``SOURCE_DATE_EPOCH``).  A multi-page PDF may carry an outline (bookmarks),
appended as a PDF incremental update (ISO 32000-1, 7.5.6 and 12.3.3).
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import re
import tempfile
from collections.abc import Callable, Iterable, Iterator, Sequence
from pathlib import Path
from typing import Any

from stability.runtime import interrupts, readfiles

__all__ = ["json_text", "with_tire_range", "distinct_notes", "atomic_path", "write_error", "failed_write",
           "WRITE_ERRNOS", "write_pdf", "save_figure", "atomic_write_text", "PDF_METADATA", "add_outline",
           "read_outline"]

#: metadata of every PDF written (no dates: byte-identical output for identical input)
PDF_METADATA = {"Author": "stability", "Creator": "stability", "Producer": "stability",
                "CreationDate": None, "ModDate": None}


#: Write failures reported as one line naming the output file (disk full, read-only, no permission, quota,
#: file too large, I/O error).
WRITE_ERRNOS = frozenset(getattr(errno, n) for n in ("ENOSPC", "EROFS", "EACCES", "EPERM", "EDQUOT", "EFBIG", "EIO")
                         if hasattr(errno, n))


def failed_write(exc: BaseException) -> OSError | None:
    """The write failure behind ``exc``, if any: ``exc`` itself or an OSError in its chain of causes.

    A writer may fail a second time while it cleans up after a full disk
    (matplotlib's PDF backend raises ``AttributeError`` from ``close``);
    the first failure is the one to report.

    Parameters
    ----------
    exc : BaseException

    Returns
    -------
    OSError or None
        An OSError with an errno of :data:`WRITE_ERRNOS`, else None.
    """
    seen = set()
    e: BaseException | None = exc
    while e is not None and id(e) not in seen:
        seen.add(id(e))
        if isinstance(e, OSError) and e.errno in WRITE_ERRNOS:
            return e
        e = e.__cause__ or e.__context__
    return None


def write_error(exc: OSError, path: str | os.PathLike[str]) -> OSError:
    """``exc`` (raised while writing a temporary file for ``path``) as an error naming ``path`` itself.

    Parameters
    ----------
    exc : OSError
        The failure; its errno is kept.
    path : path-like
        The output file the user asked for.

    Returns
    -------
    OSError
        ``OSError(errno, "cannot write: <reason>", path)``.
    """
    reason = exc.strerror or str(exc) or type(exc).__name__
    return OSError(exc.errno, f"cannot write: {reason}", os.fspath(path))


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[str]:
    """Yield a temporary file name next to ``path``; rename it to ``path`` on success.

    On any exception (a signal included, see :mod:`stability.runtime.interrupts`) the
    temporary file is removed and ``path`` is untouched; a write failure
    (:data:`WRITE_ERRNOS`) is raised as an :class:`OSError` naming ``path``.
    A file the process has read as an input (:func:`stability.runtime.readfiles.was_read`)
    is never replaced.

    Parameters
    ----------
    path : path-like
        Output file.

    Yields
    ------
    str
        The temporary file name to write.

    Raises
    ------
    ValueError
        ``path`` is a file this run has read (an input is never overwritten).
    OSError
        The file cannot be written; ``filename`` is ``path``.
    """
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    if not directory.exists():
        raise ValueError(f"output directory {str(directory)!r} does not exist")
    if readfiles.was_read(path):
        raise ValueError(f"output {str(path)!r} is a file this run reads; an input is never overwritten")
    try:
        fd, tmp = tempfile.mkstemp(dir=directory, prefix=f".{path.name}.", suffix=".tmp")
    except OSError as exc:
        raise write_error(exc, path) from exc
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the usual permissions
    try:
        yield tmp
        interrupts.check()
        os.replace(tmp, path)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        failed = failed_write(exc) if not isinstance(exc, KeyboardInterrupt) else None
        if failed is not None and failed.filename in (None, tmp):
            raise write_error(failed, path) from exc
        raise


def _pyplot():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def write_pdf(figures: Iterable, path: str | os.PathLike[str], *, title: str = "stability report",
              close: bool = True, on_page: Callable[[int], None] | None = None,
              outline: Sequence[tuple[str, int]] | Callable[[], Sequence[tuple[str, int]]] | None = None) -> Path:
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
    outline : sequence of (str, int), or a callable returning one, optional
        Bookmarks: title and 0-based page index, in order (see
        :func:`add_outline`).  A callable is called after the last page.

    Returns
    -------
    pathlib.Path
        ``path``.
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
        entries = outline() if callable(outline) else outline
        if entries:
            add_outline(tmp, entries)
    return Path(path)


def _pdf_text(s: str) -> bytes:
    """A PDF text string: literal when printable ASCII, else UTF-16BE with a byte-order mark (hex)."""
    if all(32 <= ord(ch) < 127 for ch in s):
        return b"(" + s.replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)").encode("ascii") + b")"
    return b"<FEFF" + s.encode("utf-16-be").hex().upper().encode("ascii") + b">"


def add_outline(path: str | os.PathLike[str], entries: Sequence[tuple[str, int]]) -> None:
    """Append a flat outline (bookmarks) to a PDF written by matplotlib, as an incremental update.

    The original bytes are kept; new objects (the outline and its items),
    the catalog redefined with ``/Outlines`` and ``/PageMode /UseOutlines``,
    a cross-reference section and a trailer pointing back (``/Prev``) are
    appended.  Deterministic: the same input gives the same bytes.

    Parameters
    ----------
    path : path-like
        A PDF with a classic cross-reference table (as matplotlib writes).
    entries : sequence of (str, int)
        Title and 0-based page index of each bookmark, in order.
    """
    data = Path(path).read_bytes()
    tail = data[data.rindex(b"trailer"):]
    size = int(re.search(rb"/Size (\d+)", tail).group(1))          # type: ignore[union-attr]
    root = int(re.search(rb"/Root (\d+) 0 R", tail).group(1))      # type: ignore[union-attr]
    info = re.search(rb"/Info (\d+) 0 R", tail)
    prev = int(re.search(rb"startxref\s+(\d+)", tail).group(1))   # type: ignore[union-attr]
    cat = re.search(rb"(?<![0-9])%d 0 obj\s*<<(.*?)>>\s*endobj" % root, data, re.S)
    if cat is None or b"/Outlines" in cat.group(1):
        raise ValueError(f"{str(path)!r}: no plain catalog to add an outline to")
    pages_ref = int(re.search(rb"/Pages (\d+) 0 R", cat.group(1)).group(1))  # type: ignore[union-attr]
    pages = re.search(rb"(?<![0-9])%d 0 obj\s*<<.*?/Kids \[(.*?)\]" % pages_ref, data, re.S)
    kids = [int(k) for k in re.findall(rb"(\d+) 0 R", pages.group(1))]  # type: ignore[union-attr]
    n = len(entries)
    first = size + 1
    body = bytearray(data if data.endswith(b"\n") else data + b"\n")
    offsets: dict[int, int] = {}

    def obj(num: int, content: bytes) -> None:
        offsets[num] = len(body)
        body.extend(b"%d 0 obj\n<< " % num + content + b" >>\nendobj\n")

    obj(size, b"/Type /Outlines /First %d 0 R /Last %d 0 R /Count %d" % (first, size + n, n))
    for i, (title, page_index) in enumerate(entries):
        if not 0 <= page_index < len(kids):
            raise ValueError(f"outline entry {title!r}: page index {page_index} not in 0..{len(kids) - 1}")
        links = (b" /Prev %d 0 R" % (first + i - 1) if i else b"") + \
            (b" /Next %d 0 R" % (first + i + 1) if i < n - 1 else b"")
        obj(first + i, b"/Title " + _pdf_text(title) + b" /Parent %d 0 R" % size + links
            + b" /Dest [ %d 0 R /Fit ]" % kids[page_index])
    obj(root, cat.group(1).strip() + b" /Outlines %d 0 R /PageMode /UseOutlines" % size)
    xref = len(body)
    body.extend(b"xref\n0 1\n0000000000 65535 f \n%d 1\n%010d 00000 n \n" % (root, offsets[root]))
    body.extend(b"%d %d\n" % (size, n + 1))
    for num in range(size, size + n + 1):
        body.extend(b"%010d 00000 n \n" % offsets[num])
    body.extend(b"trailer\n<< /Size %d /Root %d 0 R" % (size + n + 1, root)
                + (b" /Info %d 0 R" % int(info.group(1)) if info else b"")
                + b" /Prev %d >>\nstartxref\n%d\n%%%%EOF\n" % (prev, xref))
    Path(path).write_bytes(bytes(body))


def read_outline(path: str | os.PathLike[str]) -> list[tuple[str, int]]:
    """The flat outline written by :func:`add_outline`: (title, 0-based page index) in order.

    Parameters
    ----------
    path : path-like

    Returns
    -------
    list of (str, int)
        Empty when the PDF has no such outline.
    """
    data = Path(path).read_bytes()
    pages = re.search(rb"/Type /Pages\s*/Kids \[(.*?)\]", data, re.S)
    kids = [int(k) for k in re.findall(rb"(\d+) 0 R", pages.group(1))] if pages else []
    out = []
    for m in re.finditer(rb"/Title (\((?:\\.|[^\\)])*\)|<FEFF[0-9A-F]*>) /Parent \d+ 0 R.*?/Dest \[ (\d+) 0 R", data):
        raw = m.group(1)
        if raw.startswith(b"<"):
            title = bytes.fromhex(raw[5:-1].decode()).decode("utf-16-be")
        else:
            title = re.sub(rb"\\(.)", rb"\1", raw[1:-1]).decode("ascii")
        out.append((title, kids.index(int(m.group(2)))))
    return out


def save_figure(fig, path: str | os.PathLike[str], *, title: str = "stability figure",
                close: bool = False) -> Path:
    """Save one figure atomically in the format named by the file suffix (PDF reproducible).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : path-like
        Output file; the suffix names the format.
    title : str
        PDF title metadata.
    close : bool
        Close the figure after saving.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    kwargs = {"metadata": {"Title": title, **PDF_METADATA}} if fmt == "pdf" else {}
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=fmt, **kwargs)
    if close:
        _pyplot().close(fig)
    return path


def atomic_write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write text to ``path`` atomically (temporary file in the same directory + rename).

    Parameters
    ----------
    path : path-like
        Output file.
    text : str
        Text to write.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    with atomic_path(path) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
    return Path(path)


def json_text(data: Any) -> str:
    """``data`` as the JSON text the commands print (indent 2; NaN and infinity refused; numpy values as numbers).

    Parameters
    ----------
    data : Any
        JSON-serialisable result.

    Returns
    -------
    str
    """
    return json.dumps(data, indent=2, allow_nan=False, default=_json_default)


def _json_default(x: Any) -> Any:
    import numpy as np

    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError(f"{type(x).__name__} is not JSON serialisable")


def distinct_notes(notes: list) -> list:
    """Tire-range notes without the wheel-less repeats of a note already given per wheel.

    Parameters
    ----------
    notes : list of RangeNote
        As collected by :func:`stability.tires.collect_notes`.

    Returns
    -------
    list of RangeNote
    """
    placed = {(n.tire, n.quantity, round(n.value, 6)) for n in notes if n.wheel}
    return [n for n in notes if n.wheel or (n.tire, n.quantity, round(n.value, 6)) not in placed]


def with_tire_range(data: Any, notes: list | None, policy: str | None) -> Any:
    """``data`` with the ``tire_range`` entry every JSON output carries: the policy and the distinct notes.

    Parameters
    ----------
    data : Any
        The result; only a dict gains the entry.
    notes : list of RangeNote or None
        Notes collected while computing (:func:`stability.tires.collect_notes`); None: no entry.
    policy : str or None
        The tire-range policy used (``"warn"``, ``"clamp"`` or ``"raise"``).

    Returns
    -------
    Any
        A new dict with ``tire_range``, or ``data`` unchanged.
    """
    if isinstance(data, dict) and notes is not None:
        return {**data, "tire_range": {"policy": policy, "notes": [n.to_dict() for n in distinct_notes(notes)]}}
    return data
