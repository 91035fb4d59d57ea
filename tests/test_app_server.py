"""``python -m stability.app``: its options, and a served page that answers (needs the ``app`` extra)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
import urllib.request

import pytest

from stability.app.server import _is_loopback, main


@pytest.mark.parametrize("argv, fragment", [(["--port", "70000"], "--port 70000 is invalid; valid range: 0 to 65535"),
                                            (["--port", "x"], "--port 'x' is invalid; expected an integer"),
                                            (["--host", "no.such.host.invalid"], "--host 'no.such.host.invalid'")])
def test_bad_options_are_one_line(capsys, argv, fragment):
    try:
        status = main(argv)
    except SystemExit as exc:                   # argparse's own usage errors
        status = exc.code
    assert status == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and fragment in err[0]


def test_loopback_is_the_only_quiet_host():
    assert _is_loopback("127.0.0.1") and _is_loopback("localhost") and _is_loopback("::1")
    assert not _is_loopback("0.0.0.0") and not _is_loopback("192.168.1.4")


@pytest.mark.slow
def test_served_page_answers():
    """A server on a free port answers the page request (a session: the chair's linear views computed)."""
    pytest.importorskip("panel")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen([sys.executable, "-m", "stability.app", "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        line = proc.stdout.readline()           # printed once the port is bound, before serving
        m = re.search(r"(http://127\.0\.0\.1:\d+/)", line)
        assert m, (line, proc.stderr.read() if proc.poll() is not None else "")
        url = m.group(1)
        deadline = time.monotonic() + 60
        while True:
            try:
                with urllib.request.urlopen(url + "?chair=revised&trail=0.055", timeout=30) as r:
                    html = r.read().decode()
                    status = r.status
                break
            except OSError:
                if time.monotonic() > deadline or proc.poll() is not None:
                    raise
                time.sleep(0.2)
        assert status == 200 and "<title>stability explorer</title>" in html
    finally:
        proc.terminate()
        proc.wait(timeout=30)
