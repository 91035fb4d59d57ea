"""The garbage collector of a command line (stability.runtime.collector): the youngest generation's threshold raised
while a command imports, the objects alive when it starts frozen and the threshold kept raised for its run, the
collector still collecting what the computation makes; nothing in a library or test process.  Each process-changing case runs in
its own interpreter (a freeze in this one would keep the test session's objects)."""

from __future__ import annotations

import gc
import subprocess
import sys

from stability.runtime import collector


def _probe(code: str) -> list[str]:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return out.stdout.split()


def test_settle_without_a_deferral_does_nothing():
    """A library or test process: no threshold changed, nothing frozen."""
    before, frozen = gc.get_threshold(), gc.get_freeze_count()
    assert collector.settle() is False
    assert gc.get_threshold() == before and gc.get_freeze_count() == frozen and gc.isenabled()


def test_defer_then_settle_freezes_and_sets_the_run_threshold():
    code = ("import gc; from stability.runtime import collector as c; t = gc.get_threshold(); "
            "print(c.defer_for_imports(), gc.get_threshold()[0] == max(c.IMPORT_THRESHOLD, t[0]), "
            "gc.get_threshold()[1:] == t[1:], c.defer_for_imports()); "
            "print(c.settle(), gc.get_threshold() == (max(c.RUN_THRESHOLD, t[0]), *t[1:]), "
            "gc.get_freeze_count() > 0, gc.isenabled(), c.settle())")
    assert _probe(code) == ["True", "True", "True", "False", "True", "True", "True", "True", "False"]


def test_no_deferral_when_the_collector_is_off():
    code = ("import gc; gc.disable(); from stability.runtime import collector as c; t = gc.get_threshold(); "
            "print(c.defer_for_imports(), gc.get_threshold() == t, c.settle(), gc.get_freeze_count())")
    assert _probe(code) == ["False", "True", "False", "0"]


def test_a_cycle_made_after_settling_is_still_collected():
    """Freezing keeps the imports' objects out of the traversals, not the computation's: a reference cycle made
    after :func:`settle` is freed by the next collection (found through a weak reference)."""
    code = ("import gc, weakref; from stability.runtime import collector as c; c.defer_for_imports(); c.settle()\n"
            "class Node: pass\n"
            "a, b = Node(), Node(); a.other, b.other = b, a; r = weakref.ref(a); del a, b\n"
            "print(r() is not None, gc.collect() > 0, r() is None)")
    assert _probe(code) == ["True", "True", "True"]


def test_a_command_line_process_defers_and_its_command_settles():
    """``python -m stability.X`` imports the package with ``sys.argv[0] == "-m"``: the threshold is raised
    then, and :func:`stability.cli.run` settles before the command's work (inside it the youngest threshold is
    the run's and the imports' objects frozen); a plain ``import stability`` changes nothing."""
    code = ("import gc, sys; t = gc.get_threshold(); sys.argv[0] = '-m'; import stability, argparse; "
            "from stability.runtime.collector import IMPORT_THRESHOLD, RUN_THRESHOLD; "
            "print(gc.get_threshold()[0] == max(IMPORT_THRESHOLD, t[0]), gc.get_freeze_count() == 0); "
            "from stability.cli import run; seen = []; "
            "status = run(argparse.ArgumentParser(), [], lambda a: seen.append((gc.get_threshold() == "
            "(max(RUN_THRESHOLD, t[0]), *t[1:]), "
            "gc.get_freeze_count() > 0))); print(status, *seen[0])")
    assert _probe(code) == ["True", "True", "0", "True", "True"]
    plain = "import gc; t = gc.get_threshold(); import stability; print(gc.get_threshold() == t)"
    assert _probe(plain) == ["True"]
