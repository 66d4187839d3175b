"""What `pip install .` carries: every package of the source tree and the templates (issue 20's
packaging metadata; a package missing from pyproject.toml's list installs a tutgen that cannot import)."""

from __future__ import annotations

import tomllib
from typing import Any

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

    def folder(package: str) -> Any:
        # as setuptools maps it: the longest package-dir prefix, then the rest of the name as folders
        base = max((k for k in dirs if package == k or package.startswith(k + ".")), key=len)
        return dirs[base].joinpath(*package[len(base) :].split(".")[1:])

    for package, patterns in config["package-data"].items():
        assert package in config["packages"], f"{package}: package data of a package that is not listed"
        for pattern in patterns:
            assert list(folder(package).glob(pattern)), f"{package}: {pattern} matches no file"


def test_every_template_folder_is_a_listed_package() -> None:
    """setuptools warns that a folder of templates not in the packages list "would be ignored" (a
    namespace package it may stop installing): each one is listed, so the templates keep coming along."""
    listed = set(_pyproject()["tool"]["setuptools"]["packages"])
    folders = {
        ".".join(("tutgen", "templates", *d.relative_to(ROOT / "templates").parts))
        for d in (ROOT / "templates").rglob("*")
        if d.is_dir() and "__pycache__" not in d.parts and any(d.glob("*.j2"))
    }
    assert folders and folders - listed == set(), "add these to [tool.setuptools] packages in pyproject.toml"


#: the import names of the runtime dependencies in pyproject.toml (pyyaml is ``yaml``; pydantic brings
#: ``pydantic_core``, sympy ``mpmath``, typer its own click), beside the standard library and tutgen itself
_RUNTIME_IMPORTS = {
    "sympy",
    "mpmath",
    "yaml",
    "jinja2",
    "typer",
    "numpy",
    "pydantic",
    "pydantic_core",
    "rich",
    "tutgen",
}


def _module_level_imports(tree: Any) -> set[str]:
    """The top-level names imported when the module is imported: its body's imports, and those of ``try``
    and ``if`` blocks at module level, but not ``if TYPE_CHECKING:`` (annotations only) nor any inside a
    function (the lazy imports of optional extras)."""
    import ast

    names: set[str] = set()

    def visit(statements: list[ast.stmt]) -> None:
        for node in statements:
            if isinstance(node, ast.Import):
                names.update(alias.name.split(".")[0] for alias in node.names)
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module.split(".")[0])
            elif isinstance(node, ast.If):
                if "TYPE_CHECKING" not in ast.unparse(node.test):
                    visit(node.body)
                visit(node.orelse)
            elif isinstance(node, ast.Try):
                visit(node.body)

    visit(tree.body)
    return names


def test_the_package_imports_only_its_declared_dependencies() -> None:
    """`pip install .` alone must run every command: a module-level import of something only the test
    extras bring (click, once, through typer's older releases) breaks the README's first command."""
    import ast
    import sys

    undeclared = {}
    for path in sorted((ROOT / "tutgen").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        extra = {
            n for n in _module_level_imports(tree) if n not in _RUNTIME_IMPORTS and n not in sys.stdlib_module_names
        }
        if extra:
            undeclared[str(path.relative_to(ROOT))] = sorted(extra)
    assert undeclared == {}


def test_the_command_line_starts_without_the_heavy_modules() -> None:
    """`tutgen --help` and `tutgen --version` (issue 17: start-up <= 0.2 s) import neither sympy, numpy,
    pydantic, jinja2 nor yaml: each command imports what it needs inside its function. A fresh
    interpreter, so that nothing the tests imported counts."""
    import subprocess
    import sys

    heavy = ("sympy", "numpy", "pydantic", "jinja2", "yaml")
    code = (
        "import sys\n"
        "import tutgen.cli.main as m\n"
        "for argv in (['--help'], ['--version']):\n"
        "    try:\n"
        "        m.app(argv, prog_name='tutgen')\n"
        "    except SystemExit:\n"
        "        pass\n"
        f"print('heavy:' + ','.join(n for n in {heavy!r} if n in sys.modules))\n"
    )
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True)
    assert "Usage" in done.stdout and "tutgen " in done.stdout
    assert done.stdout.splitlines()[-1] == "heavy:"
