"""`tutgen code` as a library: load and derive a spec, print its dynamics in a language."""

from __future__ import annotations

import os
from pathlib import Path

from tutgen.codegen.printers import LANGUAGES, generate_code
from tutgen.codegen.program import module_name
from tutgen.errors import UsageError

__all__ = ["code_for_spec", "plan_code_output"]


def plan_code_output(spec: Path, output: str | Path, language: str, *, force: bool) -> Path:
    """The file to write: ``output``, or ``output/<module><ext>`` for a directory (or a path ending in
    '/'); a usage error for the spec itself or an existing file without ``force``."""
    from tutgen.api import check_output_path

    text = str(output)
    output = Path(output)
    check_output_path(output)
    target = output
    if output.is_dir() or text.endswith(("/", os.sep)):
        target = output / (module_name(spec.stem) + LANGUAGES[language][0])
    if target.exists() and spec.exists() and os.path.samefile(target, spec):
        raise UsageError(f"refusing to overwrite the spec {target} with code; choose another -o")
    if target.is_dir():
        raise UsageError(f"-o {target}: this is a directory; add a trailing '/' to write into it")
    if target.exists() and not force:
        raise UsageError(f"{target} exists; add --force to overwrite it")
    return target


def code_for_spec(spec: Path, language: str, timeout: float | None = None, linear: bool = False) -> str:
    """The code of ``spec``'s dynamics in ``language`` (with ``linear``, also the linear model), all
    within ``timeout`` seconds."""
    from tutgen.engine.pipeline import derive
    from tutgen.limits import deadline, stage
    from tutgen.spec.validate import load_system

    with deadline(timeout):
        stage("loading the specs", spec.name)
        system = load_system(spec)
        stage("derivation")
        derivation = derive(system, "lagrange")
        stage("code generation", language)
        return generate_code(derivation, language, spec.name, linear)
