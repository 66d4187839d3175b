"""Jinja environments: strict, brace-safe for LaTeX, and a user's --template-dir first and sandboxed."""

from __future__ import annotations

from pathlib import Path

import jinja2
import jinja2.sandbox
import pytest

from tests.conftest import SPECS, solved

P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"


def test_latex_env_uses_brace_safe_delimiters() -> None:
    from tutgen.render.env import latex_env

    env = latex_env()
    out = env.from_string(r"\textbf{((( x | latex_escape )))}((* if y *)){y}((* endif *))((# no #))").render(
        x="a_b", y=True
    )
    assert out == r"\textbf{a\_b}{y}"


def test_envs_are_strict() -> None:
    from tutgen.render.env import latex_env, markdown_env

    for env in (markdown_env(), latex_env()):
        assert env.undefined is jinja2.StrictUndefined
        assert not isinstance(env, jinja2.sandbox.SandboxedEnvironment)
    with pytest.raises(jinja2.UndefinedError):
        markdown_env().from_string("{{ missing }}").render()


def test_template_dir_overrides_a_block_and_is_sandboxed(tmp_path: Path) -> None:
    from tutgen.render.env import markdown_env
    from tutgen.render.markdown import render_markdown

    (tmp_path / "blocks").mkdir()
    (tmp_path / "blocks" / "boxed.md.j2").write_text("> **Answer.** ${{ block.tex }}$\n", encoding="utf-8")
    assert isinstance(markdown_env(tmp_path), jinja2.sandbox.SandboxedEnvironment)
    text = render_markdown(solved(str(P05))[1], tmp_path)
    assert "> **Answer.** $" in text
    assert "\\boxed" not in text


def test_sandbox_refuses_unsafe_attribute_access(tmp_path: Path) -> None:
    from tutgen.render.markdown import render_markdown

    (tmp_path / "solution.md.j2").write_text("{{ title.__class__.__mro__[1].__subclasses__() }}\n", encoding="utf-8")
    with pytest.raises(jinja2.exceptions.SecurityError):
        render_markdown(solved(str(P05))[1], tmp_path)
