"""The equations step of the compiled kernels (numba): the generated equations, the pin moments, the layouts.

The generated functions of :mod:`stability.models.full_width` and
:mod:`stability.models.slope` compiled as they are, the accelerations of a
step with given pin moments, with held (locked or stuck) casters, and under
the stick-slip pin friction law; and the array layouts the engine writes.
Shared by :mod:`stability.simulate.kernel` (which re-exports every name) and
:mod:`stability.simulate.adaptive_kernel`; their cached code is flushed when
this file changes (:data:`stability.simulate.cache_stamp.KERNEL_SOURCES`).
"""

from __future__ import annotations

import types
from typing import Any

from numba import njit
from numba.core import cgutils
from numba.core import types as _nbtypes
from numba.extending import intrinsic, overload

from stability.models.forces import generated as _fo
from stability.models.full_width import generated as _fw
from stability.models.slope import generated as _sl
from stability.simulate import kernel_link
from stability.simulate.kernel_link import LinkOnlyCompiler
from stability.tires import law as _tire_law

__all__ = ["accelerations", "model_accelerations", "by_model", "leading", "borrowed", "held_pins", "stick_slip",
           "compiled", "DRIVE_D", "DRIVE_E", "normal_loads", "tire_resultant", "tire_moment", "slip_angle",
           "kinetic_pin_moment", "pin_holds", "break_away_moment", "rest_rate", "lateral_force", "camber_force",
           "rolling_force", "SLOPE_MODEL", "STOP_LEVEL", "SETTLE", "SETTLE_WINDOW", "EXTERNAL_MZ", "NCFG", "NPARAM",
           "NSTATE", "ST_THEDD", "ST_FC1", "ST_FC2", "ST_PREV", "ST_TPREV", "ST_NEXTK", "ST_MZ", "ST_NREC", "ST_TRACK",
           "STOPPED_WARNINGS", "STOPPED_LEVEL", "STOPPED_NONFINITE", "STOPPED_SETTLED", "X_M", "X_P", "D1", "D2", "T1",
           "T2", "TRAIL", "L1", "H", "M", "M_C", "I_Z", "I_ZP", "G", "ROLL_K", "PIN_DAMP", "MAF", "MBF", "U0", "V0",
           "ETA0", "BETA0", "FCIMP", "CT", "ST", "TOE", "SLOPE", "C_PHI", "S_PHI", "C_THETA", "S_THETA", "NREC_ALL",
           "NREC_STATES", "cv_exact", "cv_thesis", "acc_exact", "acc_thesis", "acc_slope", "gravity_body"]

# Every helper is its own numba function, compiled once and shared by both kernels. The step's helpers are
# inlined by LLVM (forceinline: as fast as numba-IR inlining, without a copy of the callee's IR per call site,
# which made inline="always" cost about 3x the compile time); no Python wrapper unless Python calls it.
_NOWRAP: dict[str, Any] = dict(no_cpython_wrapper=True, no_cfunc_wrapper=True)   # options numba's stubs omit
#: no reference counting (numba's NRT off, a jit option): for the step's entry and helpers, which allocate no array
#: and return none (their callers hold the arrays; the step's are views without a count, :func:`borrowed`).  numba
#: otherwise emits an increment and a decrement for every assignment of a variable, walking each member of a tuple
#: (the parameter tuple's 18): about a tenth of the first use's CPU (measured), for code that does nothing on such
#: views.  A function that allocates cannot be compiled so (numba refuses); one that returned an array would hand its
#: caller a reference it never counted
_NOREF: dict[str, Any] = dict(_nrt=False)
#: compiled for linking into the entries only: no module-wide optimisation nor machine code of their own
#: (:mod:`stability.simulate.kernel_link`)
_LINK: dict[str, Any] = dict(pipeline_class=LinkOnlyCompiler) if kernel_link.AVAILABLE else {}
_int = njit(cache=True, nogil=True, **_NOWRAP, **_NOREF, **_LINK)                      # called from compiled code only
_inl = njit(cache=True, nogil=True, forceinline=True, **_NOWRAP, **_NOREF, **_LINK)    # inlined into the step by LLVM
_inl_py = njit(cache=True, nogil=True, forceinline=True)             # the same, also called from Python (tests)
#: the per-model overloads' options: literal dispatch, and no wrappers for their implementations (numba's default
#: gives each a C-callable wrapper that LLVM optimises and emits though nothing calls it), nor reference counts
_OVERLOAD: dict[str, Any] = dict(prefer_literal=True, jit_options=dict(_NOWRAP, **_NOREF, **_LINK))


def compiled(module: types.ModuleType, names: tuple[str, ...], decorator: Any,
             overrides: dict[str, Any] | None = None) -> types.SimpleNamespace:
    """The functions ``names`` of a plain-Python ``module`` compiled as they are, calling each other compiled.

    Each function is copied into one shared namespace (the module's globals)
    in which every name of ``names`` is its compiled version, so that a call
    between them resolves to compiled code (numba cannot call a Python
    function).  The module itself is untouched: Python callers keep the
    originals, which run on floats and numpy arrays.

    Parameters
    ----------
    module : module
        A module of plain arithmetic functions (generated equations, the tire law).
    names : tuple of str
        The functions to compile.
    decorator : callable
        numba's ``njit`` with the options of the caller.
    overrides : dict, optional
        Further names of the shared namespace (the lanes kernel's: :mod:`math`
        with its polynomial trigonometry, the lane versions of the functions
        these call).  A name of ``names`` that is a numba dispatcher is
        compiled again from its Python function.

    Returns
    -------
    types.SimpleNamespace
        The compiled functions by name.
    """
    ns = dict(vars(module))
    ns.update(overrides or {})
    out = {}
    for name in names:
        f = getattr(module, name)
        f = getattr(f, "py_func", f)
        ns[name] = out[name] = decorator(types.FunctionType(f.__code__, ns, name, f.__defaults__, f.__closure__))
    return types.SimpleNamespace(**out)


#: the tire force law of :mod:`stability.tires.law` (what Tire.lateral_force evaluates), compiled
_tires = compiled(_tire_law, ("cubic", "segment_force", "lateral_force", "camber_force", "rolling_resistance",
                              "rolling_force"), _inl)
lateral_force = _tires.lateral_force
camber_force = _tires.camber_force
rolling_force = _tires.rolling_force
cv_exact = _int(_fw.contact_velocities_exact)
cv_thesis = _int(_fw.contact_velocities_thesis)
acc_exact = _int(_fw.accelerations_exact)
acc_thesis = _int(_fw.accelerations_thesis)
# the chair on a plane (stability.models.slope): in-plane gravity on every body
acc_slope = _int(_sl.accelerations_slope_exact)
gravity_body = _int(_sl.gravity_body)
#: the contact forces (stability.models.forces): normal loads, resultant, yaw moment, slip angle, pin friction
#: (bound to names of this module: numba resolves module globals, not attributes of a namespace)
_forces = compiled(_fo, tuple(_fo.__all__), _inl)
normal_loads = _forces.normal_loads
tire_resultant = _forces.tire_resultant
tire_moment = _forces.tire_yaw_moment
slip_angle = _forces.slip_angle
kinetic_pin_moment = _forces.kinetic_pin_moment
pin_holds = _forces.pin_holds
break_away_moment = _forces.break_away_moment
rest_rate = _forces.rest_rate

# Params vector layout (stability.models.params.Params order)
X_M, X_P, D1, D2, T1, T2, TRAIL, L1, H, M, M_C, I_Z, I_ZP, G, ROLL_K, PIN_DAMP, MAF, MBF = range(18)
#: a run's parameters (the row's length)
NPARAM = MBF + 1
# per-run scalars: u0, v0, eta0, beta0, impulse force, cos(toe), sin(toe), toe flag
U0, V0, ETA0, BETA0, FCIMP, CT, ST, TOE = range(8)
#: per-run slots: constant drive forces on the left and right main wheels along their headings, N (0 in
#: simulations; the linearisation about a slope's equilibrium holds the drive that keeps it, as the statics)
DRIVE_D, DRIVE_E = 8, 9
# cfg slots of the plane: flag, cos/sin of the cross slope, cos/sin of the grade
SLOPE, C_PHI, S_PHI, C_THETA, S_THETA = range(13, 18)
#: cfg slot: every run stops at ``levels[cfg[18]]`` (-1: never); ``status[0]``: 1 warning rule, 2 that level,
#: 3 the yaw rate left the finite numbers (NaN or infinite: the peak is then NaN, never a finite answer)
STOP_LEVEL, STOPPED_WARNINGS, STOPPED_LEVEL, STOPPED_NONFINITE = 18, 1.0, 2.0, 3.0
#: cfg slot: a run with a stop level and stick-slip friction also stops when it has settled (``status[0]`` 4):
#: after the push, both casters stuck for :data:`SETTLE_WINDOW` s and neither ``|yaw rate|`` nor either holding
#: moment larger than at the middle of that window (docs/studies.md: it then never reaches the level)
SETTLE, STOPPED_SETTLED, SETTLE_WINDOW = 19, 4.0, 0.5
#: cfg slot: 1.0 when the yaw moment is the caller's (``state[ST_MZ]``, a Python input set between steps)
EXTERNAL_MZ = 20
#: the configuration row's length (``engine._config``)
NCFG = EXTERNAL_MZ + 1
#: a run's state between kernel calls: the ten states in :class:`~stability.simulate.results.ChairState`'s order
#: (0-9), the lagged yaw acceleration, the previous step's force sums, the summaries' previous sample (|yaw rate|,
#: time), the controller's next sample and held output (or the caller's yaw moment), the rows recorded, the settle
#: tracker (5); the controller's states follow (``NSTATE`` on)
ST_THEDD, ST_FC1, ST_FC2, ST_PREV, ST_TPREV, ST_NEXTK, ST_MZ, ST_NREC, ST_TRACK = range(10, 19)
NSTATE = ST_TRACK + 5
#: model codes: 0 thesis, 1 exact, 2 exact on a slope (accelerations with in-plane gravity)
SLOPE_MODEL = 2
#: recorded columns after t (COLUMNS[1:]); the first 10 are the states
NREC_ALL, NREC_STATES = 31, 10


@intrinsic
def borrowed(typingctx, arr):
    """A view of the array ``arr`` without a reference count (``arr`` must outlive it): the same array with no
    meminfo (nor parent object).

    numba counts references to an array passed into a function with atomic operations that LLVM cannot remove, a
    pair per call: the step's helpers (MECHAN and the tire law, with their tables) took one pair per array and call,
    every step, which cost about a fifth of a run where the arrays are counted (a run called from Python; the
    parallel loop's runs are views without a count).  They also kept the lanes kernel's tire law from being
    vectorised.  A view without a meminfo has no count to keep.  An intrinsic, so that nothing is compiled for it.
    """
    if not isinstance(arr, _nbtypes.Array):
        return None

    def codegen(context, builder, sig, args):
        ary = context.make_array(sig.args[0])(context, builder, value=args[0])
        ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
        ary.parent = cgutils.get_null_value(ary.parent.type)
        return ary._getvalue()

    return arr(arr), codegen


@intrinsic
def leading(typingctx, arr, n):
    """The first ``n`` elements of the 1-D array ``arr`` as a tuple (``n`` a compile-time constant, at most the
    array's length; read without a bounds check, as numba's indexing).

    The step reads its parameter row (:data:`NPARAM`: P as a tuple, indexed as the row), its configuration row
    (:data:`NCFG`) and a run's state (the ten states and the slots before :data:`ST_TRACK`) so.  A tuple has no
    reference count to keep when passed to a helper, and each of numba's array reads is typed and lowered on its
    own (about 1.5 ms of the first use's compile each, 40 in the step); an intrinsic compiles nothing of its own.
    """
    if not (isinstance(arr, _nbtypes.Array) and arr.ndim == 1 and isinstance(n, _nbtypes.IntegerLiteral)):
        return None
    tup = _nbtypes.UniTuple(arr.dtype, n.literal_value)

    def codegen(context, builder, sig, args):
        aryty = sig.args[0]
        ary = context.make_array(aryty)(context, builder, value=args[0])
        return context.make_tuple(builder, tup, [context.unpack_value(builder, aryty.dtype, cgutils.get_item_pointer(
            context, builder, aryty, ary, [context.get_constant(_nbtypes.intp, i)], wraparound=False))
            for i in range(tup.count)])

    return tup(arr, n), codegen


@_int
def held_pins(model, s, F, ma, mb, hold_a, hold_b, fy_ext, mz, rdc, P, g1, g2):
    """Accelerations with the casters flagged ``hold_*`` held (locked or stuck): ``(acc, M_A, M_B)``.

    A held caster's pin moment keeps its swivel acceleration zero (the
    accelerations are affine in the pin moments: two or three evaluations);
    the other keeps the moment given.  ``rdc``: the thesis variant's lagged
    yaw acceleration (WCHAIR scheme), or None (adaptive scheme).
    """
    if not (hold_a or hold_b):
        return model_accelerations(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2), ma, mb
    if hold_a and hold_b:
        a0 = model_accelerations(model, s, F, 0.0, 0.0, fy_ext, mz, rdc, P, g1, g2)
        a1 = model_accelerations(model, s, F, 1.0, 0.0, fy_ext, mz, rdc, P, g1, g2)
        a2 = model_accelerations(model, s, F, 0.0, 1.0, fy_ext, mz, rdc, P, g1, g2)
        k11, k21 = a1[3] - a0[3], a1[4] - a0[4]
        k12, k22 = a2[3] - a0[3], a2[4] - a0[4]
        det = k11 * k22 - k12 * k21
        ma = (-a0[3] * k22 + a0[4] * k12) / det
        mb = (-a0[4] * k11 + a0[3] * k21) / det
        ud = a0[0] + ma * (a1[0] - a0[0]) + mb * (a2[0] - a0[0])
        vd = a0[1] + ma * (a1[1] - a0[1]) + mb * (a2[1] - a0[1])
        rd = a0[2] + ma * (a1[2] - a0[2]) + mb * (a2[2] - a0[2])
        return (ud, vd, rd, 0.0, 0.0), ma, mb
    if hold_a:
        a0 = model_accelerations(model, s, F, 0.0, mb, fy_ext, mz, rdc, P, g1, g2)
        a1 = model_accelerations(model, s, F, 1.0, mb, fy_ext, mz, rdc, P, g1, g2)
        r = -a0[3] / (a1[3] - a0[3])
        return ((a0[0] + r * (a1[0] - a0[0]), a0[1] + r * (a1[1] - a0[1]), a0[2] + r * (a1[2] - a0[2]), 0.0,
                 a0[4] + r * (a1[4] - a0[4])), r, mb)
    a0 = model_accelerations(model, s, F, ma, 0.0, fy_ext, mz, rdc, P, g1, g2)
    a1 = model_accelerations(model, s, F, ma, 1.0, fy_ext, mz, rdc, P, g1, g2)
    r = -a0[4] / (a1[4] - a0[4])
    return ((a0[0] + r * (a1[0] - a0[0]), a0[1] + r * (a1[1] - a0[1]), a0[2] + r * (a1[2] - a0[2]),
             a0[3] + r * (a1[3] - a0[3]), 0.0), ma, r)


@_int
def stick_slip(model, s, F, fy_ext, mz, rdc, P, g1, g2):
    """Accelerations and pin moments under stick-slip Coulomb friction: ``(acc, M_A, M_B)``.

    A swivelling caster (rate not zero) gets the kinetic moment against its
    rate, as in WCHAIR.  A caster at rest stays at rest while the moment
    that holds it is within its friction limit (Karnopp's stick phase);
    otherwise it breaks away with the limit moment in the holding moment's
    direction.  Holding one caster changes the other's holding moment, so a
    break-away is decided again with the other's new moment.
    """
    ed, bd = s[7], s[8]
    ma = kinetic_pin_moment(ed, P[MAF])
    mb = kinetic_pin_moment(bd, P[MBF])
    ha, hb = ed == 0.0, bd == 0.0
    for _ in range(3):
        if not (ha or hb):
            break
        acc, ra, rb = held_pins(model, s, F, ma, mb, ha, hb, fy_ext, mz, rdc, P, g1, g2)
        free_a = ha and not pin_holds(ra, P[MAF])
        free_b = hb and not pin_holds(rb, P[MBF])
        if not (free_a or free_b):
            return acc, ra, rb
        if free_a:
            ma, ha = break_away_moment(ra, P[MAF]), False
        if free_b:
            mb, hb = break_away_moment(rb, P[MBF]), False
    return model_accelerations(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2), ma, mb


@_int
def accelerations(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2):
    """The generated accelerations of the model.

    0 thesis (with the lagged yaw acceleration ``rdc``), 1 exact, 2 exact on a
    plane with the in-plane gravity ``g1, g2`` (m/s^2) on every body.  The
    model is chosen at run time; compiled code calls
    :func:`model_accelerations`, which compiles only the model a literal
    ``model`` names.
    """
    if model == SLOPE_MODEL:
        return _acc_slope(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2)
    if model == 0:
        return _acc_thesis(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2)
    return _acc_exact(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2)


@_inl
def _acc_thesis(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2):
    u, v, r, ce, se, cb, sb, ed, bd = s
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    return acc_thesis(u, v, r, ce, se, cb, sb, ed, bd, FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, ma, mb,
                      fy_ext, mz, P[X_M], P[X_P], P[D1], P[D2], P[T1], P[T2], P[TRAIL], P[L1], P[M],
                      P[M_C], P[I_Z], P[I_ZP], rdc)


@_inl
def _acc_exact(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2):
    u, v, r, ce, se, cb, sb, ed, bd = s
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    return acc_exact(u, v, r, ce, se, cb, sb, ed, bd, FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, ma, mb,
                     fy_ext, mz, P[X_M], P[X_P], P[D1], P[D2], P[T1], P[T2], P[TRAIL], P[L1], P[M],
                     P[M_C], P[I_Z], P[I_ZP])


@_inl
def _acc_slope(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2):
    u, v, r, ce, se, cb, sb, ed, bd = s
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    return acc_slope(u, v, r, ce, se, cb, sb, ed, bd, FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, ma, mb,
                     fy_ext, mz, g1, g2, P[X_M], P[X_P], P[D1], P[D2], P[T1], P[T2], P[TRAIL], P[L1], P[M],
                     P[M_C], P[I_Z], P[I_ZP])


def model_accelerations(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2):
    """:func:`accelerations` for compiled code only (numba chooses the implementation when compiling the caller).

    With ``model`` a numba integer literal (the WCHAIR kernel's entry points)
    the call compiles that model's generated accelerations alone; with a
    run-time integer it is :func:`accelerations`, all three behind a branch.

    Parameters
    ----------
    model : int
        0 thesis, 1 exact, :data:`SLOPE_MODEL`.
    s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2
        As :func:`accelerations`'s (moments N m, forces N, gravity m/s^2).

    Returns
    -------
    tuple of float
        The accelerations (m/s^2, rad/s^2).
    """
    raise NotImplementedError("compiled code only (numba overload)")


def by_model(model: Any, impls: tuple[Any, Any, Any], generic: Any) -> Any:
    """numba overload helper: the implementation of a call for its model.

    Parameters
    ----------
    model : numba type
        The call's model argument's type.
    impls : tuple of numba dispatcher
        Thesis, exact, slope: each with the overloaded function's parameters.
    generic : numba dispatcher
        The run-time branching version.

    Returns
    -------
    function
        The Python function of ``impls[code]`` for a literal model code, else of ``generic``, compiled as the
        call's implementation.
    """
    chosen = impls[model.literal_value] if isinstance(model, _nbtypes.IntegerLiteral) else generic
    return chosen.py_func


@overload(model_accelerations, **_OVERLOAD)
def _model_accelerations(model, s, F, ma, mb, fy_ext, mz, rdc, P, g1, g2):
    return by_model(model, (_acc_thesis, _acc_exact, _acc_slope), accelerations)
