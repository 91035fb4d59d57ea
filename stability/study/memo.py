"""Reuse of searches already run: one search's result per set of inputs, while a memo is open.

A batched search's result for one job (a chair at a speed, a chair against a reference time) does not depend on the
other jobs of its batch (each problem of :func:`stability.study.search.bracket_search` and of the speed bisection
proposes its own points; every run is its own), so a job asked again with the same inputs can take the result
already found.  The advisor (:func:`stability.advise.advise`) opens a memo: its screening runs one variant of every
change (x0.5 pin friction), and a change whose intervals it then computes asks for that variant again, as the
intervals of the changes a pair is made of ask for the reference chair's times again.

Outside :func:`search_memo` nothing is kept.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Hashable, Iterator, Sequence
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any, TypeVar

__all__ = ["search_memo", "memo_searches", "memoised"]

T = TypeVar("T")

_MEMO: ContextVar[dict | None] = ContextVar("stability_search_memo", default=None)


@contextmanager
def search_memo() -> Iterator[dict]:
    """Open a memo of search results (an enclosing one is reused); closed, and forgotten, on exit.

    Yields
    ------
    dict
        The memo: ``(kind, job key) -> result``.
    """
    outer = _MEMO.get()
    token = _MEMO.set({} if outer is None else outer)
    try:
        yield _MEMO.get() or {}
    finally:
        _MEMO.reset(token)


def memo_searches(fn: Callable[..., T]) -> Callable[..., T]:
    """Decorator: ``fn`` runs inside :func:`search_memo` (its searches asked again are not run again).

    Parameters
    ----------
    fn : callable

    Returns
    -------
    callable
        ``fn`` with the memo open around each call.
    """
    @functools.wraps(fn)
    def wrapped(*args: Any, **kwargs: Any) -> T:
        with search_memo():
            return fn(*args, **kwargs)

    return wrapped


def _key(kind: str, k: Hashable | None) -> tuple | None:
    if k is None:
        return None
    try:
        hash(k)
    except TypeError:                       # a job with an unhashable input (a layout's lists) is never reused
        return None
    return (kind, k)


def memoised(kind: str, keys: Sequence[Hashable | None], compute: Callable[[list[int]], Sequence[T]]) -> list[T]:
    """The results of jobs ``keys``: those found in the open memo taken from it, the others computed in one batch.

    Parameters
    ----------
    kind : str
        The search (its results are only reused for the same search).
    keys : sequence of hashable or None
        Each job's complete inputs; None (or an unhashable key) is never reused.
    compute : callable
        ``compute(indices)`` -> the results of the jobs at those indices, in order (one batch).

    Returns
    -------
    list
        One result per job, in order.
    """
    memo = _MEMO.get()
    if memo is None:
        return list(compute(list(range(len(keys)))))
    full = [_key(kind, k) for k in keys]
    todo: list[int] = []
    first: dict[Any, int] = {}
    for i, k in enumerate(full):
        if k is None:
            todo.append(i)
        elif k not in memo and k not in first:
            first[k] = i
            todo.append(i)
    found = list(compute(todo)) if todo else []
    got = dict(zip(todo, found, strict=True))
    for i in todo:
        if full[i] is not None:
            memo[full[i]] = got[i]
    return [got[i] if k is None else (got[i] if i in got else memo[k]) for i, k in enumerate(full)]
