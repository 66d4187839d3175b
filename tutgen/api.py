"""The library face of the CLI: load, derive, render, write — in that order, all or nothing.

:func:`load`, :func:`loads`, :func:`derive`, :func:`render` and :func:`check` are the public Python API,
re-exported as ``tutgen.load`` … (docs/api.md); the rest serves the command line.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

from tutgen.errors import Location, SpecError, SpecErrors, TemplateError, UsageError

if TYPE_CHECKING:  # pragma: no cover
    from tutgen.check.run import CheckRun
    from tutgen.engine.derivation import Derivation
    from tutgen.model.system import System

EXTENSIONS = {"md": ".md", "tex": ".tex", "pdf": ".pdf", "json": ".json"}


def load(path: str | Path) -> System:
    """Read and validate a spec file: a ``System`` (tutgen/model/system.py), or
    :class:`~tutgen.errors.SpecErrors` with every problem at its file:line:col."""
    from tutgen.spec.validate import load_system

    return load_system(path)


def loads(text: str, name: str = "<spec>") -> System:
    """:func:`load` of a spec's text; ``name`` is the file name its errors are reported at."""
    from tutgen.spec.validate import load_system_text

    return load_system_text(text, name)


def derive(system: System, *args: object, **kwargs: object) -> Derivation:
    """Everything the spec asks for, in teaching order (:func:`tutgen.engine.pipeline.derive`; its
    options, such as the methods to present, are passed on). Raises
    :class:`~tutgen.errors.DerivationError` for a spec tutgen cannot derive."""
    from tutgen.engine.pipeline import derive as derive_system

    return derive_system(system, *args, **kwargs)


def check(spec: str | Path, answers: Sequence[str | Path], **options: object) -> CheckRun:
    """Mark answers files against a spec, as ``tutgen check`` does (:func:`tutgen.check.run.check`; its
    options ``key``, ``jobs``, ``answer_timeout``, ``file_timeout`` are passed on). The result's
    ``exit_code`` is the command's; ``files`` holds each file's verdict, item by item."""
    from tutgen.check.run import check as check_files

    return check_files(spec, answers, **options)  # type: ignore[arg-type]


def render(
    derivation: object, fmt: str = "md", template_dir: Path | None = None, *, expand: bool = False
) -> str | bytes:
    """Render one derivation in a format: 'md', 'tex', 'json' give text, 'pdf' gives bytes
    (the 'tex' document compiled with latexmk; :class:`tutgen.render.pdf.PdfError` if it cannot be).
    An error in a user's template (``template_dir``) is a :class:`~tutgen.errors.TemplateError`.
    ``expand``: the JSON of a large serial arm with its entries written out, not only its program
    (``tutgen solve --expand``, docs/json-output.md#the-program-of-a-serial-arm)."""
    with user_template_errors(template_dir):
        return _render(derivation, fmt, template_dir, expand)


def _render(derivation: object, fmt: str, template_dir: Path | None, expand: bool = False) -> str | bytes:
    from tutgen.engine.derivation import Derivation

    assert isinstance(derivation, Derivation)
    if fmt == "json":
        from tutgen.render.jsonout import derivation_to_json, dumps

        return dumps(derivation_to_json(derivation, expand=expand))
    if fmt in ("tex", "pdf"):
        from tutgen.render.latex import render_latex

        tex = render_latex(derivation, template_dir)
        if fmt == "tex":
            return tex
        from tutgen.figure.picture import picture_files
        from tutgen.render.pdf import compile_pdf

        files = picture_files([derivation.system])  # the spec's own picture
        if derivation.simulation is not None:  # the plots of `ask: [simulation]`, by their names in the .tex
            from tutgen.render.sections.simulation import tex_files

            files.update(tex_files(derivation.simulation))
        return compile_pdf(tex, files=files)
    from tutgen.render.markdown import render_markdown

    return render_markdown(derivation, template_dir)


@contextmanager
def user_template_errors(template_dir: Path | None) -> Iterator[None]:
    """Errors of a user's templates as :class:`~tutgen.errors.TemplateError` (a usage error, exit 2),
    located at the template line where Jinja stopped. Without ``template_dir`` the templates are
    tutgen's own, and an error in them is a bug: it is let through."""
    import jinja2

    try:
        yield
    except jinja2.TemplateSyntaxError as err:
        if template_dir is None:
            raise
        where = Location(err.filename or err.name or str(template_dir), err.lineno or 0)
        raise TemplateError(where, f"template syntax: {err.message}") from None
    except jinja2.TemplateError as err:
        if template_dir is None:
            raise
        # "undefined", "unsafe" (the sandbox) or "not found"; Jinja puts the template's frames, with
        # the template's file and line, into the traceback
        raise TemplateError(_template_frame(err, template_dir), f"template: {err.message or err}") from None
    except RecursionError as err:
        where = _template_frame(err, template_dir) if template_dir is not None else None
        if where is None or where.line == 0:  # not in a user's template: not the user's error
            raise
        raise TemplateError(where, "the templates include or call themselves without end") from None


def _template_frame(err: BaseException, template_dir: Path) -> Location:
    """The last traceback frame that runs a file of ``template_dir`` (or the directory itself)."""
    root = os.path.realpath(template_dir)
    found = Location(str(template_dir))
    tb = err.__traceback__
    while tb is not None:
        name = tb.tb_frame.f_code.co_filename
        if name.startswith(str(template_dir)) or os.path.realpath(name).startswith(root + os.sep):
            found = Location(name, tb.tb_lineno)
        tb = tb.tb_next
    return found


def solve_specs(
    paths: list[Path],
    fmt: str,
    method: str | None = None,
    template_dir: Path | None = None,
    timeout: float | None = None,
) -> list[str | bytes]:
    """Load every spec (reporting all their errors at once), derive each, render each: all of it
    within ``timeout`` seconds (None or 0 for no limit), one budget shared by the three stages, so a
    :class:`~tutgen.errors.DerivationTimeout` names the stage it ran out in."""
    return solve_and_derive(paths, fmt, method, template_dir, timeout)[0]


def solve_and_derive(
    paths: list[Path],
    fmt: str,
    method: str | None = None,
    template_dir: Path | None = None,
    timeout: float | None = None,
    expand: bool = False,
) -> tuple[list[str | bytes], list[Derivation]]:
    """:func:`solve_specs`, and the derivations it rendered (for :func:`figure_files`); ``expand`` as
    in :func:`render`."""
    from tutgen.engine.pipeline import derive_with_deadline
    from tutgen.limits import deadline, stage
    from tutgen.spec.validate import load_system

    if template_dir is not None and not template_dir.is_dir():
        raise UsageError(f"--template-dir {template_dir}: not a directory")
    if fmt == "pdf":
        from tutgen.render.pdf import find_latexmk

        find_latexmk()  # no LaTeX: say so before the slow part
    with deadline(timeout):
        systems = []
        errors: list[SpecError] = []
        for path in paths:
            stage("loading the specs", path.name)
            try:
                systems.append(load_system(path))
            except SpecErrors as exc:
                errors += exc.errors
        if errors:
            raise SpecErrors(errors)
        derivations = [derive_with_deadline(system, method, timeout) for system in systems]
        derivations = simulate_asked(derivations, timeout)
        texts = []
        for path, d in zip(paths, derivations, strict=True):
            stage("rendering", f"{path.name} as {fmt}")
            texts.append(render(d, fmt, template_dir, expand=expand))
        return texts, derivations


def simulate_asked(derivations: list[Derivation], timeout: float | None = None) -> list[Derivation]:
    """Each derivation with the run of its `simulate` section when it asks for one (``ask:
    [simulation]``, tutgen/sim/solution.py); scipy and matplotlib are imported only then."""
    from tutgen.engine.steps import StepKind
    from tutgen.limits import stage

    if not any(d.has_step(StepKind.SIMULATION) for d in derivations):
        return derivations
    from tutgen.sim.solution import attach_simulation

    out = []
    for d in derivations:
        if d.has_step(StepKind.SIMULATION):
            stage("simulation", Path(d.system.source).name)
        out.append(attach_simulation(d, timeout))
    return out


#: Used where the file system cannot be asked (``pathconf``): the limits of Linux and macOS.
NAME_MAX = 255
PATH_MAX = 4096


def check_output_path(path: Path, option: str = "-o", limits: dict[Path, int] | None = None) -> None:
    """Refuse, as a usage error, an output path no file system can hold: a NUL byte, a name longer
    than the file system allows (``NAME_MAX``, in bytes), a path longer than ``PATH_MAX``. ``limits``:
    the NAME_MAX found for each parent directory, kept by a caller that checks many paths at once (a
    sheet's 4 617 files live in a few hundred directories)."""
    text = str(path)
    if "\0" in text:
        raise UsageError(f"{option}: a path cannot contain a NUL character")
    encoded = os.fsencode(text)
    if len(encoded) >= PATH_MAX:
        raise UsageError(f"{option}: the path is {len(encoded)} bytes long; at most {PATH_MAX - 1} are allowed")
    parts = path.parts
    if limits is None:
        limit = _name_max(path)
    elif path.parent in limits:  # its directory's names were checked with the first path in it
        limit, parts = limits[path.parent], (path.name,)
    else:
        limit = limits[path.parent] = _name_max(path)
    for part in parts:
        if len(os.fsencode(part)) > limit:
            shown = part[:40] + "…"
            raise UsageError(
                f"{option}: the name '{shown}' is {len(os.fsencode(part))} bytes long; the file system allows {limit}"
            )


def _name_max(path: Path) -> int:
    """NAME_MAX of the file system that would hold ``path``: asked of its nearest existing ancestor."""
    probe = path.absolute()
    for candidate in (probe, *probe.parents):
        try:
            if candidate.exists():
                return int(os.pathconf(candidate, "PC_NAME_MAX"))
        except (OSError, ValueError):
            continue
    return NAME_MAX


def plan_outputs(specs: list[Path], output: str | Path, fmt: str, *, force: bool) -> list[Path]:
    """Where each result goes; refuse to overwrite a spec, or an existing file without --force.

    ``output`` is a directory when there are several specs, when it is an existing directory, or
    when it ends with a path separator (``-o out/``); otherwise it is the file to write.
    """
    ext = EXTENSIONS[fmt]
    text = str(output)
    out = Path(output)
    check_output_path(out)
    if len(specs) > 1 or out.is_dir() or text.endswith(("/", os.sep)):
        if out.exists() and not out.is_dir():
            raise UsageError(f"-o {text}: several specs need a directory, and this is a file")
        targets = [out / (spec.stem + ext) for spec in specs]
        stems = [t.name for t in targets]
        dupes = sorted({s for s in stems if stems.count(s) > 1})
        if dupes:
            raise UsageError(f"two specs would write the same file: {', '.join(dupes)}; solve them separately")
    else:
        targets = [out]
    for target in targets:
        check_output_path(target)
        if _is_spec(target, specs):
            raise UsageError(f"refusing to overwrite the spec {target} with the solution; choose another -o")
        if target.is_dir():
            raise UsageError(f"-o {target}: this is a directory; add a trailing '/' to write into it")
        if target.exists() and not force:
            raise UsageError(f"{target} exists; add --force to overwrite it")
    return targets


def _is_spec(target: Path, specs: list[Path]) -> bool:
    """Whether ``target`` is one of the input files (by path, through symlinks, or as a hard link)."""
    if target.resolve() in {spec.resolve() for spec in specs}:
        return True
    if not target.exists():
        return False
    return any(spec.exists() and os.path.samefile(target, spec) for spec in specs)


def write_outputs(targets: list[Path], texts: list[str] | list[bytes] | list[str | bytes]) -> None:
    """Write each text (or PDF's bytes) through a temporary file and a rename, so no file is ever
    half-written."""
    umask = os.umask(0)
    os.umask(umask)
    for target, text in zip(targets, texts, strict=True):
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
        except OSError as err:
            raise UsageError(f"cannot write {target}: {err.strerror or err}") from None
        try:
            # mkstemp makes the file readable by its owner only; give it the usual permissions
            os.fchmod(fd, 0o666 & ~umask)
            if isinstance(text, bytes):
                with os.fdopen(fd, "wb") as fb:
                    fb.write(text)
            else:
                with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
                    fh.write(text)
            os.replace(tmp, target)
        except BaseException as err:
            Path(tmp).unlink(missing_ok=True)
            if isinstance(err, OSError):
                raise UsageError(f"cannot write {target}: {err.strerror or err}") from None
            raise


def simulation_files(derivation: Derivation | None, directory: Path) -> tuple[list[Path], list[bytes]]:
    """The plots of a derivation's simulation (``ask: [simulation]``) as files in ``directory``: beside
    a Markdown, LaTeX or JSON solution, which refer to them by name."""
    if derivation is None or derivation.simulation is None:
        return [], []
    plots = derivation.simulation.plots
    return [directory / p.name for p in plots], [p.png for p in plots]


def figure_files(
    specs: list[Path], targets: list[Path], *, force: bool, derivations: Sequence[Derivation] | None = None
) -> tuple[list[Path], list[str | bytes]]:
    """The files a Markdown solution refers to, to be written beside it: the generated figure's SVG
    (``<spec>.figure.svg``), the free-body diagrams of its Newton–Euler step (``<spec>.fbd-<body>.svg``,
    with ``derivations``, where that step is printed), the plots of its simulation (``ask:
    [simulation]``: ``<spec>.simulation.png``, ``<spec>.snapshots.png``) and a copy of the spec's own
    picture (``figure.file``, same relative path). Refuses to overwrite an existing file without
    ``force``, as the solutions themselves."""
    from tutgen.figure.picture import read_picture
    from tutgen.figure.view import svg_file
    from tutgen.render.sections.newton_euler import free_bodies
    from tutgen.spec.validate import load_system

    paths: list[Path] = []
    contents: list[str | bytes] = []
    for i, (spec, target) in enumerate(zip(specs, targets, strict=True)):
        system = load_system(spec) if derivations is None else derivations[i].system
        svg = svg_file(system)
        if svg is not None:
            paths.append(target.parent / svg[0])
            contents.append(svg[1])
        for view in free_bodies(derivations[i]) if derivations is not None else []:
            paths.append(target.parent / view["svg"])
            contents.append(view["svg_text"])
        paths_, pngs = simulation_files(derivations[i] if derivations is not None else None, target.parent)
        paths += paths_
        contents += pngs
        picture = system.figure.file if system.figure is not None else None
        if picture is not None and picture.kind.value != "pdf":
            copy = target.parent / picture.path
            if copy.resolve() != picture.resolved:
                paths.append(copy)
                contents.append(read_picture(system))  # checked again as it is opened
    _refuse_overwrite(paths, specs, force)
    return paths, contents


def plot_files(
    specs: list[Path], targets: list[Path], derivations: Sequence[Derivation], *, force: bool
) -> tuple[list[Path], list[str | bytes]]:
    """The simulation plots a LaTeX or JSON solution names, to be written beside it (a Markdown
    solution's are among its :func:`figure_files`); refuses to overwrite as they do."""
    paths: list[Path] = []
    contents: list[str | bytes] = []
    for target, d in zip(targets, derivations, strict=True):
        more, pngs = simulation_files(d, target.parent)
        paths += more
        contents += pngs
    _refuse_overwrite(paths, specs, force)
    return paths, contents


def _refuse_overwrite(paths: list[Path], specs: list[Path], force: bool) -> None:
    for path in paths:
        if _is_spec(path, specs):
            raise UsageError(f"refusing to overwrite the spec {path} with a figure; choose another -o")
        if path.exists() and not force:
            raise UsageError(f"{path} exists; add --force to overwrite it")
