"""MathJax served with the site: the equations render without the network.

``sphinx.ext.mathjax`` loads MathJax from a CDN by default, so a site read
offline (or on a machine without internet) shows raw LaTeX.  This extension
copies MathJax 3 from the ``sphinx-mathjax-offline`` package (PyPI, in the
``docs`` extra; MathJax 3.2.2, Apache 2.0) into ``_static/mathjax`` of the
built site: the TeX-to-CommonHTML component that ``mathjax_path`` names (set
in ``conf.py``), the TeX extensions it loads on demand, the CommonHTML fonts,
the context menu and the accessibility modules it loads itself
(:data:`PARTS`, about 3 MB; the package's other components are not needed).
A missing package fails the build with the command that installs it, rather
than leaving the site on the CDN.
"""

from __future__ import annotations

import importlib.util
import shutil
from pathlib import Path
from typing import Any

#: The PyPI distribution that carries MathJax (its importable directory has the same name).
PACKAGE = "sphinx-mathjax-offline"
#: What ``mathjax_path`` names, relative to ``_static``.
MATHJAX_PATH = "mathjax/tex-chtml.js"
#: The files and folders of MathJax the site needs, relative to the package's ``static/mathjax``.
PARTS = ("tex-chtml.js", "input/tex/extensions", "output/chtml", "ui", "a11y", "sre/mathmaps/en.json",
         "sre/mathmaps/base.json")


def source() -> Path:
    """The package's MathJax folder.

    Returns
    -------
    Path

    Raises
    ------
    RuntimeError
        When the package is not installed (the message says how to install it).
    """
    spec = importlib.util.find_spec(PACKAGE)
    if spec is None or not spec.submodule_search_locations:
        raise RuntimeError(f"the documentation's equations need MathJax from the {PACKAGE!r} package: "
                           'pip install -e ".[docs]"')
    return Path(next(iter(spec.submodule_search_locations))) / "static" / "mathjax"


def copy_mathjax(outdir: Path) -> list[Path]:
    """Copy :data:`PARTS` of MathJax into ``outdir/_static/mathjax``.

    Parameters
    ----------
    outdir : Path
        The HTML builder's output folder.

    Returns
    -------
    list of Path
        The files and folders written.
    """
    src, dest = source(), outdir / "_static" / "mathjax"
    written = []
    for part in PARTS:
        s, d = src / part, dest / part
        if not s.exists():
            continue                          # an optional part this release does not ship
        d.parent.mkdir(parents=True, exist_ok=True)
        if s.is_dir():
            shutil.copytree(s, d, dirs_exist_ok=True)
        else:
            shutil.copy2(s, d)
        written.append(d)
    return written


def _build_finished(app: Any, exc: BaseException | None) -> None:
    if exc is None and app.builder.format == "html":
        copy_mathjax(Path(app.outdir))


def setup(app: Any) -> dict:
    source()                                  # fail early, with the install command, when MathJax is missing
    app.connect("build-finished", _build_finished)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
