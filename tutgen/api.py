"""The library face of the CLI: load, derive, render, write — in that order, all or nothing."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from tutgen.errors import SpecError, SpecErrors, UsageError

EXTENSIONS = {"md": ".md", "json": ".json"}


def render(derivation: object, fmt: str) -> str:
    """Render one derivation in a format ('md' or 'json')."""
    from tutgen.engine.derivation import Derivation

    assert isinstance(derivation, Derivation)
    if fmt == "json":
        from tutgen.render.jsonout import derivation_to_json, dumps

        return dumps(derivation_to_json(derivation))
    from tutgen.render.markdown import render_markdown

    return render_markdown(derivation)


def solve_specs(paths: list[Path], fmt: str) -> list[str]:
    """Load every spec (reporting all their errors at once), derive each, render each."""
    from tutgen.engine.lagrange import derive
    from tutgen.spec.validate import load_system

    systems = []
    errors: list[SpecError] = []
    for path in paths:
        try:
            systems.append(load_system(path))
        except SpecErrors as exc:
            errors += exc.errors
    if errors:
        raise SpecErrors(errors)
    return [render(derive(system), fmt) for system in systems]


def plan_outputs(specs: list[Path], output: Path, fmt: str, *, force: bool) -> list[Path]:
    """Where each result goes; refuse to overwrite a spec, or an existing file without --force."""
    ext = EXTENSIONS[fmt]
    if len(specs) > 1 or output.is_dir() or str(output).endswith(os.sep):
        if output.exists() and not output.is_dir():
            raise UsageError(f"-o {output}: several specs need a directory, and this is a file")
        targets = [output / (spec.stem + ext) for spec in specs]
        stems = [t.name for t in targets]
        dupes = sorted({s for s in stems if stems.count(s) > 1})
        if dupes:
            raise UsageError(f"two specs would write the same file: {', '.join(dupes)}; solve them separately")
    else:
        targets = [output]
    inputs = {spec.resolve() for spec in specs}
    for target in targets:
        if target.resolve() in inputs:
            raise UsageError(f"refusing to overwrite the spec {target} with the solution; choose another -o")
        if target.exists() and not force:
            raise UsageError(f"{target} exists; add --force to overwrite it")
    return targets


def write_outputs(targets: list[Path], texts: list[str]) -> None:
    """Write each text through a temporary file and a rename, so no file is ever half-written."""
    for target, text in zip(targets, texts, strict=True):
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
        try:
            with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
                fh.write(text)
            os.replace(tmp, target)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
