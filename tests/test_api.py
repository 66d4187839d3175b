"""The public Python API (`from tutgen import load, loads, derive, render, check`): its docstring
examples run, its names resolve, and importing it stays light."""

from __future__ import annotations

import doctest
import json
import subprocess
import sys
from pathlib import Path

import pytest

import tutgen
from tests.conftest import ROOT, SPECS


@pytest.mark.parametrize("module", ["tutgen", "tutgen.engine.pipeline"])
def test_the_documented_examples_run(module: str) -> None:
    import importlib

    result = doctest.testmod(importlib.import_module(module), optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0


def test_every_public_name_resolves_and_unknown_ones_do_not() -> None:
    assert set(tutgen.__all__) == {"__version__", "check", "derive", "load", "loads", "render"}
    for name in tutgen.__all__:
        assert getattr(tutgen, name) is not None
    with pytest.raises(AttributeError):
        tutgen.derivee  # noqa: B018


def test_import_tutgen_does_not_import_sympy() -> None:
    code = "import sys, tutgen; print(tutgen.__version__); print('sympy' in sys.modules)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True)
    assert done.stdout.split() == [tutgen.__version__, "False"]


def test_large_serial_arm_does_not_import_newton_euler() -> None:
    """The route of a large serial arm runs no Newton-Euler derivation (its check is the numeric
    inverse dynamics), so its modules stay out of the command's start-up (issue 17)."""
    code = (
        "import sys, tutgen; d = tutgen.derive(tutgen.load('specs/arms/scara.yaml')); tutgen.render(d);"
        "print(sorted(m for m in sys.modules if 'newton_euler' in m or 'constrained_ne' in m))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True)
    assert done.stdout.split() == ["[]"]


def test_load_derive_render_is_the_command_lines_pipeline() -> None:
    spec = SPECS / "tutorial-1/p06-two-prismatic.yaml"
    d = tutgen.derive(tutgen.load(spec))
    doc = json.loads(tutgen.render(d, "json"))
    assert doc["format"] == 1 and doc["coordinates"] == ["q1", "q2"]
    assert tutgen.render(d).startswith("# ")  # Markdown by default


def test_check_marks_answers_as_the_command_does() -> None:
    run = tutgen.check(SPECS / "tutorial-1/p03-cart-pendulum.yaml", [ROOT / "tests/check/answers/p03-printed.yaml"])
    assert run.exit_code == 0
    assert run.files and all(item.status.value == "correct" for item in run.files[0].items)


def test_bad_spec_text_is_a_located_error() -> None:
    from tutgen.errors import SpecErrors

    with pytest.raises(SpecErrors) as caught:
        tutgen.loads("tutgen: 1\ntitle: t\nbodys: {}\n", "bad.yaml")
    assert str(caught.value.errors[0]).startswith("bad.yaml:3:1")


def test_many_output_paths_are_checked_with_one_limit_per_directory(tmp_path: Path) -> None:
    """A sheet's thousands of paths share each directory's NAME_MAX (``limits``); a name too long is
    refused all the same, first in its directory or not."""
    from tutgen.api import check_output_path
    from tutgen.errors import UsageError

    limits: dict[Path, int] = {}
    for name in ("a.md", "b.md", "c.md"):
        check_output_path(tmp_path / "out" / name, limits=limits)
    assert set(limits) == {tmp_path / "out"}
    with pytest.raises(UsageError, match="bytes long; the file system allows"):
        check_output_path(tmp_path / "out" / ("n" * 300 + ".md"), limits=limits)
    with pytest.raises(UsageError, match="bytes long; the file system allows"):
        check_output_path(tmp_path / ("d" * 300) / "a.md", limits=limits)
