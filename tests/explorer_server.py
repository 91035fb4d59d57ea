"""The served explorer and the system's chromium, for the browser tests (tests/ui) and the browser benchmark.

``serve()`` runs ``python -m stability.app --port 0 --no-browser`` until the
block ends and yields its URL; ``chromium()`` is Debian's chromium
(``STABILITY_CHROMIUM`` or ``chromium`` on PATH), given to playwright as its
executable: nothing is downloaded.
"""

from __future__ import annotations

import contextlib
import os
import re
import shutil
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator


def chromium() -> str | None:
    """Path of the system's chromium, or None."""
    path = os.environ.get("STABILITY_CHROMIUM") or shutil.which("chromium") or shutil.which("chromium-browser")
    return path if path and os.path.exists(path) else None


@contextlib.contextmanager
def serve(timeout_s: float = 120.0) -> Iterator[str]:
    """Run the explorer on a free port of 127.0.0.1 and yield its URL (the server's traceback, if any, printed)."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in sys.path if p)}
    proc = subprocess.Popen([sys.executable, "-m", "stability.app", "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        m = re.search(r"(http://127\.0\.0\.1:\d+/)", line)
        assert m, line
        url = m.group(1)
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                urllib.request.urlopen(url, timeout=60).close()
                break
            except OSError:
                assert time.monotonic() < deadline and proc.poll() is None, "the server did not answer"
                time.sleep(0.5)
        yield url
    finally:
        proc.terminate()
        try:
            out, _ = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            out, _ = proc.communicate()
        if "Traceback" in (out or ""):
            print(out)
