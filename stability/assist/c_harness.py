"""Compile an exported ``assist.c`` with the system C compiler and replay inputs through it.

Used by the tests and the docs example to check a port against the test
vectors (``assist_vectors.json``).  Nothing here is needed on the controller
board.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile

import numpy as np

__all__ = ["C_FLAGS", "find_cc", "compile_replay", "replay"]

#: Flags of the check: strict C99, every warning an error, no libm.
C_FLAGS = ("-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-O2")

_MAIN = r"""#include <stdio.h>
#include "assist.h"
/* reads rows "speed cmd gyro wheel" from stdin and prints "left right" per row, from assist_init */
int main(void)
{
    assist_state s;
    float v, c, g, w, left, right;
    assist_init(&s);
    while (scanf("%f %f %f %f", &v, &c, &g, &w) == 4) {
        assist_step(&s, v, c, g, w, &left, &right);
        printf("%.9g %.9g\n", left, right);
    }
    return 0;
}
"""


def find_cc() -> str | None:
    """The system C compiler (``$CC``, ``cc``, ``gcc`` or ``clang``), or None.

    Returns
    -------
    str or None
    """
    for name in (os.environ.get("CC"), "cc", "gcc", "clang"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


def compile_replay(directory: str, out: str | None = None, cc: str | None = None) -> str:
    """Compile ``directory/assist.c`` with a replay ``main`` into an executable.

    Parameters
    ----------
    directory : str
        Holds ``assist.h`` and ``assist.c``.
    out : str, optional
        Executable path (default ``directory/assist_replay``).
    cc : str, optional
        Compiler (default :func:`find_cc`).

    Returns
    -------
    str
        The executable's path.

    Raises
    ------
    RuntimeError
        No compiler, or the compiler's error output.
    """
    cc = cc or find_cc()
    if cc is None:
        raise RuntimeError("no C compiler found (cc, gcc, clang or $CC)")
    out = out or os.path.join(directory, "assist_replay")
    with tempfile.TemporaryDirectory() as tmp:
        main = os.path.join(tmp, "replay_main.c")
        with open(main, "w", encoding="utf-8") as fh:
            fh.write(_MAIN)
        cmd = [cc, *C_FLAGS, "-I", directory, main, os.path.join(directory, "assist.c"), "-o", out]
        p = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{p.stderr}")
    return out


def replay(executable: str, inputs: np.ndarray) -> np.ndarray:
    """Run rows ``speed, command, gyro, wheel`` through a compiled replay: ``(left, right)`` per row (N m).

    Parameters
    ----------
    executable : str
        From :func:`compile_replay`.
    inputs : ndarray (N, 4)

    Returns
    -------
    ndarray (N, 2)
    """
    text = "\n".join(" ".join(f"{v:.9g}" for v in row) for row in np.asarray(inputs, dtype=float)) + "\n"
    p = subprocess.run([executable], input=text, capture_output=True, text=True, check=True)
    return np.array([[float(x) for x in line.split()] for line in p.stdout.splitlines()]).reshape(-1, 2)
