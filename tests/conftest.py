"""Shared fixtures: derivations are expensive (sympy), so each spec is derived once per session."""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from functools import cache
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, settings

ROOT = Path(__file__).resolve().parent.parent
SPECS = ROOT / "specs"
SEED = Path(os.environ.get("TUTGEN_SEED_DIR", ROOT.parent / "shared" / "seed"))

settings.register_profile("default", max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("long", max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))
#: for property tests whose every example derives a system and a reference (Kane) from scratch: a third
#: of the profile's examples (4 in the default run, 66 with HYPOTHESIS_PROFILE=long)
few_examples = settings(max_examples=max(4, settings.default.max_examples // 3))


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--update-golden",
        action="store_true",
        default=False,
        help="rewrite tests/golden/ from the current output instead of comparing (review the diff)",
    )


#: fully symbolic spatial arms: seconds to derive but minutes to print (7 MB of Markdown for the symbolic
#: PUMA), so every per-spec test of theirs runs only with ``-m slow``; tests/engine/test_recursive.py and
#: test_serial.py check their dynamics in the default run without printing them
HEAVY_SPECS = frozenset({"puma560", "stanford", "n-four-bar-crank-rocker"})  # the four-bar: ~18 s to derive
#: the specs whose PDF the default run compiles through ``latexmk`` (the product's route, sandbox and
#: all): a composite body with its figure, a jointed chain with loads, a Lagrange-only arm, a DH arm, a
#: spatial example. Every spec's LaTeX is compiled by pdflatex in tests/render/test_typeset.py anyway;
#: ``-m slow`` compiles the rest through latexmk too.
PDF_SAMPLE = frozenset({"p01-composite-inertia", "p03-cart-pendulum", "p05-rr-arm", "scara", "c-rotor-tilting-plate"})


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark the per-spec tests of HEAVY_SPECS slow, and leave slow tests out of the default run
    (``pytest -m slow`` runs them, ``-m "slow or not slow"`` everything)."""
    for item in items:
        params = getattr(getattr(item, "callspec", None), "params", {})
        if any(isinstance(v, (str, Path)) and Path(str(v)).stem in HEAVY_SPECS for v in params.values()):
            item.add_marker(pytest.mark.slow)
    if config.option.markexpr:
        return
    skip = pytest.mark.skip(reason="slow: run with pytest -m slow")
    for item in items:
        if item.get_closest_marker("slow"):
            item.add_marker(skip)


def all_specs() -> list[Path]:
    """Every problem spec under specs/ (tutorial sheets, ``*sheet*.yaml``, are not problem specs)."""
    return sorted(p for p in SPECS.rglob("*.yaml") if "sheet" not in p.stem)


class LazyDocument(Mapping[str, Any]):
    """A derivation's JSON document, built on first use: most callers of :func:`solved` read only the
    derivation, and the numeric PUMA's document takes six times as long as its derivation."""

    def __init__(self, derivation: Any) -> None:
        self._derivation = derivation
        self._doc: dict[str, Any] | None = None

    @property
    def doc(self) -> dict[str, Any]:
        if self._doc is None:
            from tutgen.render.jsonout import derivation_to_json

            self._doc = derivation_to_json(self._derivation)
        return self._doc

    def __getitem__(self, key: str) -> Any:
        return self.doc[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self.doc)

    def __len__(self) -> int:
        return len(self.doc)


@cache
def solved(path: str) -> tuple[Any, Any, LazyDocument]:
    """(system, derivation, json document) for a spec path, derived once per session (the document
    built when first read; ``dict(doc)`` or ``doc.doc`` for the plain dict)."""
    from tutgen.engine.pipeline import derive
    from tutgen.spec.validate import load_system

    system = load_system(path)
    derivation = derive(system)
    return system, derivation, LazyDocument(derivation)


@cache
def rendered(path: str, fmt: str) -> str | bytes:
    """A spec's worked solution as ``fmt`` ("md", "tex" or "pdf", through ``tutgen.api.render``), rendered
    once per session: the golden, typesetting, safety and wording tests all read the same text (a test of
    the rendering itself, e.g. that two runs agree, calls ``render`` directly)."""
    from tutgen.api import render

    return render(solved(path)[1], fmt)


def rendered_text(path: str | Path, fmt: str) -> str:
    out = rendered(str(path), fmt)
    assert isinstance(out, str)
    return out


@pytest.fixture
def solve_spec():
    return lambda path: solved(str(path))
