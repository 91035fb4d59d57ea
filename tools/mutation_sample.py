"""Mutation score of a module with mutmut's mutation operators, bounded by a seeded sample (mutmut 2.5, dev extra).

``mutmut run`` tests every mutant of a file with a fresh test process, which on the shared 2-core machine costs
10-30 s a mutant (201 mutants in ``stability/linear/critical.py`` alone).  This runner enumerates the same
mutants (:func:`mutmut.list_mutations`, :func:`mutmut.mutate`: the operators ``mutmut run`` applies), draws a
seeded sample of them (or takes all, ``--all``), applies each to a private copy of the repository (``--work``; the
``.git`` directory is not copied; no bytecode written) and runs the module's fast tests there (``MODULES``, one
process, ``-x``).  It writes one JSON line per mutant (``--out``) so that a later run with ``--only-survivors``
re-tests only the survivors of an earlier one: the score after new tests is measured on the same mutants.

Usage (from the repository root, in the project's venv)::

    python tools/mutation_sample.py stability/linear/critical.py --sample 60 --out before_critical.jsonl \\
        --tests-from main
    python tools/mutation_sample.py stability/linear/critical.py --only-survivors before_critical.jsonl \\
        --out after_critical.jsonl
    python tools/mutation_sample.py --changed --budget 180 --out ci.jsonl      # CI: the modules a change touched

Exit status: for one module, 0 when every mutant run is killed or listed in :data:`EQUIVALENT`, 1 otherwise; with
``--changed``, 1 when a module's killed share of its non-equivalent mutants is below ``--target``.  The
equivalent mutants and their reasons are the table of docs/testing.md (tests/test_mutation_tools.py keeps the two
in step).

Measured for issue 34 (seed 34; "before" = the tests of main at 12dc991 (``--tests-from main``), "after" = the
survivors re-run with this branch's tests; killed / non-equivalent mutants of the sample):

* 10 mutants per module: ``tipping/angles.py`` 7/9 -> 9/9; ``shimmy/band.py`` 8/9 -> 9/9;
  ``slope/equilibrium.py`` 7/9 -> 9/9; ``uncertainty/propagation.py`` 9/10 -> 10/10; ``measure/sheet.py`` 7/10 ->
  9/10 (a reading's words used only in the docs' generated table left); ``study/intervals.py`` 3/10 -> 10/10; ``study/impulse.py`` 4/9 -> 9/9;
  ``study/impulse_intervals.py`` 6/9 -> 9/9; ``study/censored.py`` 5/10 -> 10/10; ``sweep/run.py``
  4/9 -> 9/9; ``assist/export_c.py`` 8/9 -> 9/9; ``assist/schedule.py`` 7/9 -> 9/9;
  ``models/full_width.py`` 10/10 (no survivor); ``advise/advisor.py`` 7/10 -> 8/10;
  ``advise/limits.py`` 0/9 (the tenth not run: the source changed under the run) -> 8/8 (the ninth's line, ``value or -inf``, rewritten: it read 0 deg as missing); ``advise/levers.py`` 4/9 -> 9/9;
  ``study/search.py`` 3/5 (5 equivalent) -> 4/5.
* ``stability/linear/critical.py``, 50 mutants: 32/42 (76 %) before this branch's last tests on the file as it was
  (the Hermite interpolant inline); with the interpolant as :func:`stability.linear.critical.hermite` and its
  tests, a fresh sample of the new file: 38/40 killed, 10 equivalent, and the 2 left (a refusal's words, a zero at
  the last grid point) killed by the tests written after it: 40/40.
* ``stability/linear/model.py`` (earlier run, 50 mutants): 30/46 (65 %) -> 46/46 (100 %).

Killed since (mutation2 branch, the survivors above re-run against their module's tests,
tests/test_advise_combinations.py added to the advisor's): in the advisor, the filter of the best acceptable
single change per lever that builds the three-lever combination (``all(k.met or ...)`` -> ``and`` and the filter's
other mutants) by a synthetic chair whose only answer is three levers; the percentage in the note of a chair that
already breaks a limit (``* 101``, ``/ 100``, ``gain > 1``) against the gain recomputed from the stand-in's low ends
(``gain >= 0`` in that note's word is equivalent); in the search, the late-reach threshold (``0.8 * horizon``:
``1.8``, ``/``, ``>``, ``None``, both lines) by the runs a round proposes on either side of it; in the sheet, the
empty readings' words.

Re-measured on the current files (seed 34, 10 mutants per module, the tool's own runs): ``advise/advisor.py`` 7/10
before (survivors: the 'no change' gains, the blocked pairs' strict comparison, the note's list separator) -> 9/9 of
the non-equivalent after (tests/test_advise_combinations.py; the comparison equivalent); ``study/search.py`` 5/5 of
the non-equivalent (5 equivalent); ``measure/sheet.py`` 10/10.  Every module of MODULES is at or above the 90 %
target, so the CI step is a gate.

Full mutant sets, as far as the shared machine allowed (load 5-9 on 2 cores: 30-120 s a mutant, so none finished):
``advise/levers.py`` 23 of 149 run (13 killed, 9 timed out at 120 s and counted as killed by this runner, 1
equivalent survivor, already listed); ``advise/layout_levers.py`` (not in MODULES: below the target, so a gate would
fail every change to it) 49 of 159 run: 25/48 of the non-equivalent killed before, 33/48 after the tests of
tests/test_advise_layout.py reading docs' lever steps (the trail, drive-axle and suspension steps); left: a row's
name when two caster rows lie on one side of the c.g. or a caster sits at x = 0, a row of one caster (``row[1]``),
the rounding of the row keys, the support-line count's ``k != 0`` and a trail step to exactly 0; its rounding to 6
digits is equivalent as the short form's.

Re-sampled with a fresh seed (seed 42, 8 mutants per module, the tool's own runs on the shared machine, mut42
branch; "before" = the tests at the branch point 5cba8f1, except that the modules sampled later in the run already
had the earlier modules' new tests, none of which bears on them; "after" = the survivors re-run with
``--only-survivors``; killed / non-equivalent): ``advise/advisor.py`` 6/8 -> 8/8 (a blocked fix's JSON ``change``;
the keep-and-measure note on a limit other than shimmy); ``advise/levers.py`` 6/8 -> 8/8 (two geometry labels,
now read back whole against the changed chair's fields); ``advise/limits.py`` 5/8 -> 8/8 (a Constraint's default
note, the turning-effort note's thesis citation, the pin friction's hold trail in cm); ``sweep/run.py`` 7/8 -> 8/8
(the progress callback's row count); ``shimmy/band.py`` 8/8; ``measure/sheet.py`` 5/8 -> 8/8 (the lever arm's
upper bound, a wrong-dimension unit's words, a reading shown without its std); ``uncertainty/propagation.py``
6/8 -> 8/8 (the regression shares of an output whose range is exactly 1, the delta method's shares of a constant
output); ``assist/schedule.py`` 6/7 (1 equivalent) -> 7/7 (the bad speed's parameter name; the equivalent
annotation mutant timed out at 300 s in the re-run, load 8); ``study/search.py`` 6/8 -> 7/7 (the log fit against
the threshold law it assumes; its widened bisection start shown equivalent and listed); ``study/impulse.py`` 4/8 ->
8/8 (three JSON keys of a critical impulse; the work check's own free-caster steps); ``study/censored.py`` 4/8 ->
6/6 (the quantile's order of a value tied with a bound; the sort key's two bound offsets shown equivalent and
listed); ``study/impulse_intervals.py`` 8/8; ``assist/export_c.py`` 7/8 -> 7/7 (the ``ClosedLoop`` type alias,
read only in postponed annotations, listed equivalent); ``linear/critical.py`` 7/8 -> 8/8 (the slope step
``1e-6 / max(1, U)``: the crossings do not move, but the slope's own accuracy does, killed by the analytic slope
at 100 m/s against its rounding model, tests/test_linear.py); ``models/full_width.py`` 4/8 -> 8/8 (the doors'
documented defaults against straight-running closed forms).  Of 120 mutants, 89 killed before; 5 of the 31
survivors equivalent (4 newly listed): 89/115 (77 %) of the non-equivalent before, 115/115 after.  None of
the 25 killed by new tests was a bug in its module: they were words, JSON keys, defaults and rarely taken branches
no test read.

Seed 43 (8 mutants per module, advisor43 branch, after ``advise/limits.py`` was split into one function per limit
for ``limits.meets``; "after" = ``--only-survivors``): ``advise/limits.py`` 2/8 -> 7/7 (the cross-slope limit at
its factor, the options and words that allow a blocked change, the shimmy sentence of a friction that holds at no
trail; the default display scale of ``limit_words`` listed equivalent); ``advise/advisor.py`` 6/8 -> 7/8 (the JSON
rank; left: a chair at negative speeds advised as its layout, which only ``tests/test_advise_layout.py`` checks,
not one of the advisor's gate files).  That file then joined the gate's files: on main the same seed's sample of
``advise/advisor.py`` is 8/8.

Seed 44 (8 mutants per module, main after the merges of 2026-12-06): ``advise/limits.py`` 6/8 -> 8/8 (a
constraint's comparison as printed, the bench note of a chair within the bench's score); ``advise/advisor.py``
5/8 -> 8/8 (no gain over a chair's zero low end, the worse-rate note's threshold, the runner-up named with its
cost); the tests are in tests/test_advise.py.

Seed 48 (8 mutants per module, every module of MODULES but ``advise/advisor.py`` and ``advise/limits.py``, mut48
branch; "before" = the tests at the branch point 99a44d7 (``--tests-from``, except ``study/impulse.py`` and
``study/censored.py``, run first on the same tests); "after" = ``--only-survivors``; killed / non-equivalent):
``study/impulse.py`` 6/8 -> 8/8 (the linear critical impulse's 1 ms default sampling, which only a decaying
response's early peak shows; the work check's estimate in minutes); ``study/censored.py`` 7/8 -> 8/8 (two found
values compared smaller first); ``measure/sheet.py`` 4/8 -> 8/8 (the loaded sum's tolerance option and its
refusal's words, the user estimate refused exactly where the de Leva model is, the provenance verb of a field
weighed directly); ``study/search.py`` 5/8 -> 8/8 (``_far_below``'s 10 % rule and its floor, the bracket closed
only within the contract ``high / low - 1 <= rel_tol (1 + 1e-9)``); ``linear/critical.py`` 6/8 -> 8/8 (a hidden
crossing pair near an interval's end, a complex crossing pair of imaginary part 1.5e-8; that test also kills the
listed ``max(2.0, |lambda|)`` mutant, now unlisted); ``advise/levers.py`` 4/8 -> 8/8 (the levers' descriptions
read whole against their changed chairs, the caster-mass lever's total mass of two casters); ``sweep/run.py``
7/8 -> 7/8 (left: ``summary``'s default ``top = 3``, a count stated nowhere, docs/sweep.md or the command's help,
so a test could only copy it); ``uncertainty/propagation.py`` 3/8 -> 8/8 (the regression's p + 2 draws, a level
of 1 refused by both propagations, the delta method's default step against a cubic's central difference);
``assist/schedule.py`` 6/7 (1 equivalent, listed) -> 7/7 (an unknown design refused as the single design
refuses it); ``assist/export_c.py`` 7/8 -> 8/8 (a Q31 README's per-case derived tolerances);
``models/full_width.py`` 7/8 -> 8/8 (the tire yaw moment's unpacking, killed by the door's lever-arm test of
tests/test_derivations.py, now one of the module's files); ``study/intervals.py`` 6/7 (1 equivalent, newly
listed) -> 7/7 (each variant named by the one input it moves); ``study/impulse_intervals.py`` 7/8 -> 8/8 (the
step variant halves the run's own step); ``tipping/angles.py`` 8/8; ``shimmy/band.py`` 5/6 (2 equivalent, newly
listed) -> 6/6 (the band's JSON keys against the hand-written shimmy schema); ``slope/equilibrium.py`` 5/7 (1
equivalent, newly listed) -> 7/7 (the drive's moment balance with the main wheels' rolling force on, by mirror
symmetry; ``harder_side``'s "neither"); ``linear/model.py`` 8/8.  Of 136 mutants, 101 killed before; 5 of the 35
survivors equivalent (4 newly listed): 101/131 (77 %) of the non-equivalent before, 130/131 (99 %) after.  None
was a bug in its module: words, JSON keys, defaults, refusals at an edge, and two branches no test reached (the
rolling force's moment, a dip near an interval's end).

Seed 49 (8 mutants per module, the ten modules lowest in seed 48 or in earlier seeds; "before" = the tests at
99a44d7, "after" = ``--only-survivors`` with this branch's tests, seed 48's included): ``uncertainty/propagation.py``
4/7 (1 equivalent, newly listed: ``r_squared``'s default) -> 7/7 (the Monte Carlo mean against the linear
function's); ``measure/sheet.py`` 5/8 -> 8/8 (a wheel scale reading 0 kg, the tilt refusal with the example's own
fall at 0.6 m); ``advise/levers.py`` 7/8 -> 8/8; ``shimmy/band.py`` 8/8; ``slope/equilibrium.py`` 4/7 (1
equivalent, newly listed) -> 7/7 (level ground's "none", the strict refusal's largest cross slope, the harder
side of the smallest float); ``study/search.py`` 4/7 (1 equivalent, newly listed) -> 6/7 (``_reaching``'s
definition, the step up of a linear response; left: the log fit's bisection end ``j1 (1 - 1e-12)`` -> ``2e-12``,
which moves the fit between a value and None in 16 of 40 000 random three-point sets and which no statement
fixes); ``study/impulse.py`` 6/7 (1 equivalent, listed) -> 7/7; ``linear/critical.py`` 7/8 -> 8/8 (the short
grid's refusal read whole); ``study/censored.py`` 6/8 -> 8/8 (values within ``rel_tol`` equal, an unknown
status refused); ``study/intervals.py`` 6/8 -> 8/8 (a factor's width, the variants' labels).  Of 80 mutants, 57
killed before; 4 of the 23 survivors equivalent (3 newly listed): 57/76 (75 %) before, 75/76 (99 %) after.
Seeds 48 and 49 together: 158/207 (76 %) of the non-equivalent before, 205/207 (99 %) after.

Seed 50 (10 mutants per module, every module of MODULES, mut49 branch; "before" = the tests at the branch point
ea8b3b2 (``--tests-from``); "after" = ``--only-survivors``; killed / non-equivalent), with the survivors of seeds
48-50 sorted by why the tests missed them and one test per class and module (docs/testing.md, "Classes of
survivors"): ``uncertainty/propagation.py`` 7/10 -> 9/10 (a parameter without spread is no regressor; left: the
shares of an output whose every coefficient is exactly 0, a branch only rounding coincidences reach);
``measure/sheet.py`` 5/10 -> 10/10 (every reading's stated range is the one applied, every preset's direct
readings within the ranges, the empty-sum refusal's words, K_t given directly, the raised end's default);
``study/search.py`` 8/10 -> 10/10 (a threshold rounding to the smaller push, no proposal below ``x_min``);
``study/impulse.py`` 8/9 (1 equivalent, newly listed) -> 9/9 (the work estimate at a size its print resolves);
``study/censored.py`` 7/8 (2 equivalent) -> 8/8 ("no value"); ``study/intervals.py`` 8/10 -> 10/10 (one reference
per force, the never-reaches refusal's words); ``slope/equilibrium.py`` 9/10 -> 10/10 (``operating_point`` mirror
symmetric); ``sweep/run.py`` 9/10 -> 10/10 (the summary's heading); ``assist/schedule.py`` 8/9 (1 equivalent,
newly listed) -> 9/9 (a repeated speed refused); ``tipping/angles.py`` 8/10 -> 9/10 (a wheel and a caster one
trail apart across the fall line, an 8-15-17 closed form; left: the on-line tolerance's scale ``1e-9 (1 + rho)``);
``shimmy/band.py`` 8/9 (1 equivalent, newly listed) -> 9/9 (a caster that does not roll); ``linear/model.py`` 9/9
(1 equivalent, newly listed); ``advise/advisor.py`` 4/6 of 7 run (1 equivalent, newly listed; the time budget of
360 s left 3 unrun) -> 5/6 (warnings summarised per tire group; left: the driver's limit in the lazy screen
``meets``, reached only by a full advice with a driver); ``advise/limits.py`` 6/9 of 9 run -> 8/9 (a limit not in
the words table, the suggested tip limit as printed; left: the words of an unbounded shimmy margin, which are
backwards: a finite low end means the nominal margin is +inf, no boundary, yet the sentence says it shimmies at
every trail, and the interval's None cannot tell +inf from -inf; reported, and fixed on main after the merge,
fcf1e3e: the measures keep the infinities);
``advise/levers.py``, ``assist/export_c.py``, ``models/full_width.py`` 10/10; ``linear/critical.py``,
``study/impulse_intervals.py`` 9/9 (1 listed equivalent each).  Of 186 mutants, 152 killed before; 9 of the 34
survivors equivalent (5 newly listed): 152/177 (86 %) of the non-equivalent before, 173/177 (98 %) after.

Seed 51, a fresh sample against this branch's tests with seed 50's (6 mutants per module of the eleven modules
seed 50's tests touched; the honest "after" of the classes, where seed 50's own "after" re-ran only its
survivors): ``uncertainty/propagation.py``, ``slope/equilibrium.py``, ``sweep/run.py``, ``shimmy/band.py`` 6/6;
``advise/advisor.py`` 5/5 (1 listed equivalent); ``assist/schedule.py`` 5/5 (1 listed equivalent);
``study/search.py`` 5/6 (the documented floor of a step down, ``2 eps``); ``study/censored.py`` 4/5 (1 listed
equivalent; ``describe`` without a unit); ``measure/sheet.py`` 4/6 (the words of a non-finite value and of a wrong
dimension); ``study/impulse.py`` 4/6 (``CriticalImpulseCurve`` never built in a gate file, ``runs_per_speed``'s
default rounds); ``study/intervals.py`` 4/5 (1 newly listed equivalent, a ``zip`` over one variant list per chair;
the friction scope's words).  Of 66 mutants, 55 killed; 4 equivalent: 55/62 (89 %) of the non-equivalent, against
76 % for the fresh samples of seeds 48 and 49 before their tests; the seven survivors fell in the same classes
(words, a default, a floor, a type built only outside the gate files) and are killed by the tests written after
the run (``--only-survivors``: 7/7; the sheet's refusals now read for every reading, not only the two drawn).

Seed 52 (``--changed --base e0a8aab --budget 400``: the three gated modules the shimmy-margin fix fcf1e3e touched,
the mutants round-robin until the budget; "before" = main at 7f446b3): ``advise/advisor.py`` 16/17 (left: the
"predicted" JSON key of a built-from entry, read by no gate file); ``shimmy/band.py`` 13/15 (1 equivalent, already
listed; left: the oscillation threshold's scale ``1e-9 |lambda|`` and the placeholder ``C`` of an invalid trail);
``advise/limits.py`` 11/17 -> 14/17 (a margin exactly at the shimmy limit meets it, the straddling note's words,
``ShimmyHold`` frozen; left: the rounding allowances of three limits, ``min_tip - 1e-9``, ``limit + 1e-12`` and
``lim + 1e-9``, whose ``>=``/``<=`` differ from ``>``/``<`` only at that exact float: constants below every
tolerance).  40/49 (82 %) before, 43/49 (88 %) after.

Seed 34 (the CI gate's own draw, ``--sample 60 --seed 34``, for stop 52's last commit b03c770, which touched only
``shimmy/band.py``; CI refused that stop on it): ``shimmy/band.py`` 47/58 non-equivalent (81 %) -> 53/53 (100 %)
with 7 equivalent (the draw changed with the source: ``describe``'s ``+`` no longer has a ``- 1e-12`` allowance,
the grid's last point being linspace's stop exactly).  Killed by tests: ``margin_cell``'s default format and its
two words, the refusal of a caster with no inertia about its own c.g. (the bound ``m_c l1^2`` recomputed), a band
ending one float below the search end without ``+``.  Newly listed equivalent: the placeholders ``k`` (rigid
pivot, twice) and ``C`` (unloaded trail), the oscillation threshold's scale, a ``zip`` over lists built together.

Seed 34, the gate's own sample (60, budget 150 s): each module of MODULES but ``shimmy/band.py`` (above), drawn as
CI draws it (``--sample 60 --seed 34``, the mutants in sorted order until the budget, so the prefix CI sees; mut55
branch, the shared machine at load 4-6; "before" = the tests at the branch point 7636a6a (``--tests-from``); "after"
= ``--only-survivors``; killed / non-equivalent): ``advise/advisor.py`` 4/5 -> 5/5 (a built-from part's
``predicted``, read against the single change measured alone, and every recommendation key docs/advise.md lists);
``advise/limits.py`` 5/5; ``advise/levers.py`` 4/4 (1 listed equivalent); ``linear/critical.py`` 17/18 -> 18/18
(the guard's slope where the leading eigenvalue is defective: a hidden crossing pair beside a Jordan block, at
``1 +- asin(0.2) / pi``); ``linear/model.py`` 23/23; ``study/impulse.py`` 6/7 -> 6/6 (the module's unused
``SCHEMES``, newly listed equivalent); ``study/impulse_intervals.py`` 6/7 -> 7/7 (its record frozen: every record
a subpackage exports, one scan); ``study/censored.py`` 5/6 -> 6/6 (an empty or NaN status claims no bound);
``tipping/angles.py`` 13/18 -> 17/17 (Loane & Kirby's mean against docs/tipping.md's quotation; the JSON's tipping
lines against ``tan(angle) = distance / h``, its least stable direction read from its own angles; the lateral fall
lines' length, newly listed equivalent); ``study/search.py`` 11/11 (3 listed equivalent); ``study/intervals.py``
11/11; ``sweep/run.py`` 10/11 -> 10/10 (the manifest's JSON indentation, newly listed equivalent);
``uncertainty/propagation.py`` 17/21 -> 21/21 (R^2 recomputed as the squared correlation with a fit on the raw
fields; a result built without its optional fields); ``slope/equilibrium.py`` 14/17 -> 16/17 (mirror symmetry
with unequal pin frictions; its records frozen; left: the residual's scale ``* 100`` -> ``/ 100``, which moves
the acceptance of a root from ``1e-10`` to ``1e-6`` of the weight and differs only where the root finder stalls
between the two: every preset at six cross slopes, three grades and three speeds gave two such starts, at 9 deg (1 and 2 m/s)
beyond the manual front-caster chair's limit, refused either way by its caster angle of ``9e8`` rad); ``measure/sheet.py`` 7/15 -> 11/15 (the readings of one instrument share its
range: the four wheel scales' ten readings, the spring scale's two pulls; the example sheet without any one
reading read or refused naming it; left: the caster assembly's 20 kg bound and the words of three optional
readings, ``inertia.rigidity``, ``inertia.fixture_period``, ``user.stature``, which only the docs' generated
table shows: a statement of them could only copy the table); ``assist/schedule.py`` 3/4 (1 listed equivalent)
-> 4/4 (a schedule, its designs and their plants compare and hash by identity); ``assist/export_c.py`` 6/6 (2
listed equivalent); ``models/full_width.py`` 15/15.  Of 214 mutants run, 177 killed before; 10 survivors listed
equivalent before and 3 newly listed: 177/204 (87 %) of the non-equivalent before, 196/201 (98 %) after; every
module at or above the 90 % target but ``measure/sheet.py``.  None was a bug in its module: words and keys, a
cited constant, declarations (``frozen``, ``eq``, ``required``), one instrument's ranges, and two inputs no test
gave (unequal pins, a defective eigenvalue).  A less loaded machine runs a longer prefix in the same budget, so
the three advise modules (the most often changed) were run further (budget 300 s, on this branch's tests):
``advise/advisor.py`` 26/32 -> 30/30 (the worse-rate note needs a change that gains, the shimmy note at a trail
changed to 0 and with the chair's unbounded margin in words, no bar by default on a stderr that is a terminal;
newly listed equivalent: the own-trail condition, a use speed of 0 already refused; the re-run of the survivors
confirmed all 4 killed);
``advise/limits.py`` 17/17 (the four limits' rounding allowances, ``>= x - 1e-9`` against ``>``, newly listed
equivalent: they differ only at the allowance's own float, which seed 52 had left); ``advise/levers.py`` 21/23 -> 21/21 (the axle labels' ``d < 0`` against ``<=``, newly listed equivalent: the steps are literals, never 0).

The classes of docs/testing.md, "Classes of survivors", counted (non-equivalent survivors; seeds 48-49's from the
reasons recorded above, so approximate: 49 in all; seed 50's exact: 25): words no test read 16 / 6; a number
printed too coarsely to tell its formula 2 / 2; a boundary no test sat on 14 / 3; a default or fallback no test
omitted 6 / 2; a branch for an input no test gave 8 / 8; a behaviour tested only outside the module's gate files
2 / 2; a constant below every tolerance or a branch only rounding reaches 1 / 2.

Seed 34, equal_instability.py newly gated (``study/equal_instability.py`` joined MODULES with
tests/test_equal_instability_search.py, test_advisor_runs.py, test_study.py, test_equal_instability_signed.py and
test_layout_equal_instability.py; the gate's own draw, ``--sample 60 --seed 34 --budget 400``, eqi55 branch on main
at 607e6a5): before -> after 41/56 (73 %) -> 56/56 (100 %) of the non-equivalent, 4 newly listed equivalent (the inside
test's rounding allowance ``<=`` and ``1e-12`` -> ``2e-12``, the memo's kind, the last ``break``); on the shared
machine (load 3-4) the 60 ran in 284 s before (40 of them within CI's 180 s) and in 149 s after (all 60: a
mutant killed stops at its first failing test).  The 15 survivors by class: words 3 (the
two refusals, the reference case's words); a default 1 (progress shown); a boundary 2 (a time exactly at the
horizon plus one step, the floor of one candidate); a branch for an input no test gave 9 (the Illinois halving
and its bookkeeping for the low end, the pair moved inside an end, the horizon's step for ``dt="auto"`` and the
adaptive scheme, the result's immutability).  Six of them (the Illinois halving three times, its low-end
bookkeeping, the pair moved inside an end twice) change only which speeds a later round runs, so the final bracket
but never that it holds a crossing: killed by the pairs read against the documented rule (regula falsi in log
time, Illinois, ``0.9 tol`` apart, ``0.05 tol`` inside an end) on closed-form laws.
None was a bug in the module.

Seed 34's gate sample on the other gated modules, the classes (24 non-equivalent survivors): words or JSON keys no test read 7; a boundary no test sat on 4; a declaration no test
read (``frozen`` twice, ``eq``, ``required``) 4, a class of its own since; a branch for an input no test gave 3;
a default no test omitted 2; a value only bounded, never recomputed (``R^2``) 2; a cited constant 1; a root's
acceptance threshold only a stall reaches 1.  ``study/impulse.py``'s unused ``SCHEMES`` constant, whose three
mutants were listed equivalent, was then deleted instead (the run's schemes are ``stability.settings.run.SCHEMES``).
The deletion moved the module's lines, so the gate drew another 60: ``study/impulse.py`` 40/47 (85 %, 0 equivalent;
47 run within 180 s) -> 48/48 (1 equivalent: the memo's kind).  Killed by tests: ``push_impulse``'s default scheme
(101 steps of 1 ms for 0.1 s), the search's start (the linear prediction sampled every 10 ms, within the sampled
peak's miss, only for a chair without pin friction on either pin), equal push-range ends refused, ``dt="auto"``
bracketing the event-driven critical impulse; ``critical_impulses``' two-way chair conversion became one
(``np.atleast_1d(np.asarray(chairs, dtype=object))`` is ``(1,)`` for one chair).  The whole draw, without the budget
(a faster CI machine runs more of it): 54/59 (92 %) -> 59/59 (``--only-survivors``: the "never" and "below" answers
as bounds with their brackets, ``critical_impulse`` itself called).

Seed 34's whole draw again after ``RunSpec.fixed_step`` replaced every copy of ``WCHAIR_DT if run.dt == "auto" else
float(run.dt)`` (the edited lines change the draw; ``--budget 1000``, no prefix cut): ``study/impulse.py`` 59/59
(1 equivalent); ``study/equal_instability.py`` 55/57 -> 57/57 (3 equivalent: 1 listed before, 2 newly: a pair's
length test ``>`` -> ``>=`` that only adds empty launches, the first-round flag of later rounds whose brackets
already exclude "above" and "below"; killed: a crossing exactly at the fastest point, an empty speed bracket);
``study/intervals.py`` 53/60 (88 %, 0 listed) -> 58/58 (2 newly equivalent: ``low`` and ``high`` None together,
a local annotation; killed: the factor ranges, their undefined variants and the "nominal" dominant of an interval
assembled from given variants, the factor ranges of a real interval whose every input has one variant, the
reference case's words in the point); ``study/impulse_intervals.py`` 56/58 (1 listed) -> 57/57 (1 newly
equivalent: a ``zip``'s ``strict`` over one result per job; killed: the other model's variant at nominal friction).

Seed 34's whole draw on ``measure/sheet.py`` (``--budget 1000``, no prefix cut; sheet56 branch on main at da5e8b4):
before, 50/60 (83 %, 0 equivalent) of the non-equivalent; the 150 s prefix above had shown 4 of the 10 survivors.
Killed by tests, with two changes the user sees: every refusal of one reading now ends with what the reading
measures (``sheet reading caster.mass=20.5 kg is invalid; valid range: > 0 and <= 20 (SI: mass); caster.mass: one
caster assembly (wheel, fork, bearing)``; the words of ``caster.amplitude`` and the calibration cylinder's radius
and period made to stand alone), so the three optional readings' words (``inertia.rigidity``,
``inertia.fixture_period``, ``user.stature``) are read whole in the refusals of realistic slips; and the loaded
sum exactly on an edge of the tolerance, which the sheet refused (the check ran inside the uncertainty's finite
differences, whose step pushed such a sum outside, and the refusal named a sum within the range it printed), is
accepted (the check runs once, on the readings as given).  Also killed: the caster assembly's 20 kg plausibility
bound from both sides (20 kg read, 20.5 kg refused), the provenance's formula words (the committed
docs/examples/measured_chair.toml read against what the example sheet gives), the raised main wheels' level load,
a ``[chair]`` field given with its std and the refusal of a bad one, an unknown ``tilt.end``.  The edits changed the
draw: the new draw 56/60 (93 %) -> 59/60 (98 %) with ``--only-survivors`` (a bare number's std, the refusal of
loaded readings that give no c.g., the provenance heading without a sheet).  Left: the finite-difference step of
a reading without a std, ``1e-7`` -> ``2e-7`` of its value, which decides only whether such a reading is listed
among a field's readings (its share of the uncertainty is 0 either way) and differs for a relative effect between
about 5e-6 and 1e-5: a release amplitude of 0.3-0.35 deg without a std is listed for ``i_zp`` by the mutant, not
by the module, although ``i_zp`` depends on it.  Not equivalent, and a test at that edge would only copy the
constant; reported.

Seed 34's whole draw after the sweep's bounds (critical speeds and shimmy margin stored as values or bounds with a
status; ``--budget 1000``, no prefix cut): ``shimmy/band.py`` (``margin_bound`` added) 50/52 -> 52/52 of the
non-equivalent, 8 equivalent (1 newly: ``margin_bound``'s sign test, reached only with an infinite margin; killed:
two shimmy-free bands listed, the nearest boundary the trail's); ``sweep/run.py`` 53/58 (91 %) -> 57/57, 3
equivalent (1 newly: the manifest's ``sort_keys``, compared only with a manifest of the same code; killed: a new
results folder, the progress callback's chunks, rows and elapsed seconds, the base chair's words, a design's notes of
bounds and missing draws together).  The Parquet path's mutants need pyarrow, which the README's test command does
not install: CI's gate step installs the ``[scale]`` extra first.

Seed 34, ``advise/pruning.py`` and ``advise/combinations.py`` newly gated (the two modules that decide which pairs
of changes the advisor measures and which changes get their intervals joined MODULES with ``ADVISE``; the gate's
whole draw, ``--sample 60 --seed 34 --budget 1500``, advgate56 branch on main at da5e8b4; "before" = the tests of
da5e8b4, "after" = ``--only-survivors``; killed / non-equivalent): ``advise/pruning.py`` (54 mutants, all drawn)
36/53 (68 %) -> 53/53 (1 newly equivalent: a ``zip``'s ``strict`` over ``found``, built from ``choices``), killed
by tests of ``Pool`` on hand-built candidates: ``refined`` counts each candidate computed once (now documented:
``combinations._per_round`` keys its cache on it), a candidate without its chair and a measurement answering
fewer chairs refused, a measurement of three, four or five entries, ``unbounded``'s rule (a gain of exactly
-100 % is not below it), a bound met exactly accepted and a broken one's words, ``Choice`` frozen;
``advise/combinations.py`` 41/58 (71 %) -> 58/58 (2 newly equivalent: the ``Candidate`` alias, read only in
annotations; the triple's ``[:3]`` -> ``[:4]``, its walk stopping at the third lever), killed by hand-built
changes with the changed chair stood in by its fields: the pairs measured against docs/advise.md's rule
enumerated (``singles[i + 2:]`` skipped neighbours), the same choice from upper bounds of the gains, the
recommendation, runner-up and blocked changes against the advisor's rules with every change computed, and small
cases where a change no choice can take keeps its bound (a seventh pair, a second passing pair below the cost
cut, a third blocked pair, a fourth lever, a third change a limit blocks, blocked changes whose bounds trail or
tie the recommendation) and a recommended pair's parts computed in its own batch.  Most of the 34 non-equivalent
survivors changed which changes get their intervals (more, fewer, or in another batch) rather than the choice,
and the pruned and full advisors' decisions had been compared on one chair only.  5 mutants (``refine`` computing nothing, a
candidate never exact) loop until the 300 s timeout, counted as killed.  None was a bug in its module.

Seed 34's whole draw on ``study/intervals.py`` after ``range_text`` said "no spread" for ends that print the same
(``--budget 1500``): 54/58 (93 %) -> 56/56, 4 equivalent (2 newly: the joiner's ``< 0`` at a speed never exactly
zero, the reference runs' memo kind; killed: each variant's force, friction factor and step as asked, an interval
without a defined variant in words).

Seed 34's whole draw on ``study/impulse.py`` after its search's largest push defaulted to ``MAX_IMPULSE`` (the
import moved its lines: a new draw; ``--budget 1000``): 56/59 (95 %) -> 58/58, 2 equivalent (1 newly: the work
check given no limits for free casters, which computes the same ones itself; killed: a study of exactly the work
budget accepted and the refusal's opening words, a zero push duration refused by name, the push convention's
words).

Seed 34 on ``measure/sheet.py`` after ``_scale_masses`` (the loaded and empty scale readings as masses in one
helper; its lines moved, so the gate drew new mutants; ``--changed``, ``--budget 400``): 55/60 (92 %) -> 58/60
(97 %), 0 equivalent.  Killed by new tests: an unknown sheet entry refused by name (``unknown = None`` survived),
the empty chair's weighing missing with its reason (the words survived), a front-caster sheet's pins a trail beyond
the contacts (the caster position was read by no test).  Left: the finite-difference step's two constants for a
reading without a std (reported above) and with one (``rd.std > 0`` -> ``> 1``: docs/testing.md).
"""

# ruff: noqa: E501  (the equivalent mutants' source lines and reasons are quoted whole)
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
ADVISE = ["tests/test_advise.py", "tests/test_advise_decisions.py", "tests/test_advise_combinations.py",
          "tests/test_advise_pruning.py", "tests/test_advise_lazy.py", "tests/test_api_hostile_modules.py",
          "tests/test_one_range_table.py", "tests/test_advise_layout.py"]
MODULES = {
    "stability/linear/critical.py": ["tests/test_linear.py", "tests/test_rootlocus.py"],
    "stability/linear/model.py": ["tests/test_linear.py", "tests/test_rootlocus.py", "tests/test_api_hostile_modules.py"],
    "stability/advise/advisor.py": ADVISE,
    "stability/advise/levers.py": ADVISE,
    "stability/advise/limits.py": ADVISE,
    "stability/advise/pruning.py": ADVISE,
    "stability/advise/combinations.py": ADVISE,
    "stability/study/search.py": ["tests/test_search.py", "tests/test_search_rate_fit.py", "tests/test_impulse_fast.py"],
    "stability/study/intervals.py": ["tests/test_study_measures.py", "tests/test_impulse_step.py", "tests/test_api_hostile_modules.py",
                                    "tests/test_equal_instability_signed.py"],
    "stability/study/impulse.py": ["tests/test_impulse_fast.py", "tests/test_impulse_step.py", "tests/test_api_hostile_modules.py"],
    "stability/study/impulse_intervals.py": ["tests/test_impulse_step.py", "tests/test_intervals.py", "tests/test_api_hostile_modules.py"],
    "stability/study/censored.py": ["tests/test_sweep.py", "tests/test_study.py"],
    "stability/tipping/angles.py": ["tests/test_tipping.py", "tests/test_api_hostile_modules.py"],
    "stability/shimmy/band.py": ["tests/test_shimmy_band.py"],
    "stability/slope/equilibrium.py": ["tests/test_slope.py", "tests/test_api_hostile_modules.py"],
    "stability/sweep/run.py": ["tests/test_sweep.py"],
    "stability/uncertainty/propagation.py": ["tests/test_uncertainty.py"],
    "stability/measure/sheet.py": ["tests/test_measure.py"],
    "stability/assist/schedule.py": ["tests/test_driver.py", "tests/test_assist.py", "tests/test_assist_layout_options.py", "tests/test_api_hostile_modules.py"],
    "stability/assist/export_c.py": ["tests/test_assist_export.py", "tests/test_assist_layout_options.py"],
    "stability/models/full_width.py": ["tests/test_linear.py", "tests/test_simulate.py", "tests/test_derivations.py"],
    "stability/study/equal_instability.py": ["tests/test_equal_instability_search.py", "tests/test_advisor_runs.py", "tests/test_study.py", "tests/test_equal_instability_signed.py", "tests/test_layout_equal_instability.py"],
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


#: Mutants shown to change no answer: (module, old line, new line) -> why (the table of docs/testing.md).
EQUIVALENT: dict[tuple[str, str, str], str] = {
    ('stability/linear/critical.py',
     'h = 1e-6 * np.maximum(1.0, np.abs(speeds))',
     'h = 1e-6 * np.maximum(2.0, np.abs(speeds))'):
        "the finite-difference step of the eigenvalue slope doubles below `2 m/s`: the slope moves by `O(h^2)`, about `1e-12` relative, and only shapes the guard's interpolant",
    ('stability/linear/critical.py',
     'ok = np.abs(den) > 1e-14',
     'ok = np.abs(den) >= 1e-14'):
        '`|w^H v|` equal to `1e-14` exactly does not occur (unit eigenvectors; zero only at a defective eigenvalue)',
    ('stability/linear/critical.py',
     '(np.sign(da[:-1]) != np.sign(da[1:])) & (np.min(np.abs(herm), axis=1) < 0.05 * scale)))',
     '(np.sign(da[:-1]) != np.sign(da[1:])) & (np.min(np.abs(herm), axis=1) <= 0.05 * scale)))'):
        "the interpolant's smallest magnitude equal to `0.05` of the scale exactly does not occur",
    ('stability/linear/critical.py',
     's = brentq(alpha, lo, hi, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=500)',
     's = brentq(alpha, lo, hi, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=501)'):
        "Brent's method converges to `xtol` in far fewer iterations than either limit",
    ('stability/linear/critical.py',
     'options={"xatol": 1e-9})',
     'options={"XXxatolXX": 1e-9})'):
        "scipy warns of the unknown option and keeps its default `xatol`: the maximum's location only has to show a positive value, which a looser location still does",
    ('stability/linear/critical.py',
     'kind = "complex" if abs(lam[i].imag) > 1e-8 * max(1.0, abs(lam[i])) else "real"',
     'kind = "complex" if abs(lam[i].imag) >= 1e-8 * max(1.0, abs(lam[i])) else "real"'):
        'an imaginary part exactly at the threshold does not occur',
    ('stability/linear/critical.py',
     'direction = "destabilising" if alpha(hi) > alpha(lo) else "stabilising"',
     'direction = "destabilising" if alpha(hi) >= alpha(lo) else "stabilising"'):
        "a bracket's ends have opposite signs of `alpha`, so they are never equal",
    ('stability/tipping/angles.py',
     'for j in range(i + 1, n_pts):',
     'for j in range(i - 1, n_pts):'):
        'adds the pairs `(i, i)`, whose differences are all zero and give no candidate, and pairs already taken: the same candidate set, the same minimum',
    ('stability/shimmy/band.py',
     'c_alpha = np.where(n_a > 0, c_alpha, np.nan)',
     'c_alpha = np.where(n_a >= 0, c_alpha, np.nan)'):
        "differs only where a caster's load is exactly `0.0` N, which the continuous trail search does not hit (a negative load gives NaN either way)",
    ('stability/shimmy/band.py',
     'zeta = np.where(osc, -ev.real / np.maximum(np.abs(ev), 1e-300), np.inf)',
     'zeta = np.where(osc, -ev.real / np.maximum(np.abs(ev), 2e-300), np.inf)'):
        "the floor only keeps a zero eigenvalue from dividing by zero (`0 / floor` is `0` either way); an oscillatory eigenvalue of magnitude between `1e-300` and `2e-300` 1/s does not occur (the caster's eigenvalues scale with the speed over the relaxation length and trail, `1e-2` to `1e3` 1/s, and an eigenvalue counts as oscillatory only with an imaginary part above `1e-9` of the largest)",
    ('stability/shimmy/band.py',
     'comp = CasterCompliance(lateral_stiffness=math.inf if rigid else 1.0, relaxation_length=1.0,',
     'comp = CasterCompliance(lateral_stiffness=math.inf if rigid else 1.0, relaxation_length=2.0,'):
        'a placeholder compliance that only picks the pivot case: `_abscissa_pairs` overwrites the relaxation length it gives (`params["sigma"] = sigmas`, and the pin stiffness `k` when the pivot is compliant) before any eigenvalue is taken',
    ('stability/shimmy/band.py',
     'k=1.0 if rigid_pivot else comp.lateral_stiffness, C=c_alpha, sigma=comp.relaxation_length,',
     'k=2.0 if rigid_pivot else comp.lateral_stiffness, C=c_alpha, sigma=comp.relaxation_length,'):
        "a placeholder: the rigid-pivot case's state matrix does not contain the pin's lateral stiffness `k` (`stability.models.shimmy.state_matrices` takes any finite placeholder for an entry a case does not use; its matrices for any two values of `k` are identical)",
    ('stability/shimmy/band.py',
     'params["C"] = np.where(ok, params["C"], 1.0)',
     'params["C"] = np.where(ok, params["C"], 2.0)'):
        'a placeholder cornering stiffness where the caster carries no load, only so the eigenvalue solver gets finite entries: `abscissa` returns NaN at exactly those points (`np.where(ok, out, np.nan)`)',
    ('stability/shimmy/band.py',
     'osc = np.abs(ev.imag) > 1e-9 * np.abs(ev).max(axis=-1, keepdims=True)',
     'osc = np.abs(ev.imag) > 2e-09 * np.abs(ev).max(axis=-1, keepdims=True)'):
        "LAPACK's real eigenvalue solver returns a real eigenvalue with an imaginary part of exactly `0`, so the threshold only separates `0` from a complex pair; a pair whose imaginary part lies between `1e-9` and `2e-9` of the largest eigenvalue's magnitude (a double root to nine digits) does not occur at the speeds asked",
    ('stability/shimmy/band.py',
     'lo_stable = np.array([scans[n][a, b] < 0 for n, a, b in zip(own, i, j, strict=True)], bool)',
     'lo_stable = np.array([scans[n][a, b] < 0 for n, a, b in zip(own, i, j, strict=False)], bool)'):
        "`own`, `i` and `j` are built in the same loop, `owner` extended by `i.size` for each scan's `np.nonzero` pair `(i, j)`: always the same length",
    ('stability/shimmy/band.py',
     'comp = CasterCompliance(lateral_stiffness=math.inf if rigid else 1.0, relaxation_length=1.0,',
     'comp = CasterCompliance(lateral_stiffness=math.inf if rigid else 2.0, relaxation_length=1.0,'):
        'a placeholder compliance that only picks the pivot case: a compliant pivot\'s stiffness is overwritten by `_abscissa_pairs` (`params["k"] = ks`) before any eigenvalue is taken',
    ('stability/slope/equilibrium.py',
     'for pins in ((1, 1), (-1, -1), (1, -1), (-1, 1)) if friction_range else ():',
     'for pins in ((1, 1), (-1, -1), (1, -1), (+1, 1)) if friction_range else ():'):
        "the mixed-sign pin moments give holding moments strictly between the same-sign pairs' (each pin moment moves the holding moment the same way; checked on every preset on three cross slopes and two grades), so the range's ends come from `(1, 1)` and `(-1, -1)` with or without `(-1, 1)`",
    ('stability/slope/equilibrium.py',
     'mp = (pins[0] * chair.pin_friction_left, pins[1] * chair.pin_friction_right)',
     'mp = (pins[1] * chair.pin_friction_left, pins[1] * chair.pin_friction_right)'):
        "the four pin-moment pairs become `(1, 1)`, `(-1, -1)` twice each: only the mixed-sign pairs are lost, and their holding moments lie between the same-sign pairs' (as the entry above: each pin moment moves the holding moment the same way); checked with unequal pin frictions (0.1/0.3, 0.3/0.1, 0.05/0.5 N m) on every preset on four cross slopes and two grades: the range's ends identical at every equilibrium",
    ('stability/slope/equilibrium.py',
     'friction_range=(float(np.nanmin(fr)), float(np.nanmax(fr))) if fr and not all(map(math.isnan, fr))',
     'friction_range=(float(np.nanmin(fr)), float(np.nanmax(fr))) if fr or not all(map(math.isnan, fr))'):
        'the same `(nan, nan)` either way: without pin runs (`friction_range=False`) `[] or not all([])` is false; with every pin run failed, `nanmin`/`nanmax` of an all-NaN list are NaN (numpy warns); otherwise both conditions are true',
    ('stability/slope/equilibrium.py',
     'c_main = model.chair.main_tire_model().cornering_stiffness_per_rad(p.m * p.g / 4)',
     'c_main = model.chair.main_tire_model().cornering_stiffness_per_rad(p.m / p.g / 4)'):
        "the root finder's starting guess only (a crab angle from the main tires' stiffness): the root it converges to at the solver's `xtol` is the same; measured on every preset at four cross slopes, two grades and three speeds: the holding moments and crab angles bit-identical",
    ('stability/linear/critical.py',
     'hi = U[k + 1] if k < len(U) - 1 else U[k]',
     'hi = U[k + 1] if k < len(U) - 2 else U[k]'):
        "for a zero exactly at the last-but-one grid point the bracket ends at that point instead of the next: Brent's method returns the bracket's end where `alpha` is zero, the same speed",
    ('stability/linear/critical.py',
     'if lo < hi and np.sign(alpha(lo)) != np.sign(alpha(hi)):',
     'if lo <= hi and np.sign(alpha(lo)) != np.sign(alpha(hi)):'):
        'with `lo == hi` the two signs compared are of one value, equal, so no bracket is added either way',
    ('stability/linear/critical.py',
     'scale = max(np.max(np.abs(a)), 1e-9)',
     'scale = max(np.max(np.abs(a)), 2e-09)'):
        "the floor only acts when every grid value of `alpha` is below `1e-9` 1/s in magnitude, zero to the eigenvalue solver's rounding, where the guard's margin decides nothing",
    ('stability/study/impulse.py',
     'run_list = [(c, float(s)) for c, s in zip(chair_b.ravel(), speed_b.ravel(), strict=True)]',
     'run_list = [(c, float(s)) for c, s in zip(chair_b.ravel(), speed_b.ravel(), strict=False)]'):
        'the two arrays come from `np.broadcast_arrays`: always the same length',
    ('stability/study/impulse_intervals.py',
     'specs: list[tuple[str, str, float, float]] = [("nominal", model, 1.0, dt)]',
     'specs: list[tuple[str, str, float, float]] = [("XXnominalXX", model, 1.0, dt)]'):
        "the nominal case's label is never shown: the point is taken by its index, the variants are the specs after it",
    ('stability/study/censored.py',
     'beyond = {"=": 0, ">": -1 if higher_is_better else 1, "<": 1 if higher_is_better else -1}[side]',
     'beyond = {"=": 0, ">": -2 if higher_is_better else 1, "<": 1 if higher_is_better else -1}[side]'):
        "the key's second entry only orders a bound against the value it is tied with, and every caller compares keys (sorts, `<`): `-2` or `-1`, then `0`, then `1` is the same order; checked on every pair of eight values (with infinities and NaN) on each side in both directions: the same comparisons",
    ('stability/study/censored.py',
     'beyond = {"=": 0, ">": -1 if higher_is_better else 1, "<": 1 if higher_is_better else -1}[side]',
     'beyond = {"=": 0, ">": -1 if higher_is_better else 1, "<": 1 if higher_is_better else -2}[side]'):
        "the key's second entry only orders a bound against the value it is tied with, and every caller compares keys (sorts, `<`): `-2` or `-1`, then `0`, then `1` is the same order; checked on every pair of eight values (with infinities and NaN) on each side in both directions: the same comparisons",
    ('stability/assist/export_c.py',
     'VECTOR_BIAS_DEG_S = 2.0',
     'VECTOR_BIAS_DEG_S = 3.0'):
        'an input of the exported test vectors (the gyro bias they carry), not an answer: the exported C is checked against the Python controller on whatever vectors are written, and any bias the estimator tracks serves',
    ('stability/assist/export_c.py',
     'ClosedLoop = Callable[[float, float, float, DigitalController], None]',
     'ClosedLoop = None'):
        'a type alias read only in annotations: both modules that use it (`export_c`, `export_run`) have `from __future__ import annotations`, so they are strings nobody evaluates (the docs take types from numpydoc, `autodoc_typehints = "none"`); mypy, not a test, is what checks it',
    ('stability/assist/schedule.py',
     'standstill: Design | None = None',
     'standstill: Design & None = None'):
        'an annotation: the module has `from __future__ import annotations`, so it is a string nobody evaluates',
    ('stability/assist/schedule.py',
     'flat = stack.reshape(len(speeds), -1)',
     'flat = stack.reshape(len(speeds), -2)'):
        'numpy takes any negative size as the one unknown dimension: the same reshape',
    ('stability/assist/schedule.py',
     'U = np.asarray(speeds, dtype=float).reshape(-1)',
     'U = np.asarray(speeds, dtype=float).reshape(-2)'):
        'numpy takes any negative size as the one unknown dimension: the same reshape',
    ('stability/assist/schedule.py',
     'hit = np.flatnonzero(np.isclose(speeds, speed, rtol=0, atol=1e-12))',
     'hit = np.flatnonzero(np.isclose(speeds, speed, rtol=0, atol=2e-12))'):
        'the tolerance that recognises a grid speed: within either the interpolated controller is the grid design to '
        'round-off, so which of the two is returned is not an answer',
    ('stability/linear/model.py',
     'if M.ndim == 2:',
     'if M.ndim == 3:'):
        'a batched solve instead of the one inverse: the same matrices to rounding',
    ('stability/linear/model.py',
     'd = [float(x1) - float(x0) for x1, x0 in zip(a1, a0, strict=True)]  # u_dot, v_dot, r_dot, eta_dd, beta_dd',
     'd = [float(x1) - float(x0) for x1, x0 in zip(a1, a0, strict=False)]  # u_dot, v_dot, r_dot, eta_dd, beta_dd'):
        'the two accelerations compared always have the same five entries',
    ('stability/study/intervals.py',
     'found = dict(zip(jobs, res, strict=True))',
     'found = dict(zip(jobs, res, strict=False))'):
        '`bisect_speeds` returns one result per chair it is given (its memo keys, one per chair), and it is given one chair per job: always the same length',
    ('stability/sweep/run.py',
     'for sp, ranked in zip(per["speeds_m_s"], per["best"], strict=True):',
     'for sp, ranked in zip(per["speeds_m_s"], per["best"], strict=False):'):
        '`summary` builds one list of best designs per speed: the two lists always have the same length',
    ('stability/study/search.py',
     'fit_pair: bool = False',
     'fit_pair: bool = None'):
        'the flag is only read for its truth (`if p.fit_pair`), and `None` is false like `False`',
    ('stability/study/search.py',
     'hi = min((x for x, r in zip(self.x, self.reached, strict=True) if r), default=None)',
     'hi = min((x for x, r in zip(self.x, self.reached, strict=False) if r), default=None)'):
        '`x` and `reached` are appended together, one entry per run: always the same length',
    ('stability/study/search.py',
     'if not (t1 > t2 > t3 and j1 < j2 < j3):',
     'if not (t1 >= t2 > t3 and j1 < j2 < j3):'):
        'differs only when two interpolated times to the level are equal to the last bit',
    ('stability/study/search.py',
     'if not (t1 > t2 > t3 and j1 < j2 < j3):',
     'if not (t1 > t2 >= t3 and j1 < j2 < j3):'):
        "with `t2 == t3` the law's difference `f(J0) = (t1 - t2) / ln((j2 - J0) / (j1 - J0)) - 0` is positive at every `J0` below `j1` (`t1 > t2`, `j1 < j2`), so the bisection finds no sign change and the fit is None either way",
    ('stability/study/search.py',
     'if x_start >= x_max - 1e-12:            # no prediction: the largest push and half of it, for _rate_fit',
     'if x_start > x_max - 1e-12:            # no prediction: the largest push and half of it, for _rate_fit'):
        'differs only for a start exactly `1e-12` below the largest push',
    ('stability/study/search.py',
     'if pred is None or not lo < pred < hi:',
     'if pred is None or not lo <= pred < hi:'):
        'differs only when a fitted prediction equals a tried push to the last bit',
    ('stability/study/search.py',
     'a_, b_ = j1 - 1e3 * (j3 - j1), j1 * (1.0 - 1e-12)',
     'a_, b_ = j1 - 1e3 * (j3 + j1), j1 * (1.0 - 1e-12)'):
        "the bisection for the law's threshold push starts further below the smallest push (the bracket only widens, and the law's difference `f` keeps its sign there): a hundred halvings reach the same root to float resolution; the prediction, a proposal for the next push only, moved by at most `2.2e-12` relative in log push over forty thousand sets of three points (twenty thousand of the law, twenty thousand arbitrary), never from a value to None, far below the search's bracket width",
    ('stability/uncertainty/propagation.py',
     'r_squared: Any = float("nan")',
     'r_squared: Any = None'):
        "`propagate`, the result's only maker, always passes `r_squared` (NaN where a column has no regression): the field's default is never read",
    ('stability/advise/levers.py',
     'return round(float(x), 6)',
     'return round(float(x), 7)'):
        "on the presets the changed fields are centimetre steps and simple factors of values with few decimals, the same at six and seven; on a measured chair the field moves by less than `5e-7` (m, N m), far below every measure's resolution (the values' three-figure words do not change)",
    ('stability/advise/advisor.py',
     'f"({\'and gains\' if c.gain > 0 else \'at a cost of\'} {abs(c.gain) * 100:.0f} % on the robust "',
     'f"({\'and gains\' if c.gain >= 0 else \'at a cost of\'} {abs(c.gain) * 100:.0f} % on the robust "'):
        "the note's word differs only for a robust gain of exactly `0`, where the note says `0 %` either way (no gain, no cost)",
    ('stability/advise/limits.py',
     'return LIMIT_WORDS.get(name, (name.replace("_", " "), "", 1.0))[0]',
     'return LIMIT_WORDS.get(name, (name.replace("_", " "), "", 2.0))[0]'):
        "the default tuple's third element (a display scale) is never read: `limit_words` takes element `[0]`, the name",
    ('stability/study/impulse.py',
     'return (f"constant force at the c.g.{toward} for {duration:g} s ({Push(1.0, duration).steps(h)} steps of "',
     'return (f"constant force at the c.g.{toward} for {duration:g} s ({Push(2.0, duration).steps(h)} steps of "'):
        'the step count of a push depends on its duration and the step only (`Push.steps`: `floor(duration / dt) + 1`): the force of the stand-in `Push` is never read',
    ('stability/assist/schedule.py',
     'if self.kind == "full-state":',
     'if self.kind == "XXfull-stateXX":'):
        "for a full-state design the other branch interpolates an estimator gain it does not use (NaN from the designs' `None`) and a model plant that `replace(d, plant=true_p)` then discards: `realise` of a full-state design keeps only the plant, its speed and `K`, so both branches give the same `Design` on the true plant",
    ('stability/shimmy/band.py',
     'lateral_stiffness_range=(1.0, math.inf), relaxation_length_range=(1.0, 1.0))',
     'lateral_stiffness_range=(2.0, math.inf), relaxation_length_range=(1.0, 1.0))'):
        "the placeholder compliance's ranges are never read: `_wheel_params` takes only its lateral stiffness (which picks the pivot case) and its relaxation length, both overwritten by `_abscissa_pairs`; a range need only be valid (`0 < low <= high`)",
    ('stability/linear/model.py',
     'd = [float(x1) - float(x0) for x1, x0 in zip(a1, a0, strict=True)]  # u_dot, v_dot, r_dot, eta_dd, beta_dd',
     'd = [float(x1) + float(x0) for x1, x0 in zip(a1, a0, strict=True)]  # u_dot, v_dot, r_dot, eta_dd, beta_dd'):
        "straight running with no force is an equilibrium of the equations: the accelerations without the force, `a0`, are exactly zero (every term carries a lateral state, a caster angle's sine or a force; checked on the E&J, an asymmetric chair with both rolling resistances and no pin friction, camber 2 deg, toe 1 deg: `[0.0] * 5`), so adding or subtracting them gives the same column",
    ('stability/advise/advisor.py',
     'driver: Driver | None = None',
     'driver: Driver & None = None'):
        'an annotation of a dataclass field: the module has `from __future__ import annotations`, so it is a string nobody evaluates (`dataclasses` reads only whether it names `ClassVar` or `InitVar`)',
    ('stability/study/intervals.py',
     'scheme, scope) for chair, vlist in zip(chairs, variants, strict=True)]',
     'scheme, scope) for chair, vlist in zip(chairs, variants, strict=False)]'):
        '`variants` is built with one list per chair (`[[None] * len(specs) for _ in chairs]`): always the same length',
    ('stability/study/equal_instability.py',
     'inside = [(s, t) for s, t in sorted(pts) if lo - 1e-12 <= s <= hi + 1e-12]',
     'inside = [(s, t) for s, t in sorted(pts) if lo - 1e-12 <= s < hi + 1e-12]'):
        "differs only for a speed exactly `1e-12` m/s above the bracket's high end: the bracket's ends are evaluated speeds themselves (stored exactly, so inside either way), and every other evaluated speed lies at least `0.05 tol` from an end (a pair stays that far inside its bracket and spans `0.9 tol`) or a first-round grid spacing, never `1e-12` m/s (`tol` would be below `2e-11` m/s, a speed step far below what the runs' 1 ms time step resolves)",
    ('stability/study/equal_instability.py',
     'inside = [(s, t) for s, t in sorted(pts) if lo - 1e-12 <= s <= hi + 1e-12]',
     'inside = [(s, t) for s, t in sorted(pts) if lo - 1e-12 <= s <= hi + 2e-12]'):
        "the allowance only admits speeds within `1e-12` (or `2e-12`) m/s outside the bracket: the bracket's ends are evaluated speeds themselves (stored exactly, so inside either way), and every other evaluated speed lies at least `0.05 tol` from an end (a pair stays that far inside its bracket and spans `0.9 tol`) or a first-round grid spacing, so none lies between `1e-12` and `2e-12` m/s outside unless `tol` is below `4e-11` m/s, a speed step far below what the runs' 1 ms time step resolves",
    ('stability/study/equal_instability.py',
     'for r in memoised("equal_instability", keys, batch)]',
     'for r in memoised("XXequal_instabilityXX", keys, batch)]'):
        "the kind only keeps this search's memo entries apart from another search's (`memoised` stores `(kind, key)`); the one other kind, `critical_impulse`, differs from either name, so the same jobs are found and reused",
    ('stability/study/equal_instability.py',
     'break',
     'continue'):
        "once no job is active none becomes active again (a job's status and bracket change only while it is active), so the remaining rounds find `active` empty and do nothing either way (the progress bar is updated only after a round that ran)",
    ('stability/sweep/run.py',
     'manifest = json.dumps(spec.to_dict(), sort_keys=True, indent=1)',
     'manifest = json.dumps(spec.to_dict(), sort_keys=True, indent=2)'):
        "the indentation of the chunk directory's `spec.json`, which `run_sweep` alone writes and compares, both with this line (the directory is removed when its run merges): the same spec reads back as the same JSON either way, and a directory is accepted or refused alike (only chunks left by a version with the other indentation would be refused, as another spec, which asks for them to be removed)",
    ('stability/tipping/angles.py',
     '"lateral_left": (0.0, -1.0), "lateral_right": (0.0, 1.0)}[key]',
     '"lateral_left": (0.0, -2.0), "lateral_right": (0.0, 1.0)}[key]'):
        '`support_fall_distance` divides the fall line by its length (`math.hypot(ex, ey)`) before using it: `(0, -2) / 2` is `(0, -1)` exactly, the same fall line',
    ('stability/tipping/angles.py',
     '"lateral_left": (0.0, -1.0), "lateral_right": (0.0, 1.0)}[key]',
     '"lateral_left": (0.0, -1.0), "lateral_right": (0.0, 2.0)}[key]'):
        '`support_fall_distance` divides the fall line by its length (`math.hypot(ex, ey)`) before using it: `(0, 2) / 2` is `(0, 1)` exactly, the same fall line',
    ('stability/advise/advisor.py',
     'own = m.shimmy_trail_m if m.shimmy_trail_m is not None or not isinstance(chair, Chair) else chair.trail',
     'own = m.shimmy_trail_m if m.shimmy_trail_m is not None and not isinstance(chair, Chair) else chair.trail'):
        "the two conditions pick the same branch wherever the line runs: a chair's measures carry no row trail (`shimmy_trail_m` None: the short form, `measures.py`), so both take `chair.trail`; a layout's carry its row's trail whenever the band straddles zero, the only case that reaches the line (a layout without caster rows has `shimmy_straddles` False), so both take `m.shimmy_trail_m`",
    ('stability/advise/advisor.py',
     'if isinstance(chair, Chair) and any(u < 0 for u in use):',
     'if isinstance(chair, Chair) and any(u <= 0 for u in use):'):
        '`use_speeds` has already refused every speed of size below `0.1` m/s (`ADVISE_SPEED`), so no use speed is `0`',
    ('stability/advise/limits.py',
     'return Constraint("static_stability_deg", tip, min_tip, ">=", tip is not None and tip >= min_tip - 1e-9,',
     'return Constraint("static_stability_deg", tip, min_tip, ">=", tip is not None and tip > min_tip - 1e-9,'):
        "`tip >= min_tip - 1e-9` and `tip > min_tip - 1e-9` differ only for an angle exactly `1e-9` deg below the limit, the allowance's own float, which no computed angle lands on (the allowance only keeps an angle equal to the limit up to rounding on the allowed side)",
    ('stability/advise/limits.py',
     'return Constraint("turning_effort_N_m", effort, limit, "<=", effort <= limit + 1e-12,',
     'return Constraint("turning_effort_N_m", effort, limit, "<=", effort < limit + 1e-12,'):
        "`effort <= limit + 1e-12` and `effort < limit + 1e-12` differ only for an effort exactly `1e-12` N m above the limit, the allowance's own float, which no computed effort lands on (the allowance only keeps an effort equal to the limit up to rounding on the allowed side)",
    ('stability/advise/limits.py',
     'return Constraint(m.effort_key, None if v is None else abs(v), lim, "<=", v is not None and abs(v) <= lim + 1e-9,',
     'return Constraint(m.effort_key, None if v is None else abs(v), lim, "<=", v is not None and abs(v) <= lim + 2e-09,'):
        "`abs(v) <= lim + 1e-9` and `abs(v) <= lim + 2e-9` differ only for a value between `1e-9` and `2e-9` above the limit, a band below the rounding of any computed effort's inputs, which no computed value lands in (the allowance only keeps a value equal to the limit up to rounding on the allowed side)",
    ('stability/advise/limits.py',
     'return Constraint("human_limited_speed_m_s", u, intended, ">=", u is not None and u >= intended - 1e-9,',
     'return Constraint("human_limited_speed_m_s", u, intended, ">=", u is not None and u > intended - 1e-9,'):
        "`u >= intended - 1e-9` and `u > intended - 1e-9` differ only for a speed exactly `1e-9` m/s below the intended one, the allowance's own float, which no computed speed lands on (the allowance only keeps a speed equal to the intended one up to rounding on the allowed side)",
    ('stability/advise/levers.py',
     'return [Change("s1_fixed_wheelbase", f"axle {abs(d) * 100:g} cm {\'toward\' if d < 0 else \'away from\'} the c.g. "',
     'return [Change("s1_fixed_wheelbase", f"axle {abs(d) * 100:g} cm {\'toward\' if d <= 0 else \'away from\'} the c.g. "'):
        'the axle steps `d` are the literals `(-0.10, -0.05, 0.05)` m on the same line: never `0`, so `d < 0` and `d <= 0` name the same direction',
    ('stability/advise/levers.py',
     'return [Change("s1_fixed_s2", f"axle {abs(d) * 100:g} cm {\'toward\' if d < 0 else \'away from\'} the c.g. at fixed s2 "',
     'return [Change("s1_fixed_s2", f"axle {abs(d) * 100:g} cm {\'toward\' if d <= 0 else \'away from\'} the c.g. at fixed s2 "'):
        'the axle steps `d` are the literals `(-0.05, 0.05)` m on the same line: never `0`, so `d < 0` and `d <= 0` name the same direction',
    ('stability/study/impulse.py',
     'return memoised("critical_impulse", [(c, s, run, level, max_impulse, min_impulse, rel_tol, max_rounds)',
     'return memoised("XXcritical_impulseXX", [(c, s, run, level, max_impulse, min_impulse, rel_tol, max_rounds)'):
        "the kind only keeps this search's memo entries apart from another search's (`memoised` stores `(kind, key)`); the one other kind, `equal_instability`, differs from either name, so the same jobs are found and reused",
    ('stability/study/equal_instability.py',
     'todo = [i for i in active if len(pairs[i]) > k and (k == 0 or dict(evals[i])[pairs[i][0]] > target[i])]',
     'todo = [i for i in active if len(pairs[i]) >= k and (k == 0 or dict(evals[i])[pairs[i][0]] > target[i])]'):
        "a pair is two speeds or one midpoint: with `>=`, a one-speed pair's job joins the second launch with the empty slice `pairs[i][1:2]` and runs nothing, and a launch with no speeds returns at once, so the same runs are made",
    ('stability/study/equal_instability.py',
     'status[i], lo[i], hi[i] = _narrow(evals[i], lo[i], hi[i], float(target[i]), False)',
     'status[i], lo[i], hi[i] = _narrow(evals[i], lo[i], hi[i], float(target[i]), True)'):
        'after the first round an open job\'s `lo` has a time above the target and its `hi` one at or below it, and every later round keeps that (the new bracket is the first point as unstable and the one before it), so the first-round checks find neither "above" (the fastest point inside is `hi`) nor "below" (the slowest is `lo`)',
    ('stability/study/intervals.py',
     'if self.low is None or self.high is None:',
     'if self.low is None and self.high is None:'):
        "`low` and `high` are the smallest and largest of one list (the defined variants' speeds), so both are None or neither is; `signed` swaps them together, and either test picks the same branch",
    ('stability/study/intervals.py',
     'variants: list[list[Variant | None]] = [[None] * len(specs) for _ in chairs]',
     'variants: list[list[Variant & None]] = [[None] * len(specs) for _ in chairs]'):
        'an annotation of a local variable: Python never evaluates it (and the module has `from __future__ import annotations`); mypy, not a test, is what checks it',
    ('stability/study/impulse_intervals.py',
     'results.update(zip(jobs, res, strict=True))',
     'results.update(zip(jobs, res, strict=False))'):
        '`critical_impulses` returns one result per chair it is given, and it is given one chair per job: always the same length',
    ('stability/shimmy/band.py',
     'return (d, "above") if margin > 0 else (-d, "below")',
     'return (d, "above") if margin > 1 else (-d, "below")'):
        'the line is reached only with an infinite margin (a finite or NaN one has returned above it), and `+inf` exceeds both `0` and `1` while `-inf` exceeds neither: the same branch',
    ('stability/sweep/run.py',
     'manifest = json.dumps(spec.to_dict(), sort_keys=True, indent=1)',
     'manifest = json.dumps(spec.to_dict(), sort_keys=False, indent=1)'):
        "the manifest is only compared with one this code wrote (`--resume` refuses another spec's chunks), and `SweepSpec.to_dict` builds its keys in a fixed order, so sorted or not the same spec gives the same text and another spec another",
    ('stability/advise/pruning.py',
     'todo = [k for c, (_, t) in zip(choices, found, strict=True) for i in t for k in c.needs(i)]',
     'todo = [k for c, (_, t) in zip(choices, found, strict=False) for i in t for k in c.needs(i)]'):
        '`found` is built from `choices` on the line above, one entry per choice (`[c.pending() for c in choices]`): always the same length',
    ('stability/advise/combinations.py',
     'Candidate = Any          # stability.advise.advisor.Candidate (defined there; this module is imported by it)',
     'Candidate = None          # stability.advise.advisor.Candidate (defined there; this module is imported by it)'):
        'a type alias read only in annotations: the module has `from __future__ import annotations`, so those of its signatures are strings nobody evaluates, and the one on a local variable is never evaluated; mypy, not a test, is what checks it',
    ('stability/advise/combinations.py',
     'trio = tuple(list(best.values())[:3])',
     'trio = tuple(list(best.values())[:4])'):
        "`best` holds one change per lever of the triple's walk, which stops at the entry that brings a third lever (its `enough`: three levers), so it never holds more than three: `[:4]` takes the same ones",
    ('stability/study/intervals.py',
     'return f"range {self.low:.3g}{\' to \' if self.low < 0 else \'-\'}{self.high:.3g} m/s"',
     'return f"range {self.low:.3g}{\' to \' if self.low <= 0 else \'-\'}{self.high:.3g} m/s"'):
        'an equal-instability speed is never exactly `0`: forwards it lies in the searched bracket (from `RANGE_BRACKET[0]` up), in reverse it is negative (`signed`), so `< 0` and `<= 0` pick the same joiner',
    ('stability/study/intervals.py',
     'return np.array(memoised("reference_time", [(c, float(speed), f, spec, criterion)',
     'return np.array(memoised("XXreference_timeXX", [(c, float(speed), f, spec, criterion)'):
        "the kind only keeps this memo's entries apart from another search's (`memoised` stores `(kind, key)`); the other kinds (`critical_impulse`, `equal_instability`) differ from either name, so the same reference runs are found and reused",
    ('stability/study/impulse.py',
     'free = limits if run.casters == "free" else None       # the work check is stated for free casters',
     'free = None       # the work check is stated for free casters'):
        'with free casters the limits passed are the ones `check_study_work` computes itself when given none (the same `stable_steps` of the same chairs, speeds and model: `test_study_work_check_computes_the_free_caster_steps_itself`), so passing none changes only the work of the check, not its answer',
}


def equivalent(path: str, old: str, new: str) -> str:
    """Why the mutant ``old`` -> ``new`` of ``path`` changes no answer, or ``""``."""
    return EQUIVALENT.get((path, old, new), "")


def changed_modules(base: str | None) -> tuple[str, list[str]]:
    """The base revision and the modules of :data:`MODULES` changed between it and HEAD.

    ``base`` None: the merge base with ``origin/main`` (or ``main``) when HEAD is not on it, else ``HEAD~1``.
    """
    def git(*args: str) -> str:
        return subprocess.run(["git", "-C", str(ROOT), *args], check=True, capture_output=True,
                              text=True).stdout.strip()

    if base is None:
        head = git("rev-parse", "HEAD")
        for ref in ("origin/main", "main"):
            try:
                mb = git("merge-base", "HEAD", ref)
            except subprocess.CalledProcessError:
                continue
            if mb != head:
                base = mb
                break
        else:
            base = "HEAD~1"
    try:
        names = git("diff", "--name-only", base, "HEAD").splitlines()
    except subprocess.CalledProcessError as exc:      # a shallow clone without the base, or no git history
        print(f"cannot compare with {base}: {exc.stderr.strip()}; no mutants run", flush=True)
        return base, []
    return base, [m for m in MODULES if m in names]


def _draw(path: str, args: argparse.Namespace) -> list[tuple[int, int, str, str]]:
    every = mutants(path)
    if args.only_survivors:
        rows = [json.loads(x) for x in Path(args.only_survivors).read_text().splitlines() if x.strip()]
        chosen: list[tuple[int, int, str, str]] = []
        for r in rows:
            if r["status"] != "survived" or r.get("path", path) != path:
                continue
            # the same change of the same text may occur on several lines: the one nearest the old line number
            same = [m for m in every if (m[2], m[3]) == (r["old"], r["new"]) and m not in chosen]
            if same:
                chosen.append(min(same, key=lambda m: abs(m[0] - r["line"])))
        return sorted(chosen)
    if args.all or args.sample >= len(every):
        return every
    return sorted(random.Random(args.seed).sample(every, args.sample))


def main(argv: list[str] | None = None) -> int:
    """Command line: run the sample and print the score."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("path", nargs="?", choices=sorted(MODULES))
    ap.add_argument("--sample", type=int, default=60, help="mutants drawn per module (default 60)")
    ap.add_argument("--all", action="store_true", help="every mutant instead of a sample")
    ap.add_argument("--seed", type=int, default=34)
    ap.add_argument("--only-survivors", metavar="JSONL", help="re-test the survivors of an earlier run (matched by "
                    "their old and new line, so they are found again after lines moved)")
    ap.add_argument("--changed", action="store_true", help="the modules of MODULES changed since --base (CI)")
    ap.add_argument("--base", metavar="REV", help="with --changed: compare against REV (default: the merge base "
                    "with origin/main or main, else HEAD~1)")
    ap.add_argument("--budget", type=float, default=None, metavar="SECONDS",
                    help="start no mutant after this many seconds (the mutants are taken round-robin over the "
                         "modules, so every module gets its share)")
    ap.add_argument("--target", type=float, default=0.9, help="with --changed: exit 1 when the killed share of "
                    "the non-equivalent mutants run is below this (default 0.9, issue 34's target)")
    ap.add_argument("--out", required=True, help="JSON lines, one per mutant")
    ap.add_argument("--work", default="/tmp/mutation_sample/copy")
    ap.add_argument("--timeout", type=float, default=300.0)
    ap.add_argument("--tests-from", metavar="REV", help="the tests/ folder of this git revision (e.g. main: the "
                    "score before new tests)")
    args = ap.parse_args(argv)
    if args.changed:
        base, paths = changed_modules(args.base)
        print(f"modules changed since {base}: {', '.join(paths) or 'none of MODULES'}", flush=True)
        if not paths:
            Path(args.out).write_text("")
            return 0
    elif args.path:
        paths = [args.path]
    else:
        ap.error("give a module path or --changed")

    queues = {}
    for path in paths:
        queues[path] = _draw(path, args)
        print(f"{path}: {len(mutants(path))} mutants, drawn {len(queues[path])}", flush=True)
    # round-robin: one mutant of each module in turn, so a time budget spreads over the modules
    order = [(path, q[i]) for i in range(max(map(len, queues.values()), default=0))
             for path, q in queues.items() if i < len(q)]

    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    shutil.copytree(ROOT, work, dirs_exist_ok=True,
                    ignore=shutil.ignore_patterns(".git", "__pycache__", ".pytest_cache", "reports", "_build",
                                                  ".ci-venv", ".venv", "ui-artifacts", ".mypy_cache",
                                                  ".ruff_cache", ".benchmarks"))
    if args.tests_from:
        shutil.rmtree(work / "tests")
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", args.tests_from, "tests"], check=True,
                                 capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(work)], input=archive, check=True)
    env = dict(os.environ, PYTHONPATH=str(work), PYTHONDONTWRITEBYTECODE="1")
    score: dict[str, list[int]] = {path: [0, 0, 0] for path in paths}      # killed, run, equivalent
    t_start = time.perf_counter()
    with open(args.out, "w") as fh:
        for path, (line, index, old, new) in order:
            if args.budget is not None and time.perf_counter() - t_start > args.budget:
                print(f"time budget of {args.budget:g} s used: {len(order) - sum(r for _, r, _ in score.values())} "
                      "mutants not run", flush=True)
                break
            target = work / path
            original = target.read_text()
            cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-n", "0", "-p", "no:cacheprovider",
                   "-p", "no:warnings", *MODULES[path]]
            t0 = time.perf_counter()
            try:
                target.write_text(_mutated(path, line, index))
                proc = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True, timeout=args.timeout)
                status = "survived" if proc.returncode == 0 else "killed"
            except subprocess.TimeoutExpired:
                status = "timeout"
            finally:
                target.write_text(original)
            why = equivalent(path, old, new)
            s = score[path]
            s[0] += status != "survived"
            s[1] += 1
            s[2] += bool(why) and status == "survived"
            row = {"path": path, "line": line, "index": index, "old": old, "new": new, "status": status,
                   "seconds": round(time.perf_counter() - t0, 1)}
            if why and status == "survived":
                row["equivalent"] = why
            fh.write(json.dumps(row) + "\n")
            fh.flush()
            tag = "survived (equivalent)" if row.get("equivalent") else status
            print(f"{tag:8} {path}:{line}:{index} {old[:60]!r} -> {new[:60]!r}", flush=True)
    ok = True
    for path, (killed, run, eq) in score.items():
        share = killed / (run - eq) if run > eq else 1.0
        print(f"{path}: killed {killed}/{run}, {eq} equivalent: {100 * share:.0f} % of the non-equivalent")
        ok &= share >= args.target
    if not args.changed:
        print(f"killed {sum(s[0] for s in score.values())}/{sum(s[1] for s in score.values())}")
        return 0 if all(s[0] + s[2] == s[1] for s in score.values()) else 1
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
