"""Generated code made callable in the tests: Python as a module, C compiled with gcc and loaded by ctypes."""

from __future__ import annotations

import ctypes
import shutil
import subprocess
import sys
import types
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np

from tests.conftest import solved
from tutgen.codegen.printers import generate_code

GCC = shutil.which("gcc")
#: The flags the issue asks the generated C to compile warning-free with.
CFLAGS = ["-O2", "-Wall", "-Wextra", "-std=c99", "-Werror"]


#: specs whose JSON document (which solved() also builds) takes far longer than their derivation
#: (the numeric PUMA: 6 s to derive, 40 s for the JSON of its expanded entries; the symbolic arms: minutes):
#: derived here alone
NO_JSON = frozenset({"puma560-numeric", "puma560", "stanford"})


@cache
def derived(path: str) -> tuple[Any, Any]:
    """(system, derivation) of a spec, through the session's solved() cache where that is cheap."""
    if Path(path).stem not in NO_JSON:
        system, derivation, _ = solved(path)
        return system, derivation
    from tutgen.engine.pipeline import derive
    from tutgen.spec.validate import load_system

    system = load_system(path)
    return system, derive(system)


@cache
def code(path: str, language: str) -> str:
    return generate_code(derived(path)[1], language, Path(path).name)


@cache
def python_module(path: str) -> types.ModuleType:
    name = f"generated_{abs(hash(path))}"
    module = types.ModuleType(name)
    sys.modules[name] = module  # dataclasses look the module up while the class is made
    exec(compile(code(path, "python"), f"<generated {Path(path).name}>", "exec"), module.__dict__)
    return module


def compile_c(source: str, workdir: Path, name: str) -> ctypes.CDLL:
    """Compile ``source`` into a shared library with :data:`CFLAGS`; a warning fails the compile."""
    c_file = workdir / f"{name}.c"
    c_file.write_text(source)
    lib = workdir / f"lib{name}.so"
    result = subprocess.run(
        [GCC, *CFLAGS, "-shared", "-fPIC", str(c_file), "-o", str(lib), "-lm"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    return ctypes.CDLL(str(lib))


class CModel:
    """The C functions of one generated file, called with NumPy arrays."""

    def __init__(self, lib: ctypes.CDLL, prefix: str, n: int, fields: list[tuple[str, str]]) -> None:
        """``fields``: (spec name, C name) of each parameter, in the struct's order."""
        self.lib, self.prefix, self.n = lib, prefix, n
        self.names = dict(fields)
        members = [(c, ctypes.c_double) for _, c in fields] or [("unused", ctypes.c_double)]
        self.params_type = type("Params", (ctypes.Structure,), {"_fields_": members})

    def params(self, values: dict[str, float]) -> Any:
        """The struct: the spec's values (default_params), then ``values`` by spec name."""
        p = self.params_type()
        getattr(self.lib, f"{self.prefix}_default_params")(ctypes.byref(p))
        for k, v in values.items():
            setattr(p, self.names[k], v)
        return p

    def call(self, name: str, p: Any, *vectors: np.ndarray, size: int) -> tuple[np.ndarray, int]:
        fn: Callable[..., int] = getattr(self.lib, f"{self.prefix}_{name}")
        fn.restype = ctypes.c_int
        args = [np.ascontiguousarray(v, dtype=float) for v in vectors]
        out = np.zeros(size)
        status = fn(
            *[a.ctypes.data_as(ctypes.POINTER(ctypes.c_double)) for a in args],
            ctypes.byref(p),
            out.ctypes.data_as(ctypes.POINTER(ctypes.c_double)),
        )
        return out, int(status)


@cache
def derived_lagrange(rel: str) -> Any:
    """The Lagrange derivation of a spec (path relative to the repository), once per session: the constrained
    examples' code and simulation tests share it."""
    from tests.conftest import ROOT
    from tutgen.engine.pipeline import derive
    from tutgen.spec.validate import load_system

    return derive(load_system(ROOT / rel), "lagrange")
