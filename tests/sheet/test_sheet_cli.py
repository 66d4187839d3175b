"""`tutgen sheet` end to end: files, determinism across runs and worker counts, keys marked by
`tutgen check`, rosters, errors, Dask, and no Dask import without it."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from typer.testing import CliRunner, Result

from tests.conftest import ROOT, SPECS
from tutgen.cli.main import app
from tutgen.errors import EXIT_CHECK_FAILED, EXIT_INVALID_SPEC, EXIT_OK, EXIT_USAGE

TUTORIAL = SPECS / "tutorial-1"
SHEET = f"""
title: Small tutorial
course: ME4245
date: 2 February 2026
problems:
  - spec: {TUTORIAL / "p03-cart-pendulum.yaml"}
    vary:
      m1: {{range: [1, 5], step: 0.5, unit: kg}}
      l: {{choices: [0.5, 0.75, 1], unit: m}}
      g: 9.81 m/s^2
  - spec: {TUTORIAL / "p06-two-prismatic.yaml"}
    vary:
      m1: {{range: [2, 6], step: 0.5, unit: kg}}
      m2: {{range: [0.5, 3], step: 0.5, unit: kg}}
  - {TUTORIAL / "p10-given-kinetic-energy.yaml"}
"""


def run(*args: str | Path) -> Result:
    return CliRunner().invoke(app, [str(a) for a in args])


def tree(out: Path) -> dict[str, bytes]:
    return {str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def small(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """A three-problem sheet built with three variants, md and tex, by two workers."""
    tmp = tmp_path_factory.mktemp("sheet")
    sheet = tmp / "sheet.yaml"
    sheet.write_text(SHEET, encoding="utf-8")
    out = tmp / "out"
    result = run("sheet", sheet, "-o", out, "-f", "md", "-f", "tex", "--variants", "3", "--seed", "5", "-j", "2")
    assert result.exit_code == EXIT_OK, result.output
    return sheet, out


def test_sheet_writes_the_documented_layout(small: tuple[Path, Path]) -> None:
    _, out = small
    names = set(tree(out))
    assert {"questions.md", "questions.tex", "solutions.md", "solutions.tex", "variants/index.csv"} <= names
    for v in ("v001", "v002", "v003"):
        for p in ("p03-cart-pendulum", "p06-two-prismatic", "p10-given-kinetic-energy"):
            assert f"variants/{v}/specs/{p}.yaml" in names
            assert f"variants/{v}/key-{p}.yaml" in names
            assert f"variants/{v}/marking-{p}.yaml" in names
        for doc in ("questions.md", "questions.tex", "solutions.md", "solutions.tex"):
            assert f"variants/{v}/{doc}" in names
    figures = {f"figures/{p}.svg" for p in ("p03-cart-pendulum", "p06-two-prismatic", "p10-given-kinetic-energy")}
    assert figures <= names
    # p03 presents Newton-Euler: its two free bodies' SVGs beside each Markdown sheet (tutgen/sheet/assets.py)
    fbds = {f"figures/p03-cart-pendulum.fbd-{body}.svg" for body in ("cart", "pendulum")}
    assert fbds <= names and all(f"variants/{v}/{f}" in names for v in ("v001", "v002", "v003") for f in fbds)
    assert len(names) == 4 + 3 + 2 + 1 + 3 * (3 * 3 + 4 + 3 + 2)


def test_markdown_solution_sheets_show_the_free_bodies_written_beside_them(small: tuple[Path, Path]) -> None:
    """The same free-body diagrams as `tutgen solve -f md` shows, each by a link that exists; a variant's
    are drawn with its own numbers' problem, and each file is written once."""
    import re

    _, out = small
    for sheet in [out / "solutions.md", *sorted(out.glob("variants/*/solutions.md"))]:
        links = re.findall(r"!\[Free body: ([^]]*)\]\(<([^>]+)>\)", sheet.read_text(encoding="utf-8"))
        assert links == [(b, f"figures/p03-cart-pendulum.fbd-{b}.svg") for b in ("cart", "pendulum")]
        for _, link in links:
            assert b"<svg" in (sheet.parent / link).read_bytes()[:400]
    questions = (out / "questions.md").read_text(encoding="utf-8")
    assert "Free body" not in questions


def test_markdown_sheets_show_each_problems_figure_beside_it(small: tuple[Path, Path]) -> None:
    """Every Markdown sheet, the nominal one and each variant's, refers to its problems' SVGs by relative
    paths that exist beside it."""
    import re

    _, out = small
    drawn: dict[str, set[bytes]] = {}
    for sheet in [out / "questions.md", out / "solutions.md", *sorted(out.glob("variants/*/*.md"))]:
        links = re.findall(r"!\[Figure: [^]]*\]\(<([^>]+)>\)", sheet.read_text(encoding="utf-8"))
        assert [Path(link).stem for link in links] == [
            "p03-cart-pendulum",
            "p06-two-prismatic",
            "p10-given-kinetic-energy",
        ]
        for link in links:
            svg = (sheet.parent / link).read_bytes()
            assert svg.startswith(b"<svg") or b"<svg" in svg[:200]
            drawn.setdefault(link, set()).add(svg)
    assert set(drawn) == {
        f"figures/{p}.svg" for p in ("p03-cart-pendulum", "p06-two-prismatic", "p10-given-kinetic-energy")
    }


def test_sheet_questions_and_solutions_show_the_variants_numbers(small: tuple[Path, Path]) -> None:
    _, out = small
    index = (out / "variants" / "index.csv").read_text().splitlines()
    assert index[0] == "id,label,p03-cart-pendulum:m1,p03-cart-pendulum:l,p06-two-prismatic:m1,p06-two-prismatic:m2"
    for row in index[1:]:
        vid, _, m1, length, _, _ = row.split(",")
        number, unit = m1.split()
        questions = (out / "variants" / vid / "questions.md").read_text()
        assert f"$m_1 = {number}\\ \\mathrm{{{unit}}}$ (mass of the cart)" in questions
        assert f"$l = {length.split()[0]}\\ \\mathrm{{m}}$" in questions
        assert questions.count("## Problem ") == 3 and "## Problem 3. Inertia matrix" in questions
        assert f"*Variant {int(vid[1:])}*" in questions and "**ME4245** · 2 February 2026" in questions
        solutions = (out / "variants" / vid / "solutions.md").read_text()
        assert "### 1. Kinematics" in solutions and "Christoffel symbols" in solutions
        spec = (out / "variants" / vid / "specs" / "p03-cart-pendulum.yaml").read_text()
        assert f'm1: {{value: "{m1}", description: "mass of the cart"}}' in spec
        tex = (out / "variants" / vid / "solutions.tex").read_text()
        assert "\\section*{Problem 1. Cart on a spring carrying a motor-driven pendulum}" in tex
    assert "range:" not in (out / "variants" / "v001" / "specs" / "p03-cart-pendulum.yaml").read_text()  # "lagrange"


def test_sheet_output_is_the_same_for_any_worker_count_and_run(small: tuple[Path, Path], tmp_path: Path) -> None:
    sheet, out = small
    again = tmp_path / "again"
    result = run("sheet", sheet, "-o", again, "-f", "md", "-f", "tex", "--variants", "3", "--seed", "5", "-j", "1")
    assert result.exit_code == EXIT_OK, result.output
    assert tree(again) == tree(out)
    other = tmp_path / "other"
    assert run("sheet", sheet, "-o", other, "--variants", "3", "--seed", "6", "-j", "1").exit_code == EXIT_OK
    assert (other / "variants/index.csv").read_text() != (out / "variants/index.csv").read_text()


@pytest.mark.parametrize("problem", ["p03-cart-pendulum", "p06-two-prismatic"])
def test_sheet_key_passes_its_variant_and_fails_another(small: tuple[Path, Path], problem: str) -> None:
    _, out = small
    v1, v2 = out / "variants" / "v001", out / "variants" / "v002"
    assert (v1 / "specs" / f"{problem}.yaml").read_text() != (v2 / "specs" / f"{problem}.yaml").read_text()
    own = run("check", v1 / "specs" / f"{problem}.yaml", v1 / f"key-{problem}.yaml")
    assert own.exit_code == EXIT_OK, own.output
    other = run("check", v2 / "specs" / f"{problem}.yaml", v1 / f"key-{problem}.yaml")
    assert other.exit_code == EXIT_CHECK_FAILED, other.output


def test_sheet_roster_gives_one_variant_per_student(small: tuple[Path, Path], tmp_path: Path) -> None:
    sheet, _ = small
    roster = tmp_path / "roster.csv"
    roster.write_text("id,name\nA0001,Ada Lovelace\nA0002,Charles Babbage\n", encoding="utf-8")
    out = tmp_path / "out"
    result = run("sheet", sheet, "-o", out, "--students", roster, "-j", "1")
    assert result.exit_code == EXIT_OK, result.output
    assert sorted(p.name for p in (out / "variants").iterdir()) == ["A0001", "A0002", "index.csv"]
    assert "*Ada Lovelace*" in (out / "variants" / "A0001" / "questions.md").read_text()
    assert "student: Ada Lovelace" in (out / "variants" / "A0001" / "key-p03-cart-pendulum.yaml").read_text()


def test_sheet_refuses_existing_files_and_bad_options(small: tuple[Path, Path], tmp_path: Path) -> None:
    sheet, out = small
    result = run("sheet", sheet, "-o", out, "--variants", "3", "--seed", "5")
    assert result.exit_code == EXIT_USAGE and "exists" in result.output and "--force" in result.output
    assert run("sheet", sheet).exit_code == EXIT_USAGE
    both = run("sheet", sheet, "-o", tmp_path / "x", "--variants", "2", "--students", sheet)
    assert both.exit_code == EXIT_USAGE and "not both" in both.output
    before = tree(sheet.parent)
    onto = run("sheet", sheet, "-o", sheet.parent, "--force")
    # -o is replaced as a whole, so a directory holding the sheet itself is never an output
    assert onto.exit_code == EXIT_USAGE and f"the input {sheet} is inside it" in onto.output
    assert tree(sheet.parent) == before


def test_sheet_force_replaces_the_whole_output(small: tuple[Path, Path], tmp_path: Path) -> None:
    """--force puts the new output in the old one's place: nothing of the old run is left (v003 of a
    three-variant run is gone after a two-variant run), and nothing that is not a sheet's is deleted."""
    sheet, _ = small
    out = tmp_path / "out"
    assert run("sheet", sheet, "-o", out, "--variants", "3", "-j", "1").exit_code == EXIT_OK
    assert (out / "variants" / "v003").is_dir()
    again = run("sheet", sheet, "-o", out, "--variants", "2", "-j", "1", "--force")
    assert again.exit_code == EXIT_OK, again.output
    assert sorted(p.name for p in (out / "variants").iterdir()) == ["index.csv", "v001", "v002"]
    (out / "notes.txt").write_text("mine", encoding="utf-8")
    before = tree(out)
    refused = run("sheet", sheet, "-o", out, "--variants", "2", "-j", "1", "--force")
    assert refused.exit_code == EXIT_USAGE and "notes.txt, which is not part of a sheet's output" in refused.output
    assert tree(out) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]  # no temporary directory, no lock file left


@pytest.mark.parametrize("workers", ["1", "2"])
def test_sheet_files_a_worker_cannot_write_leave_the_old_output(
    small: tuple[Path, Path], tmp_path: Path, monkeypatch: pytest.MonkeyPatch, workers: str
) -> None:
    """The workers write each sheet's files into the staging directory themselves (issue 17); a file one
    of them cannot write (a full disk) is the user's error, named as it would be under -o, and leaves the
    old output as it was, with no staging directory and no lock file beside it."""
    import builtins
    import errno

    sheet, _ = small
    out = tmp_path / "out"
    out.mkdir()
    (out / "questions.md").write_text("old\n", encoding="utf-8")
    real_open = builtins.open

    def failing_open(path: object, *args: object, **kwargs: object) -> object:
        if str(path).endswith("v002/solutions.md"):
            raise OSError(errno.ENOSPC, "No space left on device")
        return real_open(path, *args, **kwargs)  # type: ignore[call-overload]

    monkeypatch.setattr(builtins, "open", failing_open)  # a pool's workers are forked: they have it too
    result = run("sheet", sheet, "-o", out, "-f", "md", "--variants", "2", "-j", workers, "--force")
    monkeypatch.undo()
    assert result.exit_code == EXIT_USAGE, result.output
    where = out / "variants" / "v002" / "solutions.md"
    assert f"cannot write {where}: No space left on device; nothing was written" in result.output
    assert "Traceback" not in result.output
    assert tree(out) == {"questions.md": b"old\n"}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_sheet_bad_files_are_located_without_traceback(tmp_path: Path) -> None:
    sheet = tmp_path / "sheet.yaml"
    sheet.write_text(f"title: T\nproblems:\n  - spec: {TUTORIAL / 'p03-cart-pendulum.yaml'}\n    vary: {{m3: 1}}\n")
    roster = tmp_path / "roster.csv"
    roster.write_text("name\nAda\n")
    result = run("sheet", sheet, "-o", tmp_path / "out", "--students", roster)
    assert result.exit_code == EXIT_INVALID_SPEC
    assert f"{sheet}:4:12: error: the spec" in result.output and "no parameter 'm3'" in result.output
    assert f"{roster}:1:1: error: the roster's header has no 'id' column" in result.output
    assert "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


def test_sheet_tutorial_builds_and_every_key_checks(tmp_path: Path) -> None:
    """The whole tutorial, one variant: every problem's key passes `tutgen check` on its concrete spec."""
    out = tmp_path / "out"
    result = run("sheet", TUTORIAL / "sheet.yaml", "-o", out, "-f", "md", "--variants", "1", "-j", "2")
    assert result.exit_code == EXIT_OK, result.output
    questions = (out / "questions.md").read_text()
    assert [line.split(".")[0] for line in questions.splitlines() if line.startswith("## Problem")] == [
        f"## Problem {i}" for i in range(1, 11)
    ]
    v = out / "variants" / "v001"
    for spec in sorted((v / "specs").glob("*.yaml")):
        checked = run("check", spec, v / f"key-{spec.stem}.yaml")
        assert checked.exit_code == EXIT_OK, (spec.name, checked.output)


def test_sheet_does_not_import_dask(tmp_path: Path) -> None:
    sheet = tmp_path / "sheet.yaml"
    sheet.write_text(f"title: T\nproblems: [{TUTORIAL / 'p06-two-prismatic.yaml'}]\n")
    code = textwrap.dedent(f"""
        import sys
        from typer.testing import CliRunner
        from tutgen.cli.main import app
        result = CliRunner().invoke(app, ["sheet", {str(sheet)!r}, "-o", {str(tmp_path / "out")!r}, "-n", "2"])
        assert result.exit_code == 0, result.output
        assert not [m for m in sys.modules if m == "dask" or m.startswith(("dask.", "distributed"))]
    """)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr


def test_sheet_on_a_local_dask_cluster(small: tuple[Path, Path], tmp_path: Path) -> None:
    distributed = pytest.importorskip("dask.distributed")
    sheet, out = small
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None
    ) as cluster:
        dask_out = tmp_path / "dask"
        result = run(
            "sheet", sheet, "-o", dask_out, "-f", "md", "-f", "tex", "--variants", "3", "--seed", "5",
            "--scheduler", cluster.scheduler_address,
        )  # fmt: skip
        assert result.exit_code == EXIT_OK, result.output
    assert tree(dask_out) == tree(out)


@pytest.mark.slow  # 17 s; determinism across processes is also tested by the worker-count and solve tests
def test_sheet_does_not_depend_on_the_hash_seed(small: tuple[Path, Path], tmp_path: Path) -> None:
    """Two fresh interpreters with different PYTHONHASHSEED (as on two machines) write the same bytes."""
    sheet, _ = small
    trees = []
    for hashseed in ("1", "2"):
        out = tmp_path / f"out{hashseed}"
        env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONHASHSEED": hashseed}
        args = [sys.executable, "-m", "tutgen", "sheet", str(sheet), "-o", str(out), "-n", "2", "--seed", "9"]
        done = subprocess.run([*args, "-j", hashseed], env=env, capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stderr
        trees.append(tree(out))
    assert trees[0] == trees[1]
