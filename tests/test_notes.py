"""Library warnings become notes (stability.runtime.notes): one ``note:`` line per distinct message inside a command line,
a NumericalNote (not a raw RuntimeWarning) from the API; the assist's margins no longer leak numpy's overflow."""

from __future__ import annotations

import warnings

import pytest

from stability.runtime import notes


def test_runtime_warnings_become_one_note_each_and_others_pass():
    with notes.collect() as got, warnings.catch_warnings(record=True) as passed:
        warnings.simplefilter("always")
        with notes.library_warnings("a search", "its candidate is discarded"):
            for _ in range(3):
                warnings.warn("overflow encountered in multiply", RuntimeWarning, stacklevel=2)
            warnings.warn("divide by zero encountered in divide", RuntimeWarning, stacklevel=2)
            warnings.warn("something else", UserWarning, stacklevel=2)
    assert got == ["a search: overflow encountered in multiply; its candidate is discarded",
                   "a search: divide by zero encountered in divide; its candidate is discarded"]
    assert [str(w.message) for w in passed] == ["something else"]


def test_outside_a_command_a_note_is_a_numerical_note_warning():
    with pytest.warns(notes.NumericalNote, match="a search: overflow"):
        with notes.library_warnings("a search", "discarded"):
            warnings.warn("overflow encountered in multiply", RuntimeWarning, stacklevel=2)


def test_assist_margins_raise_no_runtime_warning():
    """python-control's margin search overflows at a spurious root near 1e15 rad/s on some machines; the API
    turns that into a NumericalNote, so a caller treating RuntimeWarning as an error still gets the margins."""
    from stability import assist
    from stability.assist.design import loop_margins
    from stability.chair import preset

    sched = assist.schedule(preset("power-fwd"), [1.0, 2.0, 3.0], "gyro")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        warnings.simplefilter("ignore", notes.NumericalNote)
        margins = [loop_margins(d) for d in sched.designs]
    assert all(m.phase_margin_deg > 30 for m in margins)


def test_assist_prints_only_notes_on_stderr(capsys):
    """A cheap assist run (two speeds, no nonlinear checks): stderr holds only ``note:`` lines, no raw warning."""
    from stability.assist.__main__ import main

    assert main(["--speeds", "1,2", "--no-check"]) == 0
    err = capsys.readouterr().err
    assert all(line.startswith("note: ") for line in err.splitlines()), err
    assert "Warning" not in err


@pytest.mark.slow
def test_default_assist_prints_only_notes_on_stderr(capsys):
    """The default assist run (about 20 s: every check)."""
    from stability.assist.__main__ import main

    assert main([]) == 0
    err = capsys.readouterr().err
    assert all(line.startswith("note: ") for line in err.splitlines()), err
