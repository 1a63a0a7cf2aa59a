"""How the fast engine is compiled: Numba's options, a cache that cannot go stale,
the kernels, and the one hint to the CPU's memory system.

Cache. Numba keys its on-disk cache on the file that holds each compiled function,
but the engine's compiled code also contains the kernels (kernels.py), the World's
constants (world.py) and the engine's other modules: editing one of them would
leave the old code running. Every engine function therefore uses Numba's cache with
one more part in its key: a hash of all those sources (`SOURCE_HASH`). Change any of
them and every engine function compiles afresh.

Inlining. Helpers used in several places are compiled once each and inlined by LLVM
(`hot`), not copied into every caller by Numba: LLVM inlines in a fraction of the
time Numba takes to retype a copy. Pieces of a single caller are spliced into it by
Numba (`part`): they then cost no compile of their own. Both give the same machine
code as one long function, so the first start is short and the code readable.
"""

from __future__ import annotations

import hashlib
import sys
import types
from collections.abc import Callable
from pathlib import Path
from typing import Any

from numba import njit

from evapcool.physics import kernels

#: A compiled function as Python code sees it: Numba chooses the machine code from the
#: argument types at each call, so its Python signature is open (the compiled modules
#: are checked by Numba's type inference, see [tool.mypy] in pyproject.toml).
Compiled = Callable[..., Any]

_FAST = Path(__file__).resolve().parent
#: Modules of the package with no compiled code (editing them needs no recompile).
PYTHON_ONLY = ("__init__.py", "engine.py", "warmup.py")
#: Every source the compiled engine is built from.
SOURCES = (
    *sorted(p for p in _FAST.glob("*.py") if p.name not in PYTHON_ONLY),
    _FAST.parent / "kernels.py",
    _FAST.parent / "world.py",
)


def source_hash(paths: tuple[Path, ...] = SOURCES) -> str:
    """SHA-256 over the engine's sources (names and contents), the cache's freshness stamp.

    In a frozen executable, where the sources may not exist as files, the executable
    itself stands for them (as in Numba's own stamp).
    """
    h = hashlib.sha256()
    if getattr(sys, "frozen", False):
        st = Path(sys.executable).stat()
        h.update(f"{sys.executable}:{st.st_size}:{st.st_mtime_ns}".encode())
        return h.hexdigest()
    for path in paths:
        h.update(path.name.encode() + b"\0")
        h.update(path.read_bytes())
    return h.hexdigest()


SOURCE_HASH = source_hash()


def _source_keyed_cache() -> type[Any] | None:
    """Numba's function cache with SOURCE_HASH in every key; None if Numba changed.

    Uses Numba's FunctionCache (numba.core.caching), an internal class: tests check
    that it is in use, and without it the engine compiles at every start rather than
    ever run stale code.
    """
    try:
        from numba.core.caching import FunctionCache
    except ImportError:  # pragma: no cover - a future Numba
        return None

    class SourceKeyedCache(FunctionCache):
        def _index_key(self, sig: Any, codegen: Any) -> tuple[Any, ...]:
            base: Any = super()  # numba.core.caching carries no annotations
            return (*base._index_key(sig, codegen), SOURCE_HASH)

    return SourceKeyedCache


_CACHE = _source_keyed_cache()

#: Every compiled function of the engine, in definition order (prepare() and tests).
REGISTRY: list[Any] = []

# No compiled function allocates, so Numba's reference counting (atomic operations on
# every array passed around) is off. error_model="numpy": a division by zero gives inf
# or nan, as in the NumPy arithmetic of the reference engine, and needs no check.
_OPTIONS: dict[str, Any] = {"_nrt": False, "error_model": "numpy", "boundscheck": False}


def _compiled(fn: Callable[..., Any], **options: Any) -> Compiled:
    disp = njit(**_OPTIONS, **options)(fn)
    if _CACHE is not None and hasattr(disp, "_cache"):
        disp._cache = _CACHE(disp.py_func)
    REGISTRY.append(disp)
    compiled: Compiled = disp
    return compiled


def hot(fn: Callable[..., Any]) -> Compiled:
    """A helper of the event loop: compiled once, inlined by LLVM into its callers."""
    return _compiled(fn, forceinline=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)


def part(fn: Callable[..., Any]) -> Compiled:
    """A piece of one caller, split out for reading: Numba splices it into the caller.

    It has no compiled code of its own (and so costs no compile time of its own).
    """
    spliced: Compiled = njit(inline="always", **_OPTIONS)(fn)
    return spliced


def entry(fn: Callable[..., Any]) -> Compiled:
    """A function called from Python, or a rare step called from the event loop."""
    return _compiled(fn)


def _compile_kernels() -> types.ModuleType:
    """kernels.py compiled as it is, each kernel calling the compiled versions of the others.

    The same formulas, operation for operation, as the reference engine's: that is
    what makes the two engines' events bit-identical. (A module, so that Numba can
    resolve K.name in compiled code.)
    """
    names = [
        name
        for name, obj in vars(kernels).items()
        if isinstance(obj, types.FunctionType) and obj.__module__ == kernels.__name__
    ]
    ns = dict(vars(kernels))
    for name in names:
        fn = ns[name]
        ns[name] = hot(types.FunctionType(fn.__code__, ns, name, fn.__defaults__))
    module = types.ModuleType(__name__ + ".K", kernels.__doc__)
    for name in names:
        setattr(module, name, ns[name])
    return module


K = _compile_kernels()


def _make_prefetch() -> Compiled:
    """prefetch(table, i): ask the CPU to start loading row i of a 1-D table.

    Why: at 10^5 atoms the tables outgrow the caches and each event starts with
    misses on its atom's rows; asking for the likely next rows during the current
    event overlaps those misses with useful work. It never faults and has no effect on
    results. LLVM's prefetch intrinsic is reached through Numba's extension API for
    intrinsics and llvmlite; if they are not as expected, prefetch does nothing.
    """
    try:
        from llvmlite import binding, ir
        from numba.core import types as nt
        from numba.extending import intrinsic

        if binding.llvm_version_info < (15,):  # pragma: no cover - typed pointers
            raise ImportError("opaque pointers needed")

        @intrinsic
        def prefetch(typingctx: Any, table: Any, i: Any) -> Any:
            if not isinstance(table, nt.Array) or table.ndim != 1:
                return None

            def codegen(context: Any, builder: Any, sig: Any, args: Any) -> Any:
                ary = context.make_array(sig.args[0])(context, builder, args[0])
                row = context.cast(builder, args[1], sig.args[1], nt.intp)
                ptr = builder.gep(ary.data, [row])
                i8p = ir.IntType(8).as_pointer()
                i32 = ir.IntType(32)
                fnty = ir.FunctionType(ir.VoidType(), [i8p, i32, i32, i32])
                fn = builder.module.declare_intrinsic("llvm.prefetch.p0", fnty=fnty)
                # read, high temporal locality, data cache
                builder.call(fn, [builder.bitcast(ptr, i8p), i32(0), i32(3), i32(1)])
                return context.get_dummy_value()

            return nt.void(table, i), codegen

        return prefetch
    except (ImportError, AttributeError):  # pragma: no cover - the fallback

        @hot
        def no_prefetch(table: Any, i: Any) -> None:
            pass

        return no_prefetch


prefetch = _make_prefetch()
