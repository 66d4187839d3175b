"""tutgen.engine.fastkb: sympy's assumption tables copied as dictionaries give the tables sympy's own copy
gives, and the worked solutions do not change with it."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import sympy as sp
from sympy.core.assumptions import StdFactKB

import tutgen.engine  # noqa: F401  (installs it)
from tutgen.engine import fastkb

ROOT = Path(__file__).resolve().parents[2]


def _subclasses(cls: type) -> list[type]:
    out, todo = [], [cls]
    while todo:
        c = todo.pop()
        for s in c.__subclasses__():
            if s not in out:
                out.append(s)
                todo.append(s)
    return out


def _tables() -> list[Any]:
    """The default table of every sympy class loaded, and the tables of symbols with each assumption."""
    tables = [
        c.default_assumptions
        for c in _subclasses(sp.Basic)
        if isinstance(c.__dict__.get("default_assumptions"), StdFactKB)
    ]
    for fact in ("positive", "real", "integer", "nonnegative", "negative", "zero", "commutative"):
        for value in (True, False):
            tables.append(sp.Symbol("s", **{fact: value})._assumptions)
    return tables


def test_installed_with_tutgen_engine() -> None:
    assert fastkb.install() is True
    assert StdFactKB.copy is fastkb._dict_copy


def test_copies_equal_sympys_own_on_every_class() -> None:
    tables = _tables()
    assert len(tables) > 100  # sympy's classes, not an empty walk
    original = fastkb._ORIGINAL
    assert original is not None
    for kb in tables:
        mine, theirs = fastkb._dict_copy(kb), original(kb)
        assert type(mine) is type(theirs)
        assert dict(mine) == dict(theirs), kb
        assert mine.generator == theirs.generator
        assert mine is not kb and mine._generator is not kb._generator  # a copy, not the class's table


def test_a_copy_learns_without_touching_the_class_table() -> None:
    f = sp.Float("2.5")
    before = dict(sp.Float.default_assumptions)
    assert f.is_positive is True and f.is_zero is False
    assert dict(sp.Float.default_assumptions) == before
    assert f._assumptions is not sp.Float.default_assumptions


def test_uninstall_puts_sympys_back() -> None:
    fastkb.uninstall()
    try:
        assert StdFactKB.copy is not fastkb._dict_copy
        assert sp.Float("1.25").is_negative is False
    finally:
        assert fastkb.install() is True


def _solve(env: dict[str, str]) -> bytes:
    spec = ROOT / "specs" / "tutorial-1" / "p05-rr-arm.yaml"
    run = subprocess.run(
        [sys.executable, "-m", "tutgen", "solve", str(spec), "-f", "json"],
        capture_output=True,
        env=env,
        cwd=ROOT,
        timeout=300,
        check=True,
    )
    return run.stdout


def test_the_same_solution_with_sympys_copy() -> None:
    """TUTGEN_SYMPY_KB=sympy leaves sympy as it is, and the JSON (every result written out) is the same."""
    env = {k: v for k, v in os.environ.items() if k != "TUTGEN_SYMPY_KB"}
    probe = "import tutgen.engine; from sympy.core.assumptions import StdFactKB; print(StdFactKB.copy.__module__)"
    kept = subprocess.run(
        [sys.executable, "-c", probe],
        capture_output=True,
        text=True,
        env={**env, "TUTGEN_SYMPY_KB": "sympy"},
        check=True,
    )
    assert kept.stdout.strip() == "sympy.core.assumptions"
    used = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, env=env, check=True)
    assert used.stdout.strip() == "tutgen.engine.fastkb"
    assert _solve(env) == _solve({**env, "TUTGEN_SYMPY_KB": "sympy"})
