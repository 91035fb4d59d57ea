"""The committed reports in ``reports/`` are what the code at HEAD builds (issue 21: no stale reports).

Each committed PDF has its page texts beside it (``reports/NAME.txt``, written by ``--text``).  The
slow test rebuilds every report and compares the texts.  Error model: every number in a report is
printed rounded (3-4 significant figures); a value that differs in its last bits between processors
can round to a neighbouring last digit (one unit in the last printed digit).  The nonlinear measures
come from bracketing searches whose answer is defined to their 0.5 % bracket, and the critical push
itself is fuzzy over about 1 % (a run near the threshold can flip when its arithmetic changes in the
last bit, e.g. on another processor's instruction set), so a number may also differ by
2 % = 0.5 % + 1 % + margin.  On one machine the rebuild is bit-identical (observed difference 0).
Words must be identical.

Regenerate after a change that moves the reports::

    python tests/test_committed_reports.py
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
REPORTS = ROOT / "reports"

#: name -> command-line arguments of ``python -m stability.report`` (without -o / --text)
COMMITTED = {
    "ej-premier": ["--chair", "ej-premier"],
    "revised": ["--chair", "revised", "--compare", "ej-premier"],
    "ej-premier-front-caster": ["--chair", "ej-premier-front-caster", "--compare", "ej-premier"],
    "measured-chair": ["--chair", "docs/examples/measured_chair.toml",
                       "--uncertainty", "docs/examples/measured_chair.uncertainty.toml", "--compare", "ej-premier"],
}

#: Relative difference allowed between a committed and a rebuilt number (see the error model above).
RELATIVE = 0.02

_NUMBER = re.compile(r"[-+−]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


def _tokens(text: str) -> list[str]:
    return [t for t in re.split(r"(" + _NUMBER.pattern + r")|\s+", text) if t]


def _unit_in_last_digit(s: str) -> float:
    mant = re.split(r"[eE]", s)[0]
    exp = int(re.split(r"[eE]", s)[1]) if re.search(r"[eE]", s) else 0
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return 10.0 ** (exp - decimals)


def differences(committed: str, built: str) -> list[str]:
    """Where two report texts differ beyond the rounding error model (see the module docstring).

    Parameters
    ----------
    committed, built : str

    Returns
    -------
    list of str
        One line per difference (empty: the same report).
    """
    a, b = _tokens(committed), _tokens(built)
    if len(a) != len(b):
        return [f"token count {len(a)} vs {len(b)}"] + [f"{x!r} vs {y!r}" for x, y in zip(a, b, strict=False)
                                                          if x != y][:5]
    out = []
    for x, y in zip(a, b, strict=True):
        if x == y:
            continue
        if _NUMBER.fullmatch(x) and _NUMBER.fullmatch(y):
            fx, fy = (float(v.replace("−", "-")) for v in (x, y))
            if abs(fx - fy) <= max(1.0001 * _unit_in_last_digit(x), RELATIVE * abs(fx)):
                continue
        out.append(f"{x!r} vs {y!r}")
    return out


def test_differences_error_model():
    """The comparison passes a last-digit rounding flip and fails anything larger or any word change."""
    assert differences("speed 1.02 m/s, 3.22 N s", "speed 1.03 m/s, 3.22 N s") == []
    assert differences("speed 1.02 m/s", "speed 1.04 m/s") == []            # within 2 %
    assert differences("speed 1.02 m/s", "speed 1.10 m/s") == ["'1.02' vs '1.10'"]
    assert differences("speed 1.02 m/s", "speed 1.02 km/h") == ["'m/s' vs 'km/h'"]
    assert differences("page 3 of 20", "page 3 of 23")
    assert differences("=== page 1\nA", "=== page 1\nA\n=== page 2\nB")     # a page more


def build(name: str, out_dir: Path) -> tuple[Path, Path]:
    """Build the committed report ``name`` into ``out_dir``: (pdf, txt)."""
    pdf, txt = out_dir / f"{name}.pdf", out_dir / f"{name}.txt"
    subprocess.run([sys.executable, "-m", "stability.report", *COMMITTED[name], "--no-progress", "-o", str(pdf),
                    "--text", str(txt)], cwd=ROOT, check=True)
    return pdf, txt


#: The committed reports' chairs are manual chairs, pushed on their hand rims (the thesis's E&J Premier, its revised
#: design and front-caster variant, and the measured example of a manual chair): none has a motor.
MANUAL = {"ej-premier": True, "revised": True, "ej-premier-front-caster": True, "measured-chair": True}


@pytest.mark.parametrize("name", sorted(COMMITTED))
def test_committed_report_structure(name):
    """Issue 35: results (at most about 14 pages), then the appendix after its contents page; the pages that cannot
    apply decided from the chair's data (tests/report_structure.py), on the committed texts."""
    from report_structure import check_structure, read_text_dump

    from stability.chair.io import resolve

    args = COMMITTED[name]
    chair = resolve(str(ROOT / args[1]) if args[1].endswith(".toml") else args[1])
    check_structure(read_text_dump(REPORTS / f"{name}.txt"), chair, manual=MANUAL[name],
                    compare="--compare" in args, uncertainty="--uncertainty" in args)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(COMMITTED))
def test_committed_report_is_current(name, tmp_path):
    committed = REPORTS / f"{name}.txt"
    assert committed.exists() and (REPORTS / f"{name}.pdf").exists(), f"reports/{name} is not committed"
    _, txt = build(name, tmp_path)
    diff = differences(committed.read_text(encoding="utf-8"), txt.read_text(encoding="utf-8"))
    assert not diff, f"reports/{name} is stale (regenerate: python tests/test_committed_reports.py):\n" + \
        "\n".join(diff[:20])


if __name__ == "__main__":       # regenerate every committed report and its page-1 picture (docs/report.md)
    import shutil

    for n in sys.argv[1:] or sorted(COMMITTED):
        pdf, _ = build(n, REPORTS)
        print(f"reports/{n}.pdf")
        if shutil.which("pdftoppm"):
            stem = ROOT / "docs" / "images" / f"report-{n}-page1"
            subprocess.run(["pdftoppm", "-r", "80", "-png", "-singlefile", "-f", "1", "-l", "1", str(pdf),
                            str(stem)], check=True)
            print(f"{stem}.png")
