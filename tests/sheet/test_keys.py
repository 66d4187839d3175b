"""The answer and marking keys' YAML: written by libyaml's emitter where PyYAML has it, which must give the
very text of PyYAML's Python emitter (the fallback), so that a key is byte-identical on every machine."""

from __future__ import annotations

import pytest
import yaml

from tests.conftest import SPECS
from tutgen.sheet.build import ProblemBase, derive_problems, variant_derivation
from tutgen.sheet.model import load_sheet
from tutgen.sheet.render import dump_yaml, results_json

pytestmark = pytest.mark.skipif(not hasattr(yaml, "CSafeDumper"), reason="PyYAML without libyaml: one emitter")


@pytest.fixture(scope="module")
def tutorial_results() -> list[tuple[str, dict]]:
    sheet = load_sheet(SPECS / "tutorial-1" / "sheet.yaml")
    derivations, _ = derive_problems(sheet)
    out = []
    for p, d in zip(sheet.problems, derivations, strict=True):
        base = ProblemBase(p.number, p.key, str(p.path), p.text, d, p.marking)
        out.append((f"{p.key}/nominal", results_json(d)))
        for v in ("v001", "v002"):
            dv, *_ = variant_derivation(base, v, 2026, None)
            out.append((f"{p.key}/{v}", results_json(dv)))
    return out


def test_keys_libyaml_and_python_emitters_write_the_same_text(tutorial_results: list[tuple[str, dict]]) -> None:
    for name, results in tutorial_results:
        python = yaml.dump(
            results, Dumper=yaml.SafeDumper, sort_keys=False, allow_unicode=True, width=100, default_flow_style=None
        )
        assert dump_yaml(results) == python, name


def test_keys_emitters_agree_on_block_style_and_unicode() -> None:
    head = {"spec": "specs/p05-rr-arm.yaml", "student": "Zoë Ångström — group B: ‘θ₁’"}
    python = yaml.dump(head, Dumper=yaml.SafeDumper, sort_keys=False, allow_unicode=True, width=100)
    assert dump_yaml(head, flow=False) == python
    long = {"equation": " + ".join(f"m{i}*l{i}**2*theta{i}_ddot" for i in range(30)), "rows": [[1, 2.5], [-3, 0]]}
    python = yaml.dump(
        long, Dumper=yaml.SafeDumper, sort_keys=False, allow_unicode=True, width=100, default_flow_style=None
    )
    assert dump_yaml(long) == python
