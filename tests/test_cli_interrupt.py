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


def _handlers_installed(pid: int) -> bool:
    """The command's own handlers are installed: SIGTERM and SIGHUP are caught (``SigCgt`` of /proc/PID/status;
    the interpreter itself catches only SIGINT, so these two bits are stability.runtime.interrupts')."""
    with open(f"/proc/{pid}/status") as fh:
        mask = next(int(line.split()[1], 16) for line in fh if line.startswith("SigCgt:"))
    return all(mask >> (int(getattr(signal, n)) - 1) & 1 for n in ("SIGTERM", "SIGHUP"))


def _wait_until_ready(proc, timeout: float = 60.0) -> None:
    """Poll (every 2 ms) until the command's handlers are installed: a readiness condition, not a delay."""
    deadline = time.monotonic() + timeout             # a watchdog for a hung start, not a measured time
    while not _handlers_installed(proc.pid):
        assert proc.poll() is None, "the command ended before installing its handlers"
        assert time.monotonic() < deadline, "the handlers were never installed"
        time.sleep(0.002)


@pytest.mark.slow
@pytest.mark.skipif(not os.path.exists("/proc/self/status"), reason="reads the signal mask from /proc")
@pytest.mark.parametrize("signum,when", [("SIGINT", "ready"), ("SIGTERM", "ready"), ("SIGHUP", "ready"),
                                         ("SIGTERM", 3.0), ("SIGHUP", 3.0)])
def test_every_signal_from_the_first_line_exits_130_with_one_line_and_no_file(signum, when, tmp_path):
    """As soon as the handlers are installed (the first line of ``stability``, imports still under way) and during
    the work (3 s after that): one line, status 130, no partial or hidden file."""
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen([sys.executable, "-m", "stability.simulate", "--scheme", "adaptive", "--horizon", "3600",
                             "--rtol", "1e-10", "--atol", "1e-12", "--sample", "1", "--no-stop-on-warnings", "--csv", "out.csv",
                             "--json-file", "out.json"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    _wait_until_ready(proc)
    if when != "ready":
        time.sleep(when)                  # into the work: a 3600 s adaptive run cannot end in 3 s
    assert proc.poll() is None, "the command finished before it could be interrupted"
    proc.send_signal(getattr(signal, signum))
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, (proc.returncode, err)
    assert [line for line in err.splitlines() if line.strip()] == ["error: interrupted"], err
    assert sorted(os.listdir(tmp_path)) == [], "a partial or temporary file was left behind"
