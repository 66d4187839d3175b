"""The ready-made CI of docs/ci/ and the pre-commit hook, run as a course repository would run them:
their commands (all but the install step) in a temporary course repository, with `tutgen` on PATH."""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

from tests.conftest import ROOT, SPECS

ANSWERS = ROOT / "tests" / "check" / "answers"
#: one cheap problem: each step runs `tutgen` in a fresh process, as CI does
PROBLEMS = {"p06-two-prismatic": "p06-printed.yaml"}


@pytest.fixture
def course(tmp_path: Path) -> tuple[Path, dict[str, str]]:
    """A course repository (specs/, submissions/<problem>/<student>.yaml) and an environment whose PATH
    has a `tutgen` that runs this checkout."""
    repo = tmp_path / "course"
    for problem, answers in PROBLEMS.items():
        (repo / "specs").mkdir(parents=True, exist_ok=True)
        shutil.copy(SPECS / "tutorial-1" / f"{problem}.yaml", repo / "specs" / f"{problem}.yaml")
        (repo / "submissions" / problem).mkdir(parents=True)
        shutil.copy(ANSWERS / answers, repo / "submissions" / problem / "alice.yaml")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    shim = bin_dir / "tutgen"
    shim.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m tutgen "$@"\n')
    shim.chmod(shim.stat().st_mode | stat.S_IEXEC)
    env = {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}", "PYTHONPATH": str(ROOT)}
    return repo, env


def github_steps() -> list[str]:
    doc = yaml.safe_load((ROOT / "docs/ci/github-actions.yml").read_text(encoding="utf-8"))
    steps = doc["jobs"]["mark"]["steps"]
    return [s["run"] for s in steps if "run" in s and "pip install" not in s["run"]]


def gitlab_steps() -> list[str]:
    doc = yaml.safe_load((ROOT / "docs/ci/gitlab-ci.yml").read_text(encoding="utf-8"))
    return list(doc["tutgen"]["script"])


def run_steps(steps: list[str], repo: Path, env: dict[str, str]) -> int:
    for step in steps:
        done = subprocess.run(["bash", "-e", "-c", step], cwd=repo, env=env, capture_output=True, text=True)
        if done.returncode != 0:
            return done.returncode
    return 0


def test_the_two_ci_files_run_the_same_commands() -> None:
    """So running one of them in the default run vouches for the other (both run with -m slow)."""
    lines = {
        k: [ln.strip() for step in f() for ln in step.splitlines() if ln.strip()]
        for k, f in (("github", github_steps), ("gitlab", gitlab_steps))
    }
    assert lines["github"] == lines["gitlab"]


@pytest.mark.parametrize(
    "steps", [github_steps, pytest.param(gitlab_steps, marks=pytest.mark.slow)], ids=["github", "gitlab"]
)
def test_the_ci_job_marks_the_submissions_and_writes_junit(steps, course) -> None:
    repo, env = course
    assert steps() and any("tutgen check" in s for s in steps())
    assert run_steps(steps(), repo, env) == 0
    for problem in PROBLEMS:
        suite = ET.parse(repo / "reports" / f"{problem}.xml").getroot()
        assert suite.iter("testcase"), problem
        assert (repo / "reports" / f"{problem}.csv").read_text(encoding="utf-8").count("\n") >= 2


def test_the_ci_job_fails_on_a_wrong_answer(course) -> None:
    repo, env = course
    wrong = repo / "submissions" / "p06-two-prismatic" / "bob.yaml"
    wrong.write_text((ANSWERS / "p06-printed.yaml").read_text(encoding="utf-8").replace("m1", "m2", 1))
    assert run_steps([s for s in github_steps() if "tutgen check" in s], repo, env) == 1


def test_the_pre_commit_hook_passes_good_files_and_stops_a_bad_one(course) -> None:
    repo, env = course
    hook = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text(encoding="utf-8"))[0]
    entry = hook["entry"].split()
    specs = sorted(str(p) for p in (repo / "specs").glob("*.yaml"))
    assert subprocess.run([*entry, *specs], cwd=repo, env=env, capture_output=True).returncode == 0
    bad = repo / "specs" / "bad.yaml"
    bad.write_text("tutgen: 1\ntitle: t\nbodys: {}\n")
    done = subprocess.run([*entry, *specs, str(bad)], cwd=repo, env=env, capture_output=True, text=True)
    assert done.returncode == 3
    assert f"{bad}:3:1: error: unknown key 'bodys'" in done.stderr
