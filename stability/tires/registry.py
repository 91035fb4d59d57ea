"""Tires by name: the seven tested tires of Table 3-1, ``"linear:<C>"``, ``"file:<path>"`` and registered names."""

from __future__ import annotations

import functools
import math
import os
from pathlib import Path

from stability.runtime import readfiles
from stability.tires.data import _ALL, _cornering_coefficients, _rolling_coefficients, _table_3_2
from stability.tires.linear_tire import AnyTire, LinearTire
from stability.tires.model import Tire
from stability.tires.user import load_tire_data

__all__ = ["get", "names", "register", "registered", "resolve_spec", "unregister"]

_REGISTRY: dict[str, AnyTire] = {}


def names() -> tuple[str, ...]:
    """Names of the tested tires, main wheels first (Table 3-1).

    Returns
    -------
    tuple of str
        The built-in tire names (registered tires not included).
    """
    return _ALL


def registered() -> tuple[str, ...]:
    """Names added with :func:`register` (upper case), in order of registration.

    Returns
    -------
    tuple of str
        The registered tire names; empty if none.
    """
    return tuple(_REGISTRY)


def register(name: str, tire: AnyTire, *, replace: bool = False) -> None:
    """Make ``tire`` available to :func:`get` and chair files as ``name`` (case-insensitive).

    In this process only (worker processes started by spawn do not see it; use
    ``"file:<path>"`` in a chair file to be portable).

    Parameters
    ----------
    name : str
        Not a thesis tire name and not starting with ``linear:`` or ``file:``.
    tire : Tire or LinearTire
    replace : bool
        Allow replacing an earlier registration of the same name.

    Raises
    ------
    ValueError
        Reserved or empty name, a name already registered, or not a tire.
    """
    if not isinstance(name, str) or not name.strip():
        raise ValueError(f"name={name!r} is not valid: a non-empty string")
    key = name.strip().upper()
    if key in _ALL or key.startswith(("LINEAR:", "FILE:")):
        raise ValueError(f"name={name!r} is reserved (thesis tires {_ALL}, 'linear:', 'file:'); choose another")
    if not isinstance(tire, (Tire, LinearTire)):
        raise ValueError(f"tire={tire!r} is not valid: a stability.tires.Tire or LinearTire")
    if key in _REGISTRY and not replace:
        raise ValueError(f"name={name!r} is already registered; pass replace=True to replace it")
    _REGISTRY[key] = tire


def unregister(name: str) -> None:
    """Remove a registered tire (no error if absent).

    Parameters
    ----------
    name : str
        Tire name as given to :func:`register` (case and surrounding spaces ignored).
    """
    _REGISTRY.pop(str(name).strip().upper(), None)


def resolve_spec(spec: str, base_dir: str | os.PathLike[str]) -> str:
    """``"file:<relative path>"`` made absolute against ``base_dir`` (e.g. the chair file's folder).

    Parameters
    ----------
    spec : str
        A tire spec; anything but a relative ``file:`` spec is returned unchanged.
    base_dir : str or path-like

    Returns
    -------
    str
    """
    if isinstance(spec, str) and spec.strip().lower().startswith("file:"):
        path = Path(spec.strip()[5:].strip()).expanduser()
        if not path.is_absolute():
            return "file:" + str(Path(base_dir) / path)
    return spec


@functools.cache
def _tested(name: str) -> Tire:
    rows, d, _ = _cornering_coefficients()[name]
    return Tire(
        name=name,
        rows=rows,
        intercepts=d,
        rolling=_rolling_coefficients().get(name),
        f_r=_table_3_2().get(name),
    )


@functools.lru_cache(maxsize=32)
def _file_tire(path: str, mtime_ns: int, size: int) -> Tire:
    return load_tire_data(path)


def _from_file(spec: str) -> Tire:
    text = spec.strip()[5:].strip()
    if not text:
        raise ValueError(f"spec={spec!r} is not valid: 'file:<path>' needs a path to a tire CSV")
    path = Path(text).expanduser().resolve()
    try:
        st = path.stat()
    except OSError as exc:
        raise ValueError(f"tire data {str(path)!r} cannot be read: {exc.__class__.__name__}: {exc.strerror}") from None
    if not path.is_file():
        raise ValueError(f"tire data {str(path)!r} is not a file (spec={spec!r})")
    readfiles.note(path)                      # an input of the command, even when the parse is cached
    return _file_tire(str(path), st.st_mtime_ns, st.st_size)


def get(spec: str) -> AnyTire:
    """A tire by name, a linear tire by stiffness, a user's tire by file or by registered name.

    Parameters
    ----------
    spec : str
        One of :func:`names` (case-insensitive); ``"linear:<C>"`` with ``C``
        the cornering stiffness in N/deg (load-independent); ``"file:<path>"``
        a tire CSV (:func:`stability.tires.load_tire_data`; relative to the
        working directory, see :func:`resolve_spec`; re-read when the file
        changes); or a name given to :func:`register` (case-insensitive).

    Returns
    -------
    Tire or LinearTire

    Raises
    ------
    ValueError
        Naming the parameter, the value and the valid choices.
    """
    if isinstance(spec, str):
        key = spec.strip()
        if key.lower().startswith("linear:"):
            text = key.split(":", 1)[1].strip()
            try:
                c = float(text)
            except ValueError:
                c = math.nan
            if not (math.isfinite(c) and 0.0 < c <= 1000.0):
                raise ValueError(
                    f"spec={spec!r} is not valid: 'linear:<C>' needs 0 < C <= 1000 N/deg (a tire without "
                    "cornering stiffness carries no side force)"
                )
            return LinearTire(stiffness_N_per_deg=c)
        if key.lower().startswith("file:"):
            return _from_file(key)
        if key.upper() in _ALL:
            return _tested(key.upper())
        if key.upper() in _REGISTRY:
            return _REGISTRY[key.upper()]
    extra = f", a registered name {registered()}" if _REGISTRY else ""
    raise ValueError(
        f"spec={spec!r} is not valid; choose one of {_ALL} (any case), 'linear:<C>' "
        f"with C in N/deg, 'file:<path to tire CSV>'{extra}"
    )
