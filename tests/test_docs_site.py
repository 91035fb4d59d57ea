"""The documentation site: the API reference is complete and docs/architecture.md lists the real layout.

``test_inventory_has_every_public_name`` (marked ``docs``; CI runs it in its
docs step right after the build) reads the built ``objects.inv`` and fails
when any name in the ``__all__`` of a package or top-level module of
:mod:`stability` is missing from it. Without a built site
(``docs/_build/html``) it builds one first, without the gallery.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
BUILT = DOCS / "_build" / "html"
sys.path.insert(0, str(DOCS / "_ext"))

import stability_api  # noqa: E402  (docs/_ext: the extension that writes the API pages)


def _inventory(html: Path) -> set[str]:
    from sphinx.util.inventory import InventoryFile

    with open(html / "objects.inv", "rb") as f:
        inv = InventoryFile.load(f, "", lambda base, uri: uri)
    return {name for role, entries in inv.items() if role.startswith("py:") for name in entries}


@pytest.mark.docs
def test_inventory_has_every_public_name(tmp_path):
    pytest.importorskip("sphinx")
    html = BUILT
    if not (html / "objects.inv").exists():
        html = tmp_path / "html"
        subprocess.run([sys.executable, "-m", "sphinx", "-q", "-b", "html", "-D", "plot_gallery=0",
                        str(DOCS), str(html)], check=True, cwd=ROOT)
    names = _inventory(html)
    public = stability_api.public_names()
    missing = [f"{mod}.{name}" for mod, all_ in public.items() for name in all_ if f"{mod}.{name}" not in names]
    assert not missing, f"public names missing from the API reference: {missing}"
    assert sum(len(v) for v in public.values()) > 400      # the reference is not trivially empty


def test_public_modules_are_the_packages_and_top_level_modules():
    """The API reference covers every non-private package and top-level module that declares __all__."""
    mods = stability_api.public_modules()
    on_disk = {p.name if p.is_dir() else p.stem for p in (ROOT / "stability").iterdir()
               if not p.name.startswith("_") and (p.suffix == ".py" or (p / "__init__.py").exists())}
    assert {m.split(".")[1] for m in mods if "." in m} == on_disk
    assert mods[0] == "stability"


import validation_checks  # noqa: E402  (docs/_ext: the checks the validation page runs at build time)

_CHECKS = [(f, cheap) for f, cheap in validation_checks.CHECKS]


@pytest.mark.parametrize("check", [pytest.param(f, marks=() if cheap else pytest.mark.docs, id=f.__name__)
                                   for f, cheap in _CHECKS])
def test_validation_page_checks_pass(check):
    """Each check of the validation page (docs/validation-checks.md) agrees with its reference; the cheap
    ones run in the default suite, the simulation-based ones with the docs tests."""
    result = check()
    assert result.passed, result
