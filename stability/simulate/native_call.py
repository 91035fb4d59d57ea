"""Calls of a compiled numba function through its address: entry points that share one compiled step.

numba compiles a call of one jitted function from another by linking the
callee's code into the caller's code library, where LLVM optimises and emits it
again (the WCHAIR step, about as costly as compiling the step itself, once more
in each batch entry and in its parfor body).  :func:`call_at` calls the
function's own machine code instead, at an address taken once
(:func:`address`): the caller compiles a call, not the callee, and runs the
very instructions the callee runs when it is called from Python.
"""

from __future__ import annotations

import operator
from typing import Any

from numba import types
from numba.core import cgutils
from numba.core.registry import cpu_target
from numba.extending import intrinsic

__all__ = ["call_at", "call_none_at", "address", "row_types"]


def _call(restype: Any) -> Any:
    """The codegen of a call, returning ``restype``, of the function at the address in the first argument."""
    def codegen(context, builder, signature, llargs):
        argtys = tuple(signature.args[1])
        fnty = context.call_conv.get_function_type(restype, argtys)
        callee = builder.inttoptr(llargs[0], fnty.as_pointer())
        values = cgutils.unpack_tuple(builder, llargs[1], len(argtys))
        status, res = context.call_conv.call_function(builder, callee, restype, argtys, values)
        with cgutils.if_unlikely(builder, status.is_error):
            context.call_conv.return_status_propagate(builder, status)
        return res
    return codegen


@intrinsic
def call_at(typingctx, fp, *args):
    """``f(*args)`` for the compiled function ``f`` at address ``fp`` (:func:`address`) whose arguments have the
    types of ``args`` (literal integers as their integer type: the same machine representation) and which returns
    an ``int64``.  numba's calling convention, as a call of a jitted function compiled in place: an exception of
    ``f`` propagates.  Compiled code only."""
    if not isinstance(fp, types.Integer):
        return None
    return types.int64(fp, types.StarArgTuple.from_types(args)), _call(types.int64)


@intrinsic
def call_none_at(typingctx, fp, *args):
    """:func:`call_at` for a function that returns nothing (``None``; :func:`address` with ``returns=none``)."""
    if not isinstance(fp, types.Integer):
        return None
    return types.none(fp, types.StarArgTuple.from_types(args)), _call(types.none)


def row_types(arg_types: tuple, per_run: tuple[int, ...]) -> tuple:
    """numba's types of ``a[i]`` (an integer ``i``) for the argument types ``arg_types`` at the indices
    ``per_run``; the others unchanged.

    Parameters
    ----------
    arg_types : tuple of numba types
        A batch entry's argument types.
    per_run : tuple of int
        The indices of those that hold one row per run.

    Returns
    -------
    tuple of numba types
        What numba's typing gives for one run's row of each (its own ``getitem`` rule: layout, mutability).
    """
    ctx = cpu_target.typing_context
    ctx.refresh()
    return tuple(ctx.resolve_function_type(operator.getitem, (t, types.intp), {}).return_type if j in per_run else t
                 for j, t in enumerate(arg_types))


def address(dispatcher: Any, sig: tuple, returns: Any = types.int64) -> int:
    """The address of ``dispatcher``'s machine code for the argument types ``sig`` (compiled, or loaded from the
    cache, first), for :func:`call_at` (or :func:`call_none_at`: ``returns`` ``types.none``).

    Parameters
    ----------
    dispatcher : numba dispatcher
        A jitted function returning ``returns``.
    sig : tuple of numba types
        Its argument types.
    returns : numba type
        What it returns: ``types.int64`` (:func:`call_at`) or ``types.none`` (:func:`call_none_at`).

    Returns
    -------
    int
        The address of its compiled function in numba's calling convention (not of a Python or C wrapper).
    """
    dispatcher.compile(sig)
    cres = dispatcher.overloads[tuple(sig)]
    if cres.signature.return_type != returns:
        raise TypeError(f"{dispatcher} returns {cres.signature.return_type}, not {returns}")
    ctx = cpu_target.target_context
    ours = ctx.call_conv.get_function_type(returns, tuple(map(types.unliteral, sig)))
    theirs = ctx.call_conv.get_function_type(cres.signature.return_type, cres.signature.args)
    if str(ours) != str(theirs):     # what call_at will call it with (literals as their integer type)
        raise TypeError(f"{dispatcher}'s compiled arguments {theirs} differ from {ours}")
    return int(cres.library.get_pointer_to_function(cres.fndesc.mangled_name))
