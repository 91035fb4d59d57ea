"""The subpackages' public functions refuse a wrong first argument as the top-level API does (issue 34).

Every function a subpackage of :mod:`stability` lists in its ``__all__`` whose first parameter is ``chair``,
``chairs`` or ``layout`` is called with a preset's *name* where the object belongs (the most common slip:
``tipping.tip_angles("ej-premier")``), with no other argument.  The contract is the one-line TypeError naming the
parameter and the value, raised before any work; before this test the same calls ended in an AttributeError deep
in the body (``'str' object has no attribute 'x_main'``), or in a TypeError about a missing argument, which names
neither.  The list is built by introspection, so a new public function is covered when it is exported.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import numpy as np
import pytest

import stability
from stability import linear

#: Subpackages not scanned: the command lines' and the app's internals (their inputs are parsed text, checked by
#: the settings tables), the report's page builders (internal: fed by computed results), the generated code.
SKIP_PACKAGES = ("stability.cli", "stability.app", "stability.report", "stability._generated")
#: Functions whose first argument may legitimately be something else, with the reason.
NOT_AN_OBJECT = {
    "stability.chair.model.check_chair": "the check itself",
    "stability.assist.destabilising.destabilising_moment": "documented to take a preset name as well (Chair | str)",
    "stability.uncertainty.propagation.propagate": "duck-typed: any object with the uncertain fields as attributes and "
                                                   "replace() (a Chair, a layout's LayoutDraw)",
    "stability.uncertainty.propagation.delta_method": "duck-typed like propagate",
    "stability.slope.equilibrium.drive_report": "the chair is not read (the equilibrium holds the forces); a layout's "
                                                "report passes None",
}
FIRST = ("chair", "chairs", "layout")


def _exported():
    """Every object a scanned subpackage lists in its ``__all__``."""
    for info in pkgutil.walk_packages(stability.__path__, "stability."):
        if not info.ispkg or info.name.startswith(SKIP_PACKAGES):
            continue
        module = importlib.import_module(info.name)
        for attr in getattr(module, "__all__", ()):
            yield getattr(module, attr, None)


def _public_functions():
    seen = {}
    for f in _exported():
            if not inspect.isfunction(f):
                continue
            key = f"{f.__module__}.{f.__qualname__}"
            params = list(inspect.signature(f).parameters)
            if key not in NOT_AN_OBJECT and params and params[0] in FIRST:
                seen[key] = (f, params[0])
    return seen


PUBLIC = _public_functions()


def test_the_scan_finds_the_public_functions():
    """Guards the introspection itself: the families the issue names are in the list (a scan that found nothing
    would pass every case below vacuously)."""
    names = set(PUBLIC)
    for expected in ("stability.tipping.angles.tip_angles", "stability.advise.advisor.advise",
                     "stability.study.impulse.critical_impulse", "stability.linear.model.state_matrices",
                     "stability.layout.linear.analyse_layout", "stability.assist.design.design"):
        assert expected in names
    assert len(PUBLIC) >= 60


@pytest.mark.parametrize("key", sorted(PUBLIC))
def test_a_preset_name_instead_of_the_object_is_refused_by_name(key):
    f, first = PUBLIC[key]
    with pytest.raises(TypeError) as info:
        f("ej-premier")
    message = str(info.value)
    assert message.startswith(f"{first}='ej-premier' is invalid"), message
    assert "\n" not in message


@pytest.mark.parametrize("key", sorted(k for k, (_, first) in PUBLIC.items() if first == "chairs"))
def test_a_wrong_element_of_chairs_is_named_by_its_index(key):
    f, _ = PUBLIC[key]
    with pytest.raises(TypeError, match=r"^chairs\[1\]=3 is invalid"):
        f([stability.preset("ej-premier"), 3])


def test_the_keyword_form_is_checked_too():
    from stability.tipping import tip_angles
    with pytest.raises(TypeError, match=r"^chair=None is invalid"):
        tip_angles(chair=None)


@pytest.mark.parametrize("bad", [float("nan"), -0.5, 10**400, "fast"])
def test_speed_arguments_of_the_linear_helpers_are_checked(bad):
    """Two helpers computed with any speed (a NaN gave NaN; a negative speed a meaningless rate): refused with
    the speed's range."""
    c = stability.preset("ej-premier")
    for call in (lambda: linear.lateral_force_input(c, bad), lambda: linear.massless_caster_rate(c, bad),
                 lambda: linear.massless_caster_rate(c, np.array([0.5, bad], dtype=object))):
        with pytest.raises(ValueError, match=r"^speed=.* is invalid; valid range: (every speed a number, )?0.01 <= speed"):
            call()


#: Exported dataclasses that are not values, with the reason.
MUTABLE = {"stability.study.search.Problem": "a search's state, filled point by point as the runs come back"}


def test_the_exported_records_are_frozen():
    """A result or an input record that a subpackage exports is a value: it is compared, cached and shared between
    callers (a preset's derived tables, memoised measures), so assigning a field after it is made must raise
    (``frozen=True``).  The scan guards itself: the records of the families the tests name are in it."""
    import dataclasses

    records = {f"{c.__module__}.{c.__qualname__}": c for c in _exported()
               if isinstance(c, type) and dataclasses.is_dataclass(c)}
    assert {"stability.slope.equilibrium.HandRim", "stability.study.impulse_intervals.CriticalImpulseInterval",
            "stability.tipping.angles.TipAngles"} <= set(records)
    mutable = sorted(k for k, c in records.items() if not c.__dataclass_params__.frozen)
    assert mutable == sorted(k for k in MUTABLE if k in records), mutable

