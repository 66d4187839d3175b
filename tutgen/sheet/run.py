"""The library face of `tutgen sheet`: check the inputs and the outputs, build, write, all or nothing.

A sheet writes a whole tree, so it is planned and written as one:

- **Plan every path first** (:func:`check_names`): before anything is derived, every file the build
  will make is known, and the set is refused if two of them are the same file on some file system
  (``Ada``/``ADA`` on a case-insensitive one), if a file is also a directory of another
  (a student id ``index.csv`` beside ``variants/index.csv``), if a name is a Windows device (``CON``,
  ``nul.txt``), ends in a dot or a space, or is longer than the file system allows.
- **Write into a temporary directory beside -o, then rename it into place** (:func:`write_tree`), so
  an interrupted or failed run leaves the old output or the new one, never a mixture. An existing,
  non-empty ``-o`` is replaced only with ``--force``, and only if it holds nothing but a sheet's
  output: an input inside it, or a file that is not a sheet's, is never deleted.
- **One run per output** (:func:`output_lock`): a lock file beside ``-o`` (``flock``: released by the
  kernel however the run ends), removed when the run ends; a second run into the same ``-o`` while
  one holds it is refused.
"""

from __future__ import annotations

import contextlib
import ctypes
import dataclasses
import errno
import fcntl
import os
import re
import shutil
import tempfile
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tutgen.errors import SpecError, SpecErrors, UsageError
from tutgen.sheet.files import write_files
from tutgen.sheet.model import WINDOWS_DEVICES, Sheet
from tutgen.sheet.variants import Variant

#: What may sit at the top of a sheet's output (anything under ``variants/`` and ``figures/`` is the
#: sheet's own: the variants, and the SVGs its Markdown sheets show beside the problems).
_OUTPUT_ENTRY = re.compile(r"(?:questions|solutions)(?:[.-][A-Za-z0-9._-]*)?|variants|figures")


@dataclass(frozen=True)
class SheetPlan:
    sheet: Sheet
    out: Path
    formats: tuple[str, ...]
    variants: tuple[Variant, ...]
    targets: tuple[Path, ...]
    force: bool = False
    inputs: tuple[Path, ...] = ()

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
    """Read the sheet (and the roster), plan every output path, and refuse early: no -o, both
    --variants and --students, paths that collide or that a file system cannot hold, an output onto
    or around an input file, an existing output without --force."""
    from tutgen.api import check_output_path
    from tutgen.limits import stage
    from tutgen.sheet.build import file_names
    from tutgen.sheet.model import load_roster, load_sheet
    from tutgen.sheet.variants import variant_ids

    if output is None:
        raise UsageError("tutgen sheet writes several files: add -o DIR")
    if variants is not None and students is not None:
        raise UsageError("give --variants or --students, not both")
    out = Path(output)
    check_output_path(out)
    stage("loading the sheet", sheet_file.name)
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
    names = file_names(sheet, chosen, formats)
    check_names(names)
    targets = tuple(out / name for name in names)
    limits: dict[Path, int] = {}  # NAME_MAX by directory, asked once for each
    for target in targets:
        check_output_path(target, limits=limits)
    inputs = (sheet.path, *(p.path for p in sheet.problems), *([students] if students else []))
    check_existing(out, inputs, force=force)
    return SheetPlan(sheet, out, tuple(formats), chosen, targets, force, inputs)


def replanned(plan: SheetPlan, derivations: Sequence[Any]) -> SheetPlan:
    """``plan`` with every file the derived problems add (their free-body diagrams and simulation
    plots, tutgen/sheet/assets.py), checked as the first plan was, before anything is built."""
    from tutgen.api import check_output_path
    from tutgen.sheet.build import file_names

    names = file_names(plan.sheet, plan.variants, plan.formats, derivations)
    check_names(names)
    targets = tuple(plan.out / name for name in names)
    checked = set(plan.targets)  # by plan_sheet
    limits: dict[Path, int] = {}
    for target in targets:
        if target not in checked:
            check_output_path(target, limits=limits)
    return dataclasses.replace(plan, targets=targets)


def check_names(names: Sequence[str]) -> None:
    """Refuse (UsageError) a set of relative output paths that some file system cannot hold as
    distinct files: see the module's docstring."""
    from tutgen.api import NAME_MAX

    files: dict[str, str] = {}
    dirs: dict[str, str] = {}
    for name in names:
        parts = name.split("/")
        for part in parts:
            stem = part.split(".")[0].casefold()
            if stem in WINDOWS_DEVICES:
                raise UsageError(f"the output file {name} is named after the Windows device '{part}'; rename it")
            if part.endswith((".", " ")) or not part:
                raise UsageError(f"the output file {name} has a name ending in a dot or a space; rename it")
            if len(os.fsencode(part)) > NAME_MAX:
                raise UsageError(f"the output file {name[:60]}… has a name longer than {NAME_MAX} bytes")
        for i in range(1, len(parts)):
            folded = "/".join(parts[:i]).casefold()
            dirs.setdefault(folded, "/".join(parts[:i]))
        folded = name.casefold()
        if folded in files:
            other = files[folded]
            why = "twice" if other == name else f"as {other} and {name}, the same file where case does not count"
            raise UsageError(f"the sheet would write one file {why}; rename one of them")
        files[folded] = name
    for folded, name in files.items():
        if folded in dirs:
            raise UsageError(
                f"the sheet would write {name} as a file and as the directory of {dirs[folded]}/…; rename one of them"
            )


def check_existing(out: Path, inputs: Sequence[Path], *, force: bool) -> None:
    """An existing -o may be replaced (with --force) only if nothing in it is an input or not a sheet's."""
    if not out.exists():
        return
    real = Path(os.path.realpath(out))
    for path in inputs:
        rp = Path(os.path.realpath(path))
        if rp == real or real in rp.parents:
            raise UsageError(f"refusing to write a sheet over {out}: the input {path} is inside it; choose another -o")
    try:
        entries = sorted(os.listdir(out))
    except OSError as err:
        raise UsageError(f"-o {out}: cannot read it: {err.strerror or err}") from None
    if not entries:
        return
    if not force:
        raise UsageError(f"{out} exists and is not empty; add --force to replace it with the new sheet")
    foreign = [e for e in entries if not _OUTPUT_ENTRY.fullmatch(e)]
    if foreign:
        more = f" (and {len(foreign) - 1} more)" if len(foreign) > 1 else ""
        raise UsageError(
            f"refusing to replace {out}: it holds {out / foreign[0]}, which is not part of a sheet's output{more}"
        )


def lock_path(out: Path) -> Path:
    """The lock file of an output directory: beside it, named after it."""
    real = Path(os.path.realpath(out))
    return real.parent / f".{real.name}.tutgen-lock"


@contextlib.contextmanager
def output_lock(out: Path) -> Iterator[None]:
    """Hold the lock of ``out`` for the block; UsageError if another run holds it.

    ``flock`` is released by the kernel when the holder exits, however it exits, so a killed run
    leaves no stale lock (at most the empty file, which the next run takes and removes). The file is
    removed on the way out; a run that opened it just before is told by the inode check and retries.
    """
    path = lock_path(out)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise UsageError(f"-o {out}: cannot create its parent directory: {err.strerror or err}") from None
    for _ in range(20):
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0), 0o644)
        except OSError as err:
            raise UsageError(f"-o {out}: cannot create the lock file {path}: {err.strerror or err}") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as err:
            holder = _read_pid(fd)
            os.close(fd)
            if err.errno in (errno.EAGAIN, errno.EACCES, errno.EWOULDBLOCK):
                who = f" (process {holder})" if holder else ""
                raise UsageError(
                    f"-o {out}: another tutgen run is writing it{who}; wait for it to finish or choose another -o"
                ) from None
            raise UsageError(f"-o {out}: cannot lock {path}: {err.strerror or err}") from None
        try:
            same = os.fstat(fd).st_ino == os.stat(path, follow_symlinks=False).st_ino
        except OSError:
            same = False
        if same:
            break
        os.close(fd)  # the holder removed it as we opened it: take the new one
    else:  # pragma: no cover - twenty races in a row
        raise UsageError(f"-o {out}: cannot take the lock {path}")
    try:
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()}\n".encode())
        yield
    finally:
        from tutgen.limits import shielded

        with shielded():
            with contextlib.suppress(OSError):
                os.unlink(path)
            os.close(fd)


def _read_pid(fd: int) -> str:
    try:
        text = os.pread(fd, 32, 0).decode("ascii", errors="replace").strip()
    except OSError:
        return ""
    return text if text.isdigit() else ""


def write_tree(plan: SheetPlan, files: Sequence[tuple[str, str | bytes | None]]) -> None:
    """Write every file into a temporary directory beside -o, then put it in -o's place (replacing an
    existing output, which :func:`plan_sheet` allowed); on any error or interruption the temporary
    directory is removed and -o is as it was."""
    with staging(plan) as tmp:
        write_files(tmp, files, plan.out)
        put_in_place(plan, tmp)


@contextlib.contextmanager
def staging(plan: SheetPlan) -> Iterator[Path]:
    """A new temporary directory beside -o for the sheet's files (written there by :func:`write_files`,
    in this process or in the workers of a local executor), removed if the block fails or is
    interrupted; :func:`put_in_place` moves it to -o. An OSError becomes a UsageError naming -o."""
    from tutgen.limits import shielded

    out = Path(os.path.realpath(plan.out))
    umask = os.umask(0)
    os.umask(umask)
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}.", suffix=".tmp", dir=out.parent))
    except OSError as err:
        raise UsageError(f"cannot write {plan.out}: {err.strerror or err}") from None
    try:
        os.chmod(tmp, 0o777 & ~umask)  # mkdtemp makes it private; the output is an ordinary directory
        yield tmp
    except BaseException as err:
        with shielded():
            shutil.rmtree(tmp, ignore_errors=True)
        if isinstance(err, OSError):
            raise UsageError(f"cannot write {plan.out}: {err.strerror or err}; nothing was written") from None
        raise


def put_in_place(plan: SheetPlan, tmp: Path) -> None:
    """The staging directory ``tmp`` becomes -o, in one step (see :func:`_swap`), if -o still holds
    nothing but a sheet's output."""
    from tutgen.limits import shielded

    with shielded():  # the swap is one exchange (or, where there is none, two renames): nothing may stop it
        check_existing(plan.out, plan.inputs, force=plan.force)  # as planned, still
        _swap(tmp, Path(os.path.realpath(plan.out)))


#: Linux's renameat2: the directory file descriptor meaning "the current directory", and the flag that
#: swaps two paths in one atomic step.
_AT_FDCWD = -100
_RENAME_EXCHANGE = 2


def _exchange(a: Path, b: Path) -> bool:
    """Swap the paths ``a`` and ``b`` in one atomic step (Linux ``renameat2(RENAME_EXCHANGE)``), so that
    no moment exists in which ``b`` is missing; False where the system or file system has no such
    call (the caller then renames twice)."""
    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):  # not Linux, or a C library older than glibc 2.28
        return False
    renameat2.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    renameat2.restype = ctypes.c_int
    if renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP, errno.ENOTSUP):
        return False  # a kernel or file system without the flag
    raise OSError(err, os.strerror(err), str(b))


def _swap(new: Path, out: Path) -> None:
    """``new`` becomes ``out``. An existing ``out`` is exchanged with ``new`` in one atomic step where
    the system can (Linux), then removed; elsewhere it is moved aside first, which leaves a moment
    with no ``out`` at all (never a mixture: the old tree is put back if the second rename fails)."""
    if not os.path.lexists(out):
        os.rename(new, out)
        return
    if _exchange(new, out):
        shutil.rmtree(new, ignore_errors=True)  # it holds the old output now
        return
    old = Path(tempfile.mkdtemp(prefix=f".{out.name}.", suffix=".old", dir=out.parent))
    os.rename(out, old)  # replaces the empty directory just made
    try:
        os.rename(new, out)
    except OSError:
        os.rename(old, out)  # put the old output back
        raise
    shutil.rmtree(old, ignore_errors=True)


def run_sheet(
    plan: SheetPlan,
    *,
    seed: int = 0,
    workers: int | None = None,
    scheduler: str | None = None,
    timeout: float | None = None,
    method: str | None = None,
    on_done: Callable[[], None] | None = None,
) -> str:
    """Derive, build every sheet (in the executor), then write every file; returns a one-line report.

    Deriving and building run within ``timeout`` seconds (one budget; inside an outer deadline, that
    one's); the whole run holds the output's lock."""
    from tutgen.limits import deadline, stage
    from tutgen.sheet.build import build_sheet, derive_problems
    from tutgen.sheet.executor import check_scheduler_address, make_executor

    if scheduler:
        check_scheduler_address(scheduler)
    with output_lock(plan.out), contextlib.ExitStack() as stack:
        staged: list[Path] = []

        def staging_dir() -> Path:
            """The staging directory, made when the first file is about to be written (a run stopped before
            leaves nothing behind); removed by ``stack`` if the run fails or is stopped."""
            if not staged:
                staged.append(stack.enter_context(staging(plan)))
            return staged[0]

        with deadline(timeout):
            executor = make_executor(workers, scheduler)
            try:
                stage("derivation", "the problems")
                derivations, derive_seconds = derive_problems(plan.sheet, method, timeout, executor)
                plan = replanned(plan, derivations)  # with the free-body diagrams and plots the derivations make
                stage("rendering", "the sheets")
                build = build_sheet(
                    plan.sheet,
                    formats=plan.formats,
                    variants=plan.variants,
                    seed=seed,
                    executor=executor,
                    derivations=derivations,
                    method=method,
                    on_done=on_done,
                    # the workers of this machine write each sheet's files as they build it (in parallel, and
                    # without sending them back); a Dask cluster's may be elsewhere: they send them back
                    stage=(lambda: (staging_dir(), plan.out)) if getattr(executor, "local", False) else None,
                )
            finally:
                close = getattr(executor, "close", None)
                if close:
                    close()
        names = [plan.out / name for name, _ in build.files]
        assert names == list(plan.targets), "the build made other files than planned"
        stage("writing", str(plan.out))
        write_files(staging_dir(), build.files, plan.out)
        put_in_place(plan, staging_dir())
    variants = f", {len(plan.variants)} variants" if plan.variants else ""
    notes = "".join(f"\nnote: {n}" for n in build.notes)  # what an LMS export left out, by name
    return (
        f"wrote {len(names)} files to {plan.out}{variants} "
        f"(derivation {derive_seconds + build.derive_seconds:.1f} s, rendering {build.render_seconds:.1f} s"
        f" of worker time){notes}"
    )
