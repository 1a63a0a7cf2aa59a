"""The compiled engine core (core/*.c) as the extension evapcool.physics._core.

Everything else about the package is in pyproject.toml. The flags pin IEEE arithmetic as
written, the same as the page's WebAssembly build (web/scripts/wasm-plugin.mjs): no
contraction into fused multiply-adds, no fast-math, SSE2 (not x87) on 32-bit x86. The
extension is optional: without a C compiler the package installs and plays on the
reference engine, and says so (physics/core.py).
"""

import importlib.util
import platform
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

CORE = sorted(str(p).replace("\\", "/") for p in Path("core").glob("*.c"))


def _source_hash() -> str:
    """The sources' hash (src/evapcool/physics/coresource.py, loaded without the package)."""
    path = Path("src/evapcool/physics/coresource.py")
    spec = importlib.util.spec_from_file_location("coresource", path)
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return str(module.source_hash(Path(".").resolve()))


UNIX_FLAGS = [
    "-std=c11",
    "-O3",
    "-ffp-contract=off",
    "-fno-fast-math",
    "-fvisibility=hidden",
    "-flto",
]
# MSVC: precise semantics and no contraction (cl 19.30 and later contract only with /fp:contract).
MSVC_FLAGS = ["/O2", "/fp:precise"]


def x86_32() -> bool:
    plat = sysconfig.get_platform()
    return plat in ("win32", "linux-i686") or platform.machine().lower() in ("i386", "i686")


class ExactBuildExt(build_ext):
    """build_ext with the core's floating-point flags for the compiler in use."""

    def build_extensions(self) -> None:
        msvc = self.compiler.compiler_type == "msvc"
        flags = (
            MSVC_FLAGS if msvc else UNIX_FLAGS + (["-msse2", "-mfpmath=sse"] if x86_32() else [])
        )
        for ext in self.extensions:
            ext.extra_compile_args = [*flags, *ext.extra_compile_args]
            if not msvc:  # the kernels inline across the room files, as in the wasm build
                ext.extra_link_args = [*flags, *ext.extra_link_args]
        super().build_extensions()


setup(
    ext_modules=[
        Extension(
            "evapcool.physics._core",
            sources=["src/evapcool/physics/_coremodule.c", *CORE],
            include_dirs=["core"],
            # compiled in: an extension built in place is refused once its sources change
            define_macros=[("CORE_SOURCE_HASH", f'"{_source_hash()}"')],
            optional=True,
        )
    ],
    cmdclass={"build_ext": ExactBuildExt},
)
