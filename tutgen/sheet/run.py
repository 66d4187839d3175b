"""The library face of `tutgen sheet`: check the inputs and the outputs, build, write, all or nothing."""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from tutgen.errors import SpecError, SpecErrors, UsageError
from tutgen.sheet.model import Sheet
from tutgen.sheet.variants import Variant


@dataclass(frozen=True)
class SheetPlan:
    sheet: Sheet
    out: Path
    formats: tuple[str, ...]
    variants: tuple[Variant, ...]
    targets: tuple[Path, ...]

    @property
    def jobs(self) -> int:
        return 1 + len(self.variants)


def plan_sheet(
    sheet_file: Path,
    output: str | None,
    *,
    formats: Sequence[str] = ("md",),
    variants: int | None = None,
    students: Path | None = None,
    force: bool = False,
) -> SheetPlan:
    """Read the sheet (and the roster), and refuse early: no -o, both --variants and --students, an
    output onto an input file, an existing file without --force."""
    from tutgen.sheet.build import file_names
    from tutgen.sheet.model import load_roster, load_sheet
    from tutgen.sheet.variants import variant_ids

    if output is None:
        raise UsageError("tutgen sheet writes several files: add -o DIR")
    if variants is not None and students is not None:
        raise UsageError("give --variants or --students, not both")
    out = Path(output)
    if out.exists() and not out.is_dir():
        raise UsageError(f"-o {output}: this is a file; a sheet needs a directory")
    errors: list[SpecError] = []
    sheet = None
    try:
        sheet = load_sheet(sheet_file)
    except SpecErrors as exc:
        errors += exc.errors
    chosen: tuple[Variant, ...] = ()
    if students is not None:
        try:
            chosen = tuple(Variant(s.id, s.name or s.id) for s in load_roster(students))
        except SpecErrors as exc:
            errors += exc.errors
    elif variants:
        chosen = variant_ids(variants)
    if errors:
        raise SpecErrors(errors)
    assert sheet is not None
    if "pdf" in formats:
        from tutgen.render.pdf import find_latexmk

        find_latexmk()  # no LaTeX: say so before the slow part
    targets = tuple(out / name for name in file_names(sheet, chosen, formats))
    inputs = [sheet.path, *(p.path for p in sheet.problems), *([students] if students else [])]
    resolved = {p.resolve() for p in inputs}
    existing = []
    for target in targets:
        if target.resolve() in resolved or (
            target.exists() and any(p.exists() and os.path.samefile(target, p) for p in inputs)
        ):
            raise UsageError(f"refusing to overwrite the input {target}; choose another -o")
        if target.is_dir():
            raise UsageError(f"{target} is a directory")
        if target.exists() and not force:
            existing.append(target)
    if existing:
        more = f" (and {len(existing) - 1} more)" if len(existing) > 1 else ""
        raise UsageError(f"{existing[0]} exists{more}; add --force to overwrite")
    return SheetPlan(sheet, out, tuple(formats), chosen, targets)


def run_sheet(
    plan: SheetPlan,
    *,
    seed: int = 0,
    workers: int | None = None,
    scheduler: str | None = None,
    timeout: float | None = None,
    method: str = "lagrange",
    on_done: Callable[[], None] | None = None,
) -> str:
    """Derive, build every sheet (in the executor), then write every file; returns a one-line report."""
    from tutgen.api import write_outputs
    from tutgen.sheet.build import build_sheet, derive_problems
    from tutgen.sheet.executor import make_executor

    derivations, derive_seconds = derive_problems(plan.sheet, method, timeout)
    executor = make_executor(workers, scheduler)
    try:
        build = build_sheet(
            plan.sheet,
            formats=plan.formats,
            variants=plan.variants,
            seed=seed,
            executor=executor,
            derivations=derivations,
            method=method,
            on_done=on_done,
        )
    finally:
        close = getattr(executor, "close", None)
        if close:
            close()
    names = [plan.out / name for name, _ in build.files]
    assert names == list(plan.targets), "the build made other files than planned"
    write_outputs(names, [content for _, content in build.files])
    variants = f", {len(plan.variants)} variants" if plan.variants else ""
    return (
        f"wrote {len(names)} files to {plan.out}{variants} "
        f"(derivation {derive_seconds + build.derive_seconds:.1f} s, rendering {build.render_seconds:.1f} s"
        f" of worker time)"
    )
