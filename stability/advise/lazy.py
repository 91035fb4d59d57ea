"""Values computed when first read, in groups: the advisor's pair screening measures a design only as far as it
checks it (:class:`stability.advise.measures.LazyLinear`, :func:`stability.advise.limits.meets`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ["Lazy", "reused"]


class Lazy:
    """Named values, computed in groups when one of a group's values is first read as an attribute.

    Parameters
    ----------
    groups : dict
        Group name -> ``(names, compute)``: the names of the values the group gives and ``compute() -> dict`` of
        them (one call, the first time one of them is read), in the order :meth:`values` computes them.
    """

    def __init__(self, groups: dict[str, tuple[tuple[str, ...], Callable[[], dict[str, Any]]]]) -> None:
        self._groups = groups
        self._of = {f: name for name, (names, _) in groups.items() for f in names}
        self._done: dict[str, dict[str, Any]] = {}

    def _group(self, name: str) -> dict[str, Any]:
        if name not in self._done:
            self._done[name] = self._groups[name][1]()
        return self._done[name]

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_") or name not in self._of:
            raise AttributeError(name)
        return self._group(self._of[name])[name]

    def computed(self) -> list[str]:
        """The groups computed so far, in the order they were.

        Returns
        -------
        list of str
        """
        return list(self._done)

    def values(self) -> dict[str, Any]:
        """Every value, the groups not computed yet computed in their order.

        Returns
        -------
        dict
            Name -> value.
        """
        out: dict[str, Any] = {}
        for name in self._groups:
            out.update(self._group(name))
        return out


def reused(cache: dict, subject: object, inputs: tuple, make: Callable[[], Lazy]) -> Lazy:
    """The :class:`Lazy` values of ``subject`` with ``inputs`` kept in ``cache``, made the first time they are asked.

    The same object asked again (the advisor measures the pairs it screened) gets the values computed so far;
    keyed by the object's identity (a layout's lists are not hashable), which the entry keeps alive.

    Parameters
    ----------
    cache : dict
        Shared between calls; its entries are ``("lazy", id(subject), inputs) -> (subject, Lazy)``.
    subject : object
        The design.
    inputs : tuple
        Everything else the values depend on (hashable).
    make : callable
        ``make() -> Lazy``.

    Returns
    -------
    Lazy
    """
    key = ("lazy", id(subject), inputs)
    hit = cache.get(key)
    if hit is None or hit[0] is not subject:
        hit = cache[key] = (subject, make())
    return hit[1]
