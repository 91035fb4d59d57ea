"""Hand-written semantic mutants of the decisions and the physics, each run against the tests that should catch it.

A mutant is one textual change of one source file (``old`` -> ``new``; ``old`` must occur exactly once) that
makes an answer wrong in a way a reviewer would worry about: the advisor's ranking inverted, one of its limits
switched off, the sweep's ranking treating a bound ("above 3 m/s") as missing, a sign flipped in the linear
model, a wrong factor in tipping, a shimmy band edge moved, the generated-code door returning another variant's
function.  Each mutant is applied to a private copy of the repository (``--work``, default
``/tmp/hand_mutants/copy``; the ``.git`` directory is not copied), the group's tests run there in one process
(``pytest -x -n 0``, the default marker selection), and the mutant is *killed* when they fail.  The copy keeps its
numba cache between mutants (no kernel recompiles), and Python writes no bytecode (a mutated file is never read
from a stale ``.pyc``).

Mutants marked ``equivalent`` change no answer (the reason is stated); they are run and reported but not counted.

Usage (from the repository root, in the project's venv)::

    python tools/hand_mutants.py --list                 # the mutants, by group
    python tools/hand_mutants.py                        # every group (about 15 min on one core)
    python tools/hand_mutants.py advise sweep           # some groups
    python tools/hand_mutants.py --id advise-rank-inverted

Exit status 0 when every non-equivalent mutant run is killed, 1 otherwise.

Measured for issue 34 (55 mutants): with the tests of main at 61978c5, 35/54 non-equivalent killed (advise 13/17,
decision 0/8, sweep 4/5, linear 7/8, door 2/6, tipping 5/5, shimmy 4/5); with this branch's tests 54/54 (advise
17/17, decision 8/8, sweep 5/5, linear 8/8, door 6/6, tipping 5/5, shimmy 5/5 + 1 equivalent).
"""

# ruff: noqa: E501  (the mutants' source texts are quoted exactly, one per line)
from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


@dataclass(frozen=True)
class Mutant:
    """One semantic mutant.

    Attributes
    ----------
    id : str
        Short name (``group-what``).
    path : str
        Source file, relative to the repository root.
    old, new : str
        The text replaced (exactly one occurrence) and its replacement.
    what : str
        What the mutant does, in words.
    equivalent : str
        Empty, or why the mutant changes no answer.
    """

    id: str
    path: str
    old: str
    new: str
    what: str
    equivalent: str = ""

    @property
    def group(self) -> str:
        """The group: the id's first word."""
        return self.id.split("-", 1)[0]


#: The tests each group runs (the default marker selection applies: slow tests are not run).
TESTS = {
    "advise": ["tests/test_advise_decisions.py", "tests/test_advise.py"],
    "decision": ["tests/test_advise_decisions.py"],
    "sweep": ["tests/test_sweep.py"],
    "linear": ["tests/test_linear.py"],
    "door": ["tests/test_linear.py", "tests/test_derivations.py", "tests/test_validation.py"],
    "tipping": ["tests/test_tipping.py"],
    "shimmy": ["tests/test_shimmy_band.py", "tests/test_shimmy.py"],
}

A = "stability/advise/advisor.py"
L = "stability/advise/limits.py"
DEC = "stability/advise/decision.py"
SW = "stability/sweep/run.py"
CEN = "stability/study/censored.py"
LM = "stability/linear/model.py"
CR = "stability/linear/critical.py"
FW = "stability/models/full_width.py"
TIP = "stability/tipping/angles.py"
BAND = "stability/shimmy/band.py"
DF = "stability/shimmy/describing.py"

MUTANTS: tuple[Mutant, ...] = (
    # --- the advisor: ranking, gain, limits, screening, fallback ---------------------------------------------
    Mutant("advise-rank-inverted", A, "feasible = sorted((c for c in cands + combined if c.feasible), key=lambda c: -c.gain)",
           "feasible = sorted((c for c in cands + combined if c.feasible), key=lambda c: c.gain)",
           "the feasible candidates ranked worst first"),
    Mutant("advise-feasible-ignored", A, "for c in cands + combined if c.feasible), key=lambda c: -c.gain)",
           "for c in cands + combined), key=lambda c: -c.gain)", "candidates that break a limit recommended"),
    Mutant("advise-gain-max", A, "return min(g.values()), g", "return max(g.values()), g",
           "the robust gain is the better measure's, not the worse one's"),
    Mutant("advise-gain-median", A,
           "g = {\"critical_impulse\": rel(m.critical_impulse_Ns.robust, base.critical_impulse_Ns.robust),",
           "g = {\"critical_impulse\": rel(m.critical_impulse_Ns.value, base.critical_impulse_Ns.value),",
           "the critical impulse judged on its middle value, not the low end"),
    Mutant("advise-gain-inverted", A, "return new / old - 1.0", "return old / new - 1.0",
           "relative gain inverted (a lower measure gains)"),
    Mutant("advise-better-any", A, "better = [c for c in feasible if c.gain > 0]", "better = list(feasible)",
           "a change that loses on the robust measures recommended over 'no change'"),
    Mutant("advise-fix-cost", A, "feasible[0].gain >= -MAX_FIX_COST", "feasible[0].gain >= -10 * MAX_FIX_COST",
           "a fix costing up to 250 % of the robust measures accepted"),
    Mutant("advise-pairs-off", A, "chosen = [x for x in passing if _predicted(x[0]) > -MAX_FIX_COST][:PAIR_BUDGET]",
           "chosen = [x for x in passing if _predicted(x[0]) > -MAX_FIX_COST][:0]",
           "no pair of two levers measured"),
    Mutant("advise-pairs-worst", A, "if ok), key=lambda x: -_predicted(x[0]))",
           "if ok), key=lambda x: _predicted(x[0]))", "the pairs with the worst predicted gain measured"),
    Mutant("advise-predicted-sum", A, "f *= 1.0 + g", "f += g", "a pair's prediction the sum of the gains plus 1"),
    Mutant("advise-tip-off", L, "(m.static_stability_deg.value or -math.inf) >= min_tip - 1e-9", "True",
           "the static-stability (tip angle) limit switched off"),
    Mutant("advise-shimmy-off", L, "ok = sm is not None and sm >= MIN_SHIMMY_MARGIN_M", "ok = True",
           "the shimmy-margin limit switched off"),
    Mutant("advise-effort-off", L, "effort <= limit + 1e-12,", "True,", "the turning-effort limit switched off"),
    Mutant("advise-cross-off", L, "v is not None and abs(v) <= lim + 1e-9,", "True,",
           "the cross-slope drive-difference limit switched off"),
    Mutant("advise-bench-off", L, "m.bench_score <= lim,", "True,", "the ISO 7176-2 bench limit switched off"),
    Mutant("advise-driver-off", L, "u is not None and u >= intended - 1e-9", "True",
           "the driver's human-limited-speed limit switched off"),
    Mutant("advise-blocked-unsorted", A, "key=lambda b: (-len(b.fixes), len(b.limits), -b.candidate.gain))[:3]",
           "key=lambda b: (-len(b.fixes), len(b.limits), b.candidate.gain))[:3]",
           "the blocked changes named worst first"),
    # --- the decision's sentences and costs -------------------------------------------------------------------
    Mutant("decision-worse-inverted", DEC,
           "return self.after < self.before if self.higher_is_better else self.after > self.before",
           "return self.after > self.before if self.higher_is_better else self.after < self.before",
           "a cost's direction inverted (better reads as worse)"),
    Mutant("decision-tip-met", DEC, "met = None if after is None or smallest is None else after >= smallest.limit - 1e-9",
           "met = None if after is None or smallest is None else True", "a tip direction always meets its limit"),
    Mutant("decision-worst-direction", DEC, "worst = min(m.tip_angles_deg, key=lambda k: m.tip_angles_deg[k])",
           "worst = max(m.tip_angles_deg, key=lambda k: m.tip_angles_deg[k])",
           "the least stable direction named as the most stable one"),
    Mutant("decision-driver-enough", DEC, "verdict = \"enough\" if u >= a.intended_speed_m_s else \"NOT enough\"",
           "verdict = \"enough\"", "the driver always holds the chair at the intended speed"),
    Mutant("decision-shimmy-met", DEC, "cm(m.shimmy_margin_m.value), f\">= {100 * sm.limit:g} cm\", sm.met))",
           "cm(m.shimmy_margin_m.value), f\">= {100 * sm.limit:g} cm\", True))", "the shimmy margin always met"),
    Mutant("decision-effort-before-after", DEC, "base.turning_effort_N_m, m.turning_effort_N_m, f\"<= {te.limit:.3g} N m\"",
           "m.turning_effort_N_m, base.turning_effort_N_m, f\"<= {te.limit:.3g} N m\"",
           "the turning effort's before and after swapped"),
    Mutant("decision-cost-none-said", DEC, "worse = [c.text() for c in self.costs if c.worse]", "worse = []",
           "'WHAT IT COSTS' always says nothing"),
    Mutant("decision-limits-unmet", DEC, "unmet = [c.text() for c in self.costs if c.met is False]", "unmet = []",
           "'LIMITS' never names what the chair breaks"),
    # --- the sweep's ranking ----------------------------------------------------------------------------------
    Mutant("sweep-bound-missing", CEN, "    if not math.isfinite(value):\n        return (math.inf, 0)\n",
           "    if not math.isfinite(value) or side != \"=\":\n        return (math.inf, 0)\n",
           "a bound ('above 3 m/s') ranked as a missing value"),
    Mutant("sweep-bound-after", CEN, "beyond = {\"=\": 0, \">\": -1 if higher_is_better else 1,",
           "beyond = {\"=\": 0, \">\": 1 if higher_is_better else -1,", "'> 3' ranked after '3'"),
    Mutant("sweep-direction", CEN, "return (-value if higher_is_better else value, beyond)",
           "return (value if higher_is_better else -value, beyond)", "the measure's direction inverted"),
    Mutant("sweep-missing-ignored", SW, "ranked.sort(key=lambda e: (e[\"missing\"], sort_key(",
           "ranked.sort(key=lambda e: (0, sort_key(", "a design with failed draws ranked by its other draws"),
    Mutant("sweep-conservative-median", SW, "cons, cons_side = quantile(v, sd, q if up else 1.0 - q)",
           "cons, cons_side = quantile(v, sd, 1.0 - q if up else q)", "ranked by the optimistic end"),
    # --- the linear model and its critical speeds -------------------------------------------------------------
    Mutant("linear-sign-A", LM, "A[..., 1, :] = F[..., 1, :]", "A[..., 1, :] = -F[..., 1, :]",
           "the yaw row of the state matrix sign-flipped"),
    Mutant("linear-eta-kinematics", LM, "A[..., 2, 3] = 1.0", "A[..., 2, 3] = -1.0",
           "eta' = -eta_dot"),
    Mutant("linear-rows-swapped", LM, "A[..., 3, :] = F[..., 2, :]\n    A[..., 4, 5] = 1.0\n    A[..., 5, :] = F[..., 3, :]",
           "A[..., 3, :] = F[..., 3, :]\n    A[..., 4, 5] = 1.0\n    A[..., 5, :] = F[..., 2, :]",
           "the two casters' acceleration rows swapped"),
    Mutant("linear-input-row", LM, "G[..., 0], G[..., 1], G[..., 2], G[..., 3]",
           "G[..., 0], -G[..., 1], G[..., 2], G[..., 3]", "the yaw-moment input sign-flipped"),
    Mutant("linear-lateral-force", LM, "return np.array([1.0 / chair.m, 0.0])", "return np.array([1.0 / chair.m, 1.0 / chair.i_z])",
           "a lateral force at the c.g. makes a yaw acceleration (locked casters)"),
    Mutant("linear-critical-direction", CR, "np.sign(a[k]) != np.sign(a[k + 1]) and a[k + 1] != 0.0",
           "np.sign(a[k]) == np.sign(a[k + 1]) and a[k + 1] != 0.0", "the crossing test inverted"),
    Mutant("linear-max-real", CR, "return np.linalg.eigvals(A).real.max(axis=-1)",
           "return np.linalg.eigvals(A).real.min(axis=-1)", "the smallest real part, not the largest"),
    Mutant("linear-guard-off", CR, "        if not suspicious:\n            continue", "        if True:\n            continue",
           "the hidden-double-crossing guard switched off"),
    # --- the generated-code door --------------------------------------------------------------------------------
    Mutant("door-contact-stale", FW, "fn = getattr(_fw, f\"contact_velocities_{variant}\")",
           "fn = getattr(_fw, \"contact_velocities_exact\")", "contact velocities always the exact variant's"),
    Mutant("door-acc-stale", FW, "return _fw.accelerations_thesis(*args, r_dot_casters=r_dot_casters)",
           "return _fw.accelerations_exact(*args)", "the thesis accelerations replaced by the exact ones"),
    Mutant("door-linear-stale", FW, "name = f\"linear_{variant}\" if casters == \"free\" else f\"linear_locked_{variant}\"",
           "name = \"linear_exact\" if casters == \"free\" else f\"linear_locked_{variant}\"",
           "the linear matrices always the exact variant's"),
    Mutant("door-locked-stale", FW, "name = f\"linear_{variant}\" if casters == \"free\" else f\"linear_locked_{variant}\"",
           "name = f\"linear_{variant}\" if casters == \"free\" else \"linear_locked_exact\"",
           "the locked-caster matrices always the exact variant's"),
    Mutant("door-trig-swapped", FW, "return math.cos(angle), math.sin(angle)", "return math.sin(angle), math.cos(angle)",
           "trig() returns (sin, cos) for a scalar"),
    Mutant("door-yaw-moment-args", FW, "FEx, FEy, ce, se, cb, sb, p.x_m, p.x_p",
           "FEx, FEy, ce, se, cb, sb, p.x_p, p.x_m", "the tire yaw moment with the contact arms swapped"),
    # --- tipping --------------------------------------------------------------------------------------------------
    Mutant("tipping-atan-args", TIP, "angle_deg=math.degrees(math.atan2(rho, h))",
           "angle_deg=math.degrees(math.atan2(h, rho))", "tip angle atan(h/rho) instead of atan(rho/h)"),
    Mutant("tipping-factor", TIP, "return max(a[k] + t * b[k] - r[k] * s for k in range(n_pts))",
           "return max(a[k] + t * b[k] - 0.5 * r[k] * s for k in range(n_pts))",
           "half the caster swing radius in the fall distance"),
    Mutant("tipping-smallest", TIP, "return min(self.toward_main_wheels_deg, self.toward_casters_deg,",
           "return max(self.toward_main_wheels_deg, self.toward_casters_deg,", "the largest angle reported as the smallest"),
    Mutant("tipping-anti-tip", TIP, "return max(over, math.degrees(math.atan2(s1, h)))",
           "return min(over, math.degrees(math.atan2(s1, h)))", "the anti-tip devices lower the tip angle"),
    Mutant("tipping-slope-tilt", TIP, "tilt = math.degrees(math.atan2(g_in, gn))", "tilt = math.degrees(math.atan2(gn, g_in))",
           "the plane's tilt measured from the vertical"),
    # --- the shimmy band ----------------------------------------------------------------------------------------
    Mutant("shimmy-edge", BAND, "edges = 0.5 * (lo + hi)", "edges = lo + 0.9 * (hi - lo) + 0.002",
           "every band edge 2 mm off the bisection's bracket"),
    Mutant("shimmy-margin-sign", BAND, "return d if inside else -d", "return d",
           "a trail inside a shimmy zone gets a positive margin"),
    Mutant("shimmy-inside-open", BAND, "inside = any(a <= trail <= b for a, b in intervals)",
           "inside = any(a < trail < b for a, b in intervals)", "a trail on a band edge is outside the band",
           equivalent="a trail exactly on a bisected edge (a float from 40 bisections) does not occur; at an edge "
                      "the margin is 0 either way"),
    Mutant("shimmy-intervals-parity", BAND, "if (m % 2 == 0) == start_stable]", "if (m % 2 == 1) == start_stable]",
           "shimmy zones reported as the shimmy-free band"),
    Mutant("shimmy-margin-max", BAND, "return min(self.margin_m)", "return max(self.margin_m)",
           "the margin the largest over the speeds, not the smallest"),
    Mutant("shimmy-equivalent-damping", DF, "return 4.0 * friction / (math.pi * amplitude * frequency)",
           "return 2.0 * friction / (math.pi * amplitude * frequency)", "Coulomb friction's equivalent damping halved"),
)


def _sync(work: Path) -> None:
    """Copy the repository (without .git, caches and build output) over ``work``, keeping ``work``'s numba caches."""
    work.mkdir(parents=True, exist_ok=True)
    shutil.copytree(ROOT, work, dirs_exist_ok=True,
                    ignore=shutil.ignore_patterns(".git", "__pycache__", ".pytest_cache", "reports", "_build",
                                                  ".mutmut-cache", "mutants"))


def run_mutant(m: Mutant, work: Path, timeout: float) -> tuple[str, float, str]:
    """Apply ``m`` in ``work``, run its group's tests, restore the file.

    Returns
    -------
    tuple
        (``"killed"``, ``"survived"``, ``"timeout"`` or ``"error"``; seconds; the failing test or message).
    """
    path = work / m.path
    text = path.read_text()
    if text.count(m.old) != 1:
        return "error", 0.0, f"'old' occurs {text.count(m.old)} times in {m.path}"
    env = dict(os.environ, PYTHONPATH=str(work), PYTHONDONTWRITEBYTECODE="1")
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-n", "0", "-p", "no:cacheprovider", "-p", "no:warnings",
           *[t for t in TESTS[m.group] if (work / t).exists()]]
    t0 = time.perf_counter()
    try:
        path.write_text(text.replace(m.old, m.new))
        proc = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout", time.perf_counter() - t0, ""
    finally:
        path.write_text(text)
    dt = time.perf_counter() - t0
    if proc.returncode == 0:
        return "survived", dt, ""
    failed = [ln for ln in proc.stdout.splitlines() if ln.startswith(("FAILED", "ERROR"))]
    last = proc.stdout.strip().splitlines()[-1:] or [""]
    return "killed", dt, (failed[0] if failed else last[0])[:160]


def main(argv: list[str] | None = None) -> int:
    """Command line: run the chosen mutants and print killed/survived per group."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("groups", nargs="*", help=f"groups to run (default all): {sorted(TESTS)}")
    ap.add_argument("--id", action="append", default=[], help="run only this mutant (repeatable)")
    ap.add_argument("--list", action="store_true", help="list the mutants and exit")
    ap.add_argument("--work", default="/tmp/hand_mutants/copy", help="the repository copy to mutate")
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per mutant (a timeout counts as killed)")
    args = ap.parse_args(argv)
    bad = set(args.groups) - set(TESTS)
    if bad:
        ap.error(f"unknown group(s) {sorted(bad)}; valid: {sorted(TESTS)}")
    chosen = [m for m in MUTANTS if (not args.groups or m.group in args.groups) and (not args.id or m.id in args.id)]
    if args.list:
        for m in chosen:
            print(f"{m.id:32} {m.path:34} {m.what}" + (f"  [equivalent: {m.equivalent}]" if m.equivalent else ""))
        return 0
    work = Path(args.work)
    _sync(work)
    tally: dict[str, list[int]] = {}
    survivors = []
    for m in chosen:
        status, dt, info = run_mutant(m, work, args.timeout)
        eq = " (equivalent)" if m.equivalent else ""
        print(f"{status:8} {dt:6.1f} s  {m.id}{eq}  {info}", flush=True)
        k = tally.setdefault(m.group, [0, 0, 0])
        if m.equivalent:
            k[2] += 1
        else:
            k[1] += 1
            k[0] += status in ("killed", "timeout")
            if status not in ("killed", "timeout"):
                survivors.append(m.id)
    print("\ngroup      killed/non-equivalent  (+equivalent)")
    for grp, (n_killed, n_total, n_eq) in tally.items():
        print(f"{grp:10} {n_killed}/{n_total}" + (f"  (+{n_eq} equivalent)" if n_eq else ""))
    print(f"total      {sum(v[0] for v in tally.values())}/{sum(v[1] for v in tally.values())}")
    if survivors:
        print("survived: " + ", ".join(survivors))
    return 1 if survivors else 0


if __name__ == "__main__":
    sys.exit(main())
