"""Long work says so: a block that runs past the notice time prints its message once on stderr; a quick one, or
one under --quiet, prints nothing (the first-use compile of the simulator uses this)."""

from __future__ import annotations

import io
import time

from stability.runtime import progress


def test_notice_only_when_slow_and_not_quiet():
    out = io.StringIO()
    with progress.notice_if_slow("compiling", after=0.05, file=out):
        time.sleep(0.3)
    assert out.getvalue() == "compiling\n"
    out = io.StringIO()
    with progress.notice_if_slow("compiling", after=5.0, file=out):
        pass
    time.sleep(0.05)
    assert out.getvalue() == ""
    out = io.StringIO()
    with progress.quiet(), progress.notice_if_slow("compiling", after=0.01, file=out):
        time.sleep(0.1)
    assert out.getvalue() == ""


def test_simulator_says_compiling_once_per_process(monkeypatch):
    from stability.simulate import engine

    monkeypatch.setattr(engine, "_FIRST_USE", {"wchair": True, "wchair_load": True, "adaptive_load": True})
    monkeypatch.setattr(engine, "NOTICE_AFTER_S", 0.05)
    said = []
    monkeypatch.setattr(engine, "notice_if_slow", lambda msg, after: _Recorder(said, msg))
    with engine.first_use("wchair_load"):
        time.sleep(0.1)
    with engine.first_use("wchair"):
        time.sleep(0.1)
    assert said == [engine.COMPILE_NOTICE]       # the second block is silent: one notice per process
    assert "first use" in engine.COMPILE_NOTICE


class _Recorder:
    def __init__(self, said, msg):
        self.said, self.msg = said, msg

    def __enter__(self):
        self.said.append(self.msg)

    def __exit__(self, *exc):
        return False
