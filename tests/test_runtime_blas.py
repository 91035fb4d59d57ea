"""One OpenBLAS thread for the command lines (stability.runtime.blas): set before numpy loads, never over the
environment's own value, and a command line's process gets it."""

from __future__ import annotations

import os
import subprocess
import sys

from stability.runtime.blas import VARIABLE, one_thread_for_commands


def test_the_variable_is_set_to_one_before_numpy_loads():
    env: dict[str, str] = {}
    assert one_thread_for_commands(env, {"sys", "os"}) is True
    assert env == {VARIABLE: "1"}


def test_the_environments_own_value_is_kept():
    env = {VARIABLE: "4"}
    assert one_thread_for_commands(env, set()) is False
    assert env == {VARIABLE: "4"}


def test_nothing_is_set_once_numpy_is_loaded():
    env: dict[str, str] = {}
    assert one_thread_for_commands(env, {"numpy"}) is False
    assert env == {}


def test_a_command_line_process_runs_with_one_thread_and_a_library_import_does_not():
    """``python -m stability.X`` imports the package with ``sys.argv[0] == "-m"`` (the Python documentation of
    ``-m``): the package sets the variable then; a plain ``import stability`` (``-c``) leaves it unset.  The
    package's own ``__main__`` check is the command-line branch, run here through runpy as ``-m`` does."""
    env = {k: v for k, v in os.environ.items() if k != VARIABLE}
    probe = ("import os, sys; sys.argv[0] = '-m'; import stability; "
             f"print(os.environ.get('{VARIABLE}'), 'numpy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["1", "False"]
    plain = subprocess.run([sys.executable, "-c", f"import os, stability; print(os.environ.get('{VARIABLE}'))"],
                           env=env, capture_output=True, text=True, check=True)
    assert plain.stdout.strip() == "None"
