"""Helpers compiled for linking only: their machine code is emitted when an address is asked for, never before.

numba compiles every jitted function into a code library of its own and, when the function is compiled, optimises
that library's whole module and emits its machine code, even for a helper that only ever runs linked into a caller
(numba links a callee's code into each caller's library, where LLVM inlines, optimises and emits it again).  The
kernels' helpers (``kernel_equations._int``, ``_inl`` and the per-model overloads' implementations: MECHAN, the tire
law, the generated equations, ...) are such helpers: a first run optimised and emitted some thirty modules whose
machine code nothing called, about a tenth of the first use's CPU (issue 36; docs/simulator.md, "Compile time").

:class:`LinkOnlyCompiler` (numba's ``pipeline_class``) compiles a function as numba's default compiler does, into a
:class:`LinkOnlyLibrary`: its module is optimised function by function, as numba's are, and linked with its callees
for a caller to link in, and its module-wide optimisation and machine code wait for a caller that asks for an
address of a function it defines (:func:`stability.simulate.native_call.address`, a Python wrapper).  Every caller
links the same code as before, now optimised as a whole once, in the caller's library (where numba optimised it
again anyway): the entry's machine code does the same arithmetic.  The disk cache keeps such a library as its
bitcode (numba's own serialisation kind for it), which a later process loads by emitting it then.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

from numba.core import types as _nbtypes
from numba.core.codegen import JITCodeLibrary
from numba.core.compiler import Compiler
from numba.core.compiler_lock import global_compiler_lock, require_global_compiler_lock

__all__ = ["LinkOnlyLibrary", "LinkOnlyCompiler", "AVAILABLE", "scalar_operators"]

#: numba's code-library methods :class:`LinkOnlyLibrary` overrides or calls (written against numba 0.68; it also
#: reads the library's ``_linking_libraries``, ``_final_module`` and ``_reload_init``, set by numba's constructor).
#: A numba without one of them compiles the helpers as numba does by default (:data:`AVAILABLE` False): slower to
#: compile, the same code.
_INTERNALS = ("_get_module_for_linking", "_optimize_final_module", "_finalize_final_module", "_raise_if_finalized",
              "_ensure_finalized", "serialize_using_object_code", "get_pointer_to_function", "enable_object_caching")


class _DeferredEnv:
    """The library's codegen as numba's ``get_executable`` sees it (``library.codegen``): its ``set_env`` (which
    writes the environment's address into the emitted module) waits for the emission; the rest is the codegen's."""

    def __init__(self, library: LinkOnlyLibrary) -> None:
        self._library = library

    def set_env(self, env_name: str, env: Any) -> None:
        self._library._set_env(env_name, env)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._library._codegen, name)


class LinkOnlyLibrary(JITCodeLibrary):
    """A code library whose module is linked into its callers' libraries; its module-wide optimisation and
    machine code wait until an address of a function it defines is asked for (:meth:`get_pointer_to_function`)."""

    def __init__(self, codegen: Any, name: str) -> None:
        super().__init__(codegen, name)
        self._emitted = False
        self._envs: list[tuple[str, Any]] = []

    @property
    def _codegen_any(self) -> Any:
        """numba's JIT codegen (its ``set_env`` is not in the base class's type)."""
        return self._codegen

    @property
    def codegen(self) -> Any:
        return _DeferredEnv(self)

    def _set_env(self, env_name: str, env: Any) -> None:
        if self._emitted:
            self._codegen_any.set_env(env_name, env)
        else:
            self._envs.append((env_name, env))

    def finalize(self) -> None:
        """numba's ``finalize`` without the module-wide optimisation and the machine code: the callees' modules
        linked in (as numba links them), the library closed."""
        require_global_compiler_lock()
        self._codegen._check_llvm_bugs()
        self._raise_if_finalized()
        seen = set()
        for library in self._linking_libraries:
            if library not in seen:
                self._reload_init.update(library._reload_init)
                seen.add(library)
                self._final_module.link_in(library._get_module_for_linking(), preserve=True)
        self._finalized = True

    def _emit(self) -> None:
        """What numba's ``finalize`` does after linking: optimise the module as a whole and emit it."""
        with global_compiler_lock:
            if self._emitted:
                return
            self._optimize_final_module()
            self._final_module.verify()
            self._finalize_final_module()
            self._emitted = True
            for env_name, env in self._envs:
                self._codegen_any.set_env(env_name, env)
            self._envs.clear()

    def get_pointer_to_function(self, name: str) -> int:
        """The address of the function ``name`` (emitting the library first), or 0 if it defines none so named
        (a wrapper numba was told not to make: nothing is emitted for it)."""
        self._ensure_finalized()
        try:
            fn = self._final_module.get_function(name)
        except NameError:
            return 0
        if fn.is_declaration:
            return 0
        self._emit()
        return super().get_pointer_to_function(name)

    def serialize_using_object_code(self) -> tuple:
        """The library for numba's disk cache: its bitcode (numba's ``"bitcode"`` kind), unless emitted."""
        if self._emitted:
            return super().serialize_using_object_code()
        self._ensure_finalized()
        return (self.name, "bitcode", self._final_module.as_bitcode())


#: Whether the helpers compile for linking only (numba's internals as expected), else as numba does by default.
AVAILABLE = all(hasattr(JITCodeLibrary, name) for name in _INTERNALS)


class LinkOnlyCompiler(Compiler):
    """numba's default compiler, into a :class:`LinkOnlyLibrary` (``njit(pipeline_class=LinkOnlyCompiler)``)."""

    def _compile_core(self) -> Any:
        if self.state.library is None:
            library = LinkOnlyLibrary(self.state.targetctx.codegen(), self.state.func_id.func_qualname)
            library.enable_object_caching()
            self.state.library = library
        return super()._compile_core()


def _arrays_only(generic: Any) -> Any:
    """numba's typing of an operator by numpy's rules (``NumpyRulesArrayOperator.generic``), answering ``None`` at
    once when no operand is an array, as it answers after matching the operands to a ufunc loop."""
    def typed(self: Any, args: tuple, kws: dict) -> Any:
        if not any(isinstance(a, _nbtypes.ArrayCompatible) for a in args):
            return None
        return generic(self, args, kws)
    return typed


@contextlib.contextmanager
def scalar_operators() -> Iterator[None]:
    """Around a compile of the kernels: numba types each arithmetic operator on scalars without trying numpy's
    rules for it first.

    numba types ``a + b`` by trying its operator templates in turn, numpy's array-operator rules among the first:
    they match the operands to a ufunc loop (a search over numpy's loop table) and only then reject operands none
    of which is an array (``NumpyRulesArrayOperator.generic``: "Only accept at least one array argument").  The
    step's few thousand scalar operations paid that search each, about a twentieth of the first use (issue 36,
    measured).  Inside this block that template rejects them before the search: the same answer (``None``, the
    next template types the operator), sooner; the class's method is restored after the block.  Not reentrant
    across threads' compiles in any way that matters: the answer is the same either way.

    Yields
    ------
    None
        The block runs inside, with numpy's operator rule answering for arrays only.
    """
    from numba.core.typing import npydecl

    cls: Any = npydecl.NumpyRulesArrayOperator      # its method replaced inside the block (typed as Any for it)
    original = cls.__dict__.get("generic")
    if original is None or getattr(original, "_arrays_only", False):
        yield
        return
    patched = _arrays_only(original)
    patched._arrays_only = True
    cls.generic = patched
    try:
        yield
    finally:
        cls.generic = original
