"""What `pip install .` carries: every package of the source tree and the templates (issue 20's
packaging metadata; a package missing from pyproject.toml's list installs a tutgen that cannot import)."""

from __future__ import annotations

import tomllib

from tests.conftest import ROOT


def _pyproject() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def test_every_package_of_the_tree_is_installed() -> None:
    listed = set(_pyproject()["tool"]["setuptools"]["packages"])
    tree = {
        ".".join(init.parent.relative_to(ROOT).parts)
        for init in (ROOT / "tutgen").rglob("__init__.py")
        if "__pycache__" not in init.parts
    }
    assert tree - listed == set(), "add these to [tool.setuptools] packages in pyproject.toml"
    assert "tutgen.templates" in listed


def test_every_package_data_pattern_matches_a_file() -> None:
    config = _pyproject()["tool"]["setuptools"]
    dirs = {"tutgen": ROOT / "tutgen", **{k: ROOT / v for k, v in config["package-dir"].items()}}
    for package, patterns in config["package-data"].items():
        for pattern in patterns:
            assert list(dirs[package].glob(pattern)), f"{package}: {pattern} matches no file"
