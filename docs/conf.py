"""Sphinx configuration of the stability documentation site.

Build (no network needed; intersphinx is off)::

    pip install -e ".[docs]"
    python -m sphinx -W --keep-going -n -b html docs docs/_build/html

The API reference (``api/``), the command-line reference and the validation
table are generated at build time by the local extensions in ``_ext/``; the
gallery (``gallery/``) is executed from ``gallery_src/`` by sphinx-gallery.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent))          # the working tree's package, not an installed copy

os.environ.setdefault("MPLBACKEND", "Agg")

import stability  # noqa: E402

project = "stability"
author = "the stability authors"
copyright = "2026, the stability authors"
release = version = stability.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "stability_api",          # _ext: API pages from each package's __all__, reference resolution
    "stability_cli",          # _ext: command-line reference from the argparse parsers
    "stability_validation",   # _ext: the validation table, computed at build time
    "stability_command_output",  # _ext: commands and their output, run at build time
    "stability_mathjax",      # _ext: MathJax copied into the site (no CDN: equations render offline)
    "stability_values",       # _ext: {docvalue}`group.key` and docvalue-table, computed at build time
]

# MathJax 3 from the site itself (docs/_ext/stability_mathjax.py copies it into _static/mathjax)
mathjax_path = "mathjax/tex-chtml.js"

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "examples/*.md", "gallery_src/README.rst", "**/sg_execution_times.rst"]
templates_path: list[str] = []

# --- Markdown (MyST): the notes in docs/ stay Markdown -----------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
myst_dmath_double_inline = True

# --- autodoc + numpydoc --------------------------------------------------------------------------
autodoc_typehints = "none"                 # numpydoc's Parameters sections carry the types and units
autodoc_member_order = "bysource"
autodoc_default_options = {"members": True}
numpydoc_show_class_members = False        # no member tables (they would need a page per member)
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

# --- gallery: executed at build time ---------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": "gallery_src",
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "abort_on_example_error": True,
    "download_all_examples": False,
    "remove_config_comments": True,
    "show_memory": False,
    "write_computation_times": False,
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "reset_modules": ("matplotlib",),
    "min_reported_time": 1,
}

# --- output ---------------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"stability {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_static_path: list[str] = []
html_show_sourcelink = False
html_copy_source = False

nitpicky = True
# Without intersphinx (no network in CI) references to other projects cannot resolve; they are the
# only references allowed to stay unresolved. Every stability.* reference must resolve.
nitpick_ignore_regex = [
    (r"py:.*", r"(control|numpy|np|scipy|matplotlib|sympy|numba|argparse|pathlib)(\..*)?"),
    (r"py:class", r"string"),   # argparse.ArgumentParser.error's inherited docstring
]

# Docstrings write an absolute value as |yaw rate| or |y|; in reST that is a substitution reference.
rst_epilog = """
.. |yaw rate| replace:: \\|yaw rate\\|
.. |y| replace:: \\|y\\|
"""


def _list_new_notes(app, docname, source):
    """Append to the index's "Topics" toctree every Markdown note in docs/ that no toctree of the
    index names yet, so a note another change adds is on the site (and -W does not fail on it)."""
    if docname != root_doc:
        return
    text = source[0]
    notes = sorted(p.stem for p in HERE.glob("*.md") if p.stem != root_doc)
    missing = [n for n in notes if not any(line.strip() == n for line in text.splitlines())]
    if missing:
        marker = ":caption: Topics\n\n"
        i = text.index(marker) + len(marker)
        source[0] = text[:i] + "".join(f"{n}\n" for n in missing) + text[i:]


def setup(app):
    app.connect("source-read", _list_new_notes)
