"""The cache stamp of the compiled kernels: recompile them when the generated equations change.

Kept apart from the kernels (:mod:`stability.simulate.kernel`, :mod:`stability.simulate.adaptive_kernel`),
which call :func:`invalidate_stale_cache` once at import.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from stability.models.forces import generated as _fo
from stability.models.full_width import generated as _fw
from stability.models.slope import generated as _sl
from stability.tires import law as _tire_law

__all__ = ["KERNEL_SOURCES", "COMPILED_MODULES", "invalidate_stale_cache"]

#: The compiled modules whose functions other compiled modules call (a change to one recompiles them all).
KERNEL_SOURCES = ("kernel.py", "kernel_equations.py", "kernel_controller.py", "kernel_link.py", "adaptive_kernel.py",
                  "lanes_kernel.py", "lanes_step.py", "lanes_physics.py", "lanemath.py")
#: The plain-Python modules the kernels compile as they are (the generated equations and contact forces, the tire law).
COMPILED_MODULES = (_fw, _sl, _fo, _tire_law)


def invalidate_stale_cache(namespace: dict, stamp_name: str, extra: tuple = ()) -> None:
    """Drop the on-disk compiled code of ``namespace``'s kernels when the generated equations changed.

    numba keys a cached function on its own source file only, but a cached
    kernel carries a copy of every function it calls from other modules; so
    a stamp (the SHA-256 of :data:`COMPILED_MODULES` and
    :data:`KERNEL_SOURCES`) is kept next to the cache, and when it differs
    every kernel of the module is recompiled (not when the cache directory is
    not writable).

    Parameters
    ----------
    namespace : dict
        The kernel module's globals (its numba dispatchers are found there).
    stamp_name : str
        File name of the stamp in the module's cache folder.
    extra : tuple of module
        Further modules the kernel compiles or is (the layout kernel and its generated equations).
    """
    here = Path(__file__).parent
    sources = [*(Path(str(m.__file__)) for m in (*COMPILED_MODULES, *extra)),
               *(here / name for name in KERNEL_SOURCES)]
    digest = hashlib.sha256(b"".join(p.read_bytes() for p in sources)).hexdigest()
    kernels = [d for d in namespace.values() if getattr(d, "_cache", None) is not None and hasattr(d, "py_func")]
    try:
        stamp = Path(kernels[0]._cache.cache_path) / stamp_name    # numba internal: the module's cache folder
        if stamp.exists() and stamp.read_text() == digest:
            return
        for d in kernels:
            d._cache.flush()
        tmp = stamp.with_name(f"{stamp.name}.{os.getpid()}.tmp")   # atomic: a concurrent reader sees old or new
        tmp.write_text(digest)
        os.replace(tmp, stamp)
    except (AttributeError, IndexError, OSError):   # numba without these internals, no kernel, read-only cache
        return
