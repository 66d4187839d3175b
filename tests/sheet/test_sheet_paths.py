"""A sheet's output paths are planned before anything is written (names that collide on some file
system, or that a file system cannot hold, are refused up front), the output is written whole or not
at all, and one run at a time holds it."""

from __future__ import annotations

import errno
import os
from pathlib import Path

import pytest

from tutgen.errors import UsageError
from tutgen.sheet.run import SheetPlan, check_names, lock_path, output_lock, write_tree


@pytest.mark.parametrize(
    ("names", "expected"),
    [
        pytest.param(["variants/Ada/q.md", "variants/ADA/q.md"], "the same file where case does not count", id="case"),
        pytest.param(
            ["variants/index.csv", "variants/index.csv/q.md"], "as a file and as the directory", id="file-dir"
        ),
        pytest.param(
            ["variants/Index.CSV/q.md", "variants/index.csv"], "as a file and as the directory", id="file-dir-case"
        ),
        pytest.param(["specs/CON.yaml"], "Windows device 'CON.yaml'", id="device"),
        pytest.param(["specs/aux"], "Windows device 'aux'", id="device-bare"),
        pytest.param(["variants/a./q.md"], "ending in a dot or a space", id="dot"),
        pytest.param(["x" * 256], "longer than 255 bytes", id="long"),
        pytest.param(["q.md", "q.md"], "one file twice", id="twice"),
    ],
)
def test_sheet_paths_that_collide_or_cannot_exist_are_refused(names: list[str], expected: str) -> None:
    with pytest.raises(UsageError, match=expected):
        check_names(names)


def test_sheet_paths_that_are_distinct_everywhere_pass() -> None:
    check_names(["questions.md", "variants/A1/questions.md", "variants/A2/questions.md", "variants/index.csv",
                 "variants/console/q.md", "variants/com10/q.md"])  # fmt: skip


def _plan(out: Path, force: bool = True) -> SheetPlan:
    return SheetPlan(sheet=None, out=out, formats=(), variants=(), targets=(), force=force)  # type: ignore[arg-type]


def test_sheet_write_that_fails_midway_leaves_the_old_output(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A write that fails after some files (a full disk) leaves the old output as it was and no
    temporary directory beside it; the error is the user's, with the file it stopped at."""
    out = tmp_path / "out"
    (out / "variants").mkdir(parents=True)
    (out / "questions.md").write_text("old\n", encoding="utf-8")
    real_open = open
    written: list[str] = []

    def failing_open(path: object, *args: object, **kwargs: object) -> object:
        if str(path).endswith("v002/questions.md"):
            raise OSError(errno.ENOSPC, "No space left on device")
        written.append(str(path))
        return real_open(path, *args, **kwargs)  # type: ignore[call-overload]

    monkeypatch.setattr("builtins.open", failing_open)
    files = [("questions.md", "new\n"), ("variants/v001/questions.md", "1\n"), ("variants/v002/questions.md", "2\n")]
    with pytest.raises(UsageError, match=r"cannot write .*v002/questions.md: No space left on device"):
        write_tree(_plan(out), files)
    monkeypatch.undo()
    assert len(written) == 2  # it did get part of the way
    assert (out / "questions.md").read_text(encoding="utf-8") == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
    assert sorted(str(p.relative_to(out)) for p in out.rglob("*")) == ["questions.md", "variants"]


def test_sheet_write_replaces_the_old_output_as_a_whole(tmp_path: Path) -> None:
    out = tmp_path / "out"
    (out / "variants" / "v009").mkdir(parents=True)
    (out / "variants" / "v009" / "questions.md").write_text("stale\n", encoding="utf-8")
    write_tree(_plan(out), [("questions.md", "new\n"), ("variants/v001/key.yaml", b"k\n")])
    assert sorted(str(p.relative_to(out)) for p in out.rglob("*") if p.is_file()) == [
        "questions.md",
        "variants/v001/key.yaml",
    ]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_sheet_lock_is_exclusive_and_removed(tmp_path: Path) -> None:
    out = tmp_path / "out"
    with output_lock(out):
        assert lock_path(out).exists()
        with pytest.raises(UsageError, match=rf"another tutgen run is writing it \(process {os.getpid()}\)"):
            with output_lock(out):
                pass
    assert not lock_path(out).exists()
    with output_lock(out):  # free again
        pass


def test_sheet_write_swaps_an_existing_output_in_one_step(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """On Linux the new tree and an existing -o are exchanged in one renameat2(RENAME_EXCHANGE): no
    rename ever moves -o aside, so no moment exists without it."""
    if not hasattr(os, "uname") or os.uname().sysname != "Linux":
        pytest.skip("renameat2 is Linux's")
    out = tmp_path / "out"
    out.mkdir()
    (out / "questions.md").write_text("old\n", encoding="utf-8")
    moved: list[str] = []
    real_rename = os.rename

    def spy(src: object, dst: object) -> None:
        moved.append(str(src))
        real_rename(src, dst)  # type: ignore[arg-type]

    monkeypatch.setattr(os, "rename", spy)
    write_tree(_plan(out), [("questions.md", "new\n")])
    assert str(out) not in moved
    assert (out / "questions.md").read_text(encoding="utf-8") == "new\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
