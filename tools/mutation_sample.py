"""Mutation score of a module with mutmut's mutation operators, bounded by a seeded sample (mutmut 2.5, dev extra).

``mutmut run`` tests every mutant of a file with a fresh test process, which on the shared 2-core machine costs
10-30 s a mutant (201 mutants in ``stability/linear/critical.py`` alone).  This runner enumerates the same
mutants (:func:`mutmut.list_mutations`, :func:`mutmut.mutate`: the operators ``mutmut run`` applies), draws a
seeded sample of them (or takes all, ``--all``), applies each to a private copy of the repository (``--work``; the
``.git`` directory is not copied; no bytecode written) and runs the module's fast tests there (``MODULES``, one
process, ``-x``).  It writes one JSON line per mutant (``--out``) so that a later run with ``--only-survivors``
re-tests only the survivors of an earlier one: the score after new tests is measured on the same mutants.

Usage (from the repository root, in the project's venv)::

    python tools/mutation_sample.py stability/linear/critical.py --sample 60 --out before_critical.jsonl
    python tools/mutation_sample.py stability/linear/critical.py --only-survivors before_critical.jsonl \\
        --out after_critical.jsonl

Exit status 0 when every mutant run is killed, 1 otherwise.

Measured for issue 34 (seed 34, 50 mutants of each file; tests of ``MODULES``; "before" = the tests of main at
61978c5, "after" = this branch):

* ``stability/linear/critical.py`` (201 mutants): 15/50 -> 32/50 killed; 8 equivalent, so 15/42 (36 %) -> 32/42
  (76 %) of the non-equivalent.  Equivalent: the finite-difference step's floor 1.0 -> 2.0 m/s in ``_slopes``
  (the slope moves by O(h^2) ~ 1e-12); ``abs(den) > 1e-14`` -> ``>=``, ``< 0.05 * scale`` -> ``<=`` and
  ``alpha(hi) > alpha(lo)`` -> ``>=`` (equality does not occur; at a bracket the two ends have opposite signs);
  brentq's ``maxiter`` 500 -> 501; the bounded maximiser's ``xatol`` option misspelt (scipy warns and uses 1e-5:
  the maximum's location only needs a positive value); the complex/real threshold ``> 1e-8 max(1, |l|)`` -> ``>=``
  or ``max(2, |l|)`` (only an eigenvalue with |Im| between 1e-8 and 2e-8 would change its word).  Not killed
  (missing tests, 10): the double-crossing guard's Hermite interpolant (its basis coefficients, the step ``h``, a
  slope scaled by 1/h): a changed interpolant flags other intervals, which costs a maximisation but no answer,
  unless a hidden pair is shown by the right interpolant and not by the changed one; the test
  ``test_critical_speed_pair_hidden_where_only_the_interpolant_shows_it`` kills removing the test, not each
  coefficient (a pair constructed per coefficient would).
* ``stability/linear/model.py`` (139 mutants): 30/50 -> 46/50 killed; 4 equivalent, so 30/46 (65 %) -> 46/46
  (100 %).  Equivalent: ``M.ndim == 2`` -> ``3`` (a batched solve instead of the one inverse: the same matrices to
  rounding); the two casters' rows of an input column swapped (twice: the chair model has one trail and one pin
  line, so in straight running the casters' accelerations are equal); ``zip(strict=True)`` -> ``False`` (equal
  lengths).
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]       # the source mutated (and, without --tests-from, the tests)

#: The fast tests that judge each module's mutants (the default marker selection; slow tests excluded).
ADVISE = ["tests/test_advise.py", "tests/test_advise_decisions.py"]
MODULES = {
    "stability/linear/critical.py": ["tests/test_linear.py", "tests/test_rootlocus.py"],
    "stability/linear/model.py": ["tests/test_linear.py", "tests/test_rootlocus.py"],
    "stability/advise/advisor.py": ADVISE,
    "stability/advise/levers.py": ADVISE,
    "stability/advise/limits.py": ADVISE,
    "stability/study/search.py": ["tests/test_search.py", "tests/test_search_rate_fit.py"],
    "stability/study/intervals.py": ["tests/test_intervals.py", "tests/test_impulse_step.py"],
    "stability/study/impulse.py": ["tests/test_impulse_fast.py", "tests/test_impulse_step.py"],
    "stability/study/impulse_intervals.py": ["tests/test_impulse_step.py", "tests/test_intervals.py"],
    "stability/study/censored.py": ["tests/test_sweep.py"],
    "stability/tipping/angles.py": ["tests/test_tipping.py"],
    "stability/shimmy/band.py": ["tests/test_shimmy_band.py"],
    "stability/slope/equilibrium.py": ["tests/test_slope.py"],
    "stability/sweep/run.py": ["tests/test_sweep.py"],
    "stability/uncertainty/propagation.py": ["tests/test_uncertainty.py"],
    "stability/measure/sheet.py": ["tests/test_measure.py"],
    "stability/assist/schedule.py": ["tests/test_driver.py", "tests/test_assist.py"],
    "stability/assist/export_c.py": ["tests/test_assist_export.py"],
    "stability/models/full_width.py": ["tests/test_linear.py", "tests/test_simulate.py"],
}


def mutants(path: str) -> list[tuple[int, int, str, str]]:
    """Every mutant mutmut makes of ``path``: (line number, index on the line, old line, new line)."""
    from mutmut import Context, list_mutations, mutate

    source = (ROOT / path).read_text()
    out = []
    for mid in list_mutations(Context(source=source, filename=path)):
        new, n = mutate(Context(source=source, filename=path, mutation_id=mid))
        if n != 1:
            continue
        old_lines, new_lines = source.splitlines(), new.splitlines()
        k = mid.line_number
        out.append((k + 1, mid.index, old_lines[k].strip(), new_lines[k].strip() if k < len(new_lines) else ""))
    return out


def _mutated(path: str, line: int, index: int) -> str:
    from mutmut import Context, RelativeMutationID, mutate

    source = (ROOT / path).read_text()
    text = source.splitlines()[line - 1]
    new, n = mutate(Context(source=source, filename=path,
                            mutation_id=RelativeMutationID(text, index, line - 1, filename=path)))
    if n != 1:
        raise ValueError(f"mutant {line}:{index} of {path} not found")
    return new


def main(argv: list[str] | None = None) -> int:
    """Command line: run the sample and print the score."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("path", choices=sorted(MODULES))
    ap.add_argument("--sample", type=int, default=60, help="mutants drawn (default 60)")
    ap.add_argument("--all", action="store_true", help="every mutant instead of a sample")
    ap.add_argument("--seed", type=int, default=34)
    ap.add_argument("--only-survivors", metavar="JSONL", help="re-test the survivors of an earlier run")
    ap.add_argument("--out", required=True, help="JSON lines, one per mutant")
    ap.add_argument("--work", default="/tmp/mutation_sample/copy")
    ap.add_argument("--timeout", type=float, default=300.0)
    ap.add_argument("--tests-from", metavar="REV", help="the tests/ folder of this git revision (e.g. main: the "
                    "score before new tests)")
    args = ap.parse_args(argv)

    every = mutants(args.path)
    if args.only_survivors:
        rows = [json.loads(x) for x in Path(args.only_survivors).read_text().splitlines() if x.strip()]
        keep = {(r["line"], r["index"]) for r in rows if r["status"] == "survived"}
        chosen = [m for m in every if (m[0], m[1]) in keep]
    elif args.all or args.sample >= len(every):
        chosen = every
    else:
        chosen = sorted(random.Random(args.seed).sample(every, args.sample))
    print(f"{args.path}: {len(every)} mutants, running {len(chosen)}", flush=True)

    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    shutil.copytree(ROOT, work, dirs_exist_ok=True,
                    ignore=shutil.ignore_patterns(".git", "__pycache__", ".pytest_cache", "reports", "_build"))
    if args.tests_from:
        shutil.rmtree(work / "tests")
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", args.tests_from, "tests"], check=True,
                                 capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(work)], input=archive, check=True)
    target = work / args.path
    original = target.read_text()
    env = dict(os.environ, PYTHONPATH=str(work), PYTHONDONTWRITEBYTECODE="1")
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-n", "0", "-p", "no:cacheprovider", "-p", "no:warnings",
           *MODULES[args.path]]
    killed = 0
    with open(args.out, "w") as fh:
        for line, index, old, new in chosen:
            t0 = time.perf_counter()
            try:
                target.write_text(_mutated(args.path, line, index))
                proc = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True, timeout=args.timeout)
                status = "survived" if proc.returncode == 0 else "killed"
            except subprocess.TimeoutExpired:
                status = "timeout"
            finally:
                target.write_text(original)
            killed += status != "survived"
            row = {"line": line, "index": index, "old": old, "new": new, "status": status,
                   "seconds": round(time.perf_counter() - t0, 1)}
            fh.write(json.dumps(row) + "\n")
            fh.flush()
            print(f"{status:8} {line:4}:{index} {old[:60]!r} -> {new[:60]!r}", flush=True)
    print(f"killed {killed}/{len(chosen)}")
    return 0 if killed == len(chosen) else 1


if __name__ == "__main__":
    sys.exit(main())
