"""Long work shows progress off a terminal too (the standard; the user-journey review, friction 13)."""

from __future__ import annotations

import io

from stability.runtime import progress as P


class Clock:
    def __init__(self) -> None:
        self.t = 0.0

    def __call__(self) -> float:
        return self.t


def test_long_work_off_a_terminal_prints_lines(monkeypatch):
    clock = Clock()
    monkeypatch.setattr(P.time, "perf_counter", clock)
    out = io.StringIO()                                    # not a TTY
    with P.ProgressBar(100, "runs", file=out, unit="run") as bar:
        for _ in range(100):
            clock.t += 0.25                                # 25 s in all
            bar.update()
    lines = out.getvalue().splitlines()
    # one line each LINE_EVERY_S (10 s and 20 s), and the last one at the end
    assert lines == ["runs: 40/100 run, 10 s", "runs: 80/100 run, 20 s", "runs: 100/100 run, 25 s"]


def test_short_work_and_quiet_print_nothing(monkeypatch):
    clock = Clock()
    monkeypatch.setattr(P.time, "perf_counter", clock)
    for ctx, step in ((P.quiet(False), 0.01), (P.quiet(True), 1.0)):
        out = io.StringIO()
        with ctx, P.ProgressBar(100, "runs", file=out) as bar:
            for _ in range(100):
                clock.t += step
                bar.update()
        assert out.getvalue() == ""
    out = io.StringIO()
    with P.ProgressBar(100, "runs", file=out, enabled=False) as bar:
        for _ in range(100):
            clock.t += 1.0
            bar.update()
    assert out.getvalue() == ""
