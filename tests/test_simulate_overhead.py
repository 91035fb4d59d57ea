"""The Python around one compiled run (issue 36): the packed chair rows and the times kept between calls, a
checked run spec not checked again, the step flags set when the results are built.  None of it may change a
number: every run here is compared bit for bit with the compiled kernel called directly on arrays packed as
before the caches (each chair's parameters and tire slots built afresh: ``parameters``,
``Packed._tire_arrays``), in the same test run."""

import math

import numpy as np
import pytest

from stability import tires
from stability.chair import preset
from stability.models.params import parameters
from stability.settings.run import RunSpec
from stability.simulate import baseline, engine, packing, simulate, simulate_batch
from stability.simulate.controller import SampledController
from stability.simulate.options import initial_velocities, make_options, n_steps
from stability.simulate.results import COLUMNS

EJ = preset("ej-premier")
#: toe, camber and another caster tire: every slot of the packed rows differs from the E&J's defaults
ODD = EJ.replace(toe_deg=1.5, camber_deg=3.0, caster_tire="PU", main_lateral_scale=0.9)


def _direct(chair, speed, run):
    """The kernel called directly: ``(rec (31, n), stats, status)`` of one run, arrays packed without the caches."""
    k = engine._kernel()
    opts = make_options(run)
    P = np.array([parameters(chair)], dtype=float)
    TK, TS, TL, LIM, RK, RC, RS, CAM, CHK = (np.array([a]) for a in packing.Packed._tire_arrays(chair, opts.scheme))
    u0, v0 = initial_velocities(opts, float(speed))
    toe = math.radians(chair.toe_deg)
    S = np.zeros((1, 10))
    S[0, :8] = (u0, v0, opts.eta0, opts.beta0, opts.impulse_force, math.cos(toe), math.sin(toe),
                1.0 if toe != 0 else 0.0)
    steps = n_steps(opts)
    nrec = (steps - 1) // opts.stride + 1
    ctl = SampledController.none().arrays()
    rec = np.full((1, k.NREC_ALL, nrec), np.nan)
    stats = np.full((1, 2 + len(engine.STATS_LEVELS) + 1), np.nan)
    warn, status, counts = np.zeros((1, 3, 3)), np.zeros((1, 6)), np.zeros(1, dtype=np.int64)
    cfg = engine._config(opts, 0, -1)
    k.call_model(k.run_batch, k.variant(cfg, ctl[0]), 0, steps, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg,
                np.array(engine.STATS_LEVELS), *ctl, engine.initial_state(S, ctl), rec, stats, warn,
                status, counts)
    m = int(counts[0])
    return rec[0, :, :m], stats[0], status[0], np.arange(m) * float(opts.stride) * opts.dt


def _same(result, direct):
    rec, stats, status, t = direct
    np.testing.assert_array_equal(result.t, t)
    cols = result._records()
    for i, name in enumerate(COLUMNS[1:], start=1):
        np.testing.assert_array_equal(cols[:, i], rec[i - 1], err_msg=name)
    assert result.stats.peak_abs_yaw_rate == stats[0] and result.stats.peak_time == stats[1]
    assert result.stopped_by_warnings == bool(status[0])


@pytest.mark.parametrize("chair", [EJ, ODD], ids=["ej", "toe-camber-pu"])
def test_one_run_equals_the_kernel_called_directly_cold_and_warm(chair):
    run = RunSpec(horizon=1.0)
    direct = _direct(chair, 0.75, run)
    packing._ROWS.clear()
    engine._times.cache_clear()
    cold = simulate(chair, 0.75, run=run)           # packs the rows, builds the times
    warm = simulate(chair, 0.75, run=run)           # reads them
    _same(cold, direct)
    _same(warm, direct)
    assert cold.settings == warm.settings


def test_a_batch_of_two_chairs_equals_each_run_direct():
    run = RunSpec(horizon=0.5, sample=None)
    out = simulate_batch([EJ, ODD, EJ], [0.6, 0.9, 1.1], run=run.replace(sample=0.001), progress=False)
    for r, (c, u) in zip(out, [(EJ, 0.6), (ODD, 0.9), (EJ, 1.1)], strict=True):
        _same(r, _direct(c, u, run))


def test_a_tire_registered_again_under_its_name_is_packed_anew():
    """The rows are kept per chair and per tire as the registry gives it now: replacing the tire behind a name
    gives that tire's run (the same as naming the new tire directly), not the cached one."""
    name = "KERN36-TEST"
    tires.register(name, tires.get("linear:200"))
    try:
        chair = EJ.replace(main_tire=name)
        first = simulate(chair, 0.75, run=RunSpec(horizon=1.0))
        tires.register(name, tires.get("linear:400"), replace=True)
        second = simulate(chair, 0.75, run=RunSpec(horizon=1.0))
    finally:
        tires.unregister(name)
    np.testing.assert_array_equal(first.yaw_rate, simulate(EJ.replace(main_tire="linear:200"), 0.75,
                                                           run=RunSpec(horizon=1.0)).yaw_rate)
    np.testing.assert_array_equal(second.yaw_rate, simulate(EJ.replace(main_tire="linear:400"), 0.75,
                                                            run=RunSpec(horizon=1.0)).yaw_rate)
    assert not np.array_equal(first.yaw_rate, second.yaw_rate)


def test_packed_rows_are_read_only_and_bounded():
    params, _, rows = packing.chair_rows(EJ, "wchair")
    for a in (params, *rows):
        assert not a.flags.writeable
    for i in range(packing.ROWS_CACHE_SIZE + 5):
        packing.chair_rows(EJ.replace(m=60.0 + 0.01 * i), "wchair")
    assert len(packing._ROWS) <= packing.ROWS_CACHE_SIZE


def test_result_times_are_read_only():
    r = simulate(EJ, 0.75, run=RunSpec(horizon=0.1))
    with pytest.raises(ValueError):
        r.t[0] = 1.0
    with pytest.raises(ValueError):
        r.t.flags.writeable = True


def test_replace_with_the_same_floats_is_the_spec_itself_and_other_values_are_checked():
    run = RunSpec()
    assert run.replace(speed=run.speed) is run
    assert run.replace() is run
    one = run.replace(speed=1)                       # an int: checked and stored as a float
    assert one is not run and type(one.speed) is float and one.speed == 1.0
    assert run.replace(speed=-0.75).reverse          # the reverse shorthand still applies
    with pytest.raises(ValueError, match="speed"):
        run.replace(speed=float("nan"))
    with pytest.raises(ValueError, match="unknown run setting"):
        run.replace(sped=0.75)


def test_kernel_only_is_the_run_packed_afresh():
    """baseline.kernel_only (the baseline of the Python-share measurements) runs exactly the run: every column."""
    run = RunSpec(horizon=1.0)
    rec = baseline.kernel_only(ODD, 0.9, make_options(run))()
    np.testing.assert_array_equal(rec, _direct(ODD, 0.9, run)[0])


def test_kernel_only_refuses_an_unknown_entry_naming_the_valid_ones():
    """baseline.kernel_only's entry is checked before anything is packed or compiled: one message naming it."""
    with pytest.raises(ValueError, match=r"entry='lanes' is invalid; valid values: 'single', 'batch', "
                                         r"'polynomial_trig'"):
        baseline.kernel_only(ODD, 0.9, make_options(RunSpec(horizon=1.0)), entry="lanes")


def test_replace_checks_the_changed_settings_and_all_together_as_the_constructor_does():
    """replace checks only the changed settings (the others were checked) but every joint rule: each result equals
    the spec built from scratch with the same values, and each refusal is the constructor's."""
    run = RunSpec(horizon=2.0, sample=0.01)
    for changes in ({"speed": 1}, {"speed": -0.5}, {"push_force": 10, "model": "thesis"}, {"horizon": 3},
                    {"dt": "auto"}, {"sample": None}, {"stop_on_warnings": False}):
        fields = {**{n: getattr(run, n) for n in ("horizon", "sample")}, **changes}
        assert run.replace(**changes) == RunSpec(**fields), changes
    for changes in ({"horizon": 0.001}, {"dt": 0.5}, {"sample": 0.0015}, {"speed": -1.0, "reverse": True},
                    {"model": "linear"}, {"push_force": float("inf")}):
        with pytest.raises(ValueError) as replaced:
            run.replace(**changes)
        with pytest.raises(ValueError) as built:
            RunSpec(**{"horizon": 2.0, "sample": 0.01, **changes})
        assert str(replaced.value) == str(built.value), changes
