"""Ctrl-C during a long command: exit status 130, one line, no partial file (issue 16)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest


@pytest.mark.slow
def test_ctrl_c_exits_130_with_one_line_and_no_file(tmp_path):
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen([sys.executable, "-m", "stability.report", "-o", "out.pdf", "--text", "out.txt",
                             "--no-progress"], cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=env)
    time.sleep(4.0)                      # imports done, the report's computation under way
    assert proc.poll() is None, "the report finished before it could be interrupted"
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, (proc.returncode, err)
    lines = [line for line in err.splitlines() if line.strip()]
    assert lines == ["error: interrupted"], err
    assert sorted(os.listdir(tmp_path)) == [], "a partial or temporary file was left behind"


@pytest.mark.slow
@pytest.mark.parametrize("signum,delay", [("SIGINT", 0.15), ("SIGTERM", 0.15), ("SIGHUP", 0.15),
                                          ("SIGTERM", 3.0), ("SIGHUP", 3.0)])
def test_every_signal_from_the_first_line_exits_130_with_one_line_and_no_file(signum, delay, tmp_path):
    """During the imports (0.15 s) and during the work (3 s): one line, status 130, no partial or hidden file."""
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen([sys.executable, "-m", "stability.simulate", "--scheme", "adaptive", "--horizon", "3600",
                             "--rtol", "1e-10", "--atol", "1e-12", "--sample", "1", "--no-stop-on-warnings", "--csv", "out.csv",
                             "--json-file", "out.json"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    time.sleep(delay)
    assert proc.poll() is None, "the command finished before it could be interrupted"
    proc.send_signal(getattr(signal, signum))
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, (proc.returncode, err)
    assert [line for line in err.splitlines() if line.strip()] == ["error: interrupted"], err
    assert sorted(os.listdir(tmp_path)) == [], "a partial or temporary file was left behind"
