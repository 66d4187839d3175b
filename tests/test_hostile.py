"""Hostile input through the real command line: nothing runs, nothing hangs, no traceback.

Every file of ``tests/hostile/`` (code-execution payloads in each expression field, YAML tags, an alias
bomb, deep nesting, huge numbers, LaTeX and template injection, bad bytes), plus a 1.1 MB file made
here, is copied into a temporary directory with ``@SENTINEL@`` replaced by a path there that a payload
would create. Each runs as ``python -m tutgen solve FILE --format json`` in its own process (in
parallel, to keep the run short).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import uuid
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from tests.conftest import ROOT
from tutgen.errors import EXIT_CANNOT_DERIVE, EXIT_INVALID_SPEC, EXIT_OK
from tutgen.spec.loader import MAX_FILE_BYTES

HOSTILE = ROOT / "tests" / "hostile"
CORPUS = sorted(HOSTILE.glob("*.yaml"))
NAMES = [p.name for p in CORPUS] + ["oversized-1.1MB.yaml"]
TIMEOUT = 60
#: What a line on stderr may be: a located error, or the hint under one.
ERROR_LINE = re.compile(r"^(?P<path>.+?)(:\d+(:\d+)?)?: error: \S")
HINT_LINE = re.compile(r"^  \S")


def _oversized(sentinel: str) -> bytes:
    """A valid-looking spec padded past the 1 MiB limit with a long comment."""
    payload = f"__import__('os').system('touch {sentinel}')"
    head = f'tutgen: 1\ntitle: big\nparameters: [m]\nbodies:\n  b: {{mass: "{payload}"}}\n'
    pad = "# " + "x" * 1000 + "\n"
    return (head + pad * (int(1.1 * MAX_FILE_BYTES) // len(pad) + 1)).encode()


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory: pytest.TempPathFactory) -> dict[str, tuple[Path, Path, subprocess.CompletedProcess]]:
    """(spec, sentinel, finished process) per corpus file, all run once, in parallel."""
    work = tmp_path_factory.mktemp("hostile")
    jobs: dict[str, tuple[Path, Path]] = {}
    for name in NAMES:
        sentinel = work / f"tutgen-pwned-{uuid.uuid4().hex}"
        data = _oversized(str(sentinel)) if name.startswith("oversized") else (HOSTILE / name).read_bytes()
        spec = work / name
        spec.write_bytes(data.replace(b"@SENTINEL@", str(sentinel).encode()))
        jobs[name] = (spec, sentinel)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}

    def run(name: str) -> subprocess.CompletedProcess:
        spec, _ = jobs[name]
        return subprocess.run(
            [sys.executable, "-m", "tutgen", "solve", str(spec), "--format", "json"],
            cwd=work,
            env=env,
            capture_output=True,
            timeout=TIMEOUT,
            check=False,
        )

    with ThreadPoolExecutor(max_workers=min(8, os.cpu_count() or 2)) as pool:
        done = dict(zip(NAMES, pool.map(run, NAMES), strict=True))
    return {name: (*jobs[name], done[name]) for name in NAMES}


def test_hostile_corpus_covers_every_expression_field() -> None:
    fields = {p.stem.removeprefix("payload-") for p in CORPUS if p.stem.startswith("payload-")}
    assert fields >= {
        "parameter-value", "mass", "com", "part-size", "position", "orientation-angle", "joint-origin",
        "joint-offset", "spring-stiffness", "spring-extension", "damper-coefficient", "load-force",
        "load-torque", "generalized-force", "energy-kinetic", "energy-potential",
    }  # fmt: skip
    for path in CORPUS:
        if path.stem.startswith("payload-"):
            assert b"@SENTINEL@" in path.read_bytes(), path.name


@pytest.mark.parametrize("name", NAMES)
def test_hostile_input_is_refused_or_solved_safely(name: str, outcomes: dict) -> None:
    spec, sentinel, proc = outcomes[name]
    stderr = proc.stderr.decode("utf-8", errors="replace")
    assert proc.returncode in {EXIT_OK, EXIT_INVALID_SPEC, EXIT_CANNOT_DERIVE}, stderr
    assert "Traceback" not in stderr
    assert not sentinel.exists(), f"{name}: a payload ran"
    if proc.returncode == EXIT_OK:
        assert not stderr.strip()
        return
    lines = stderr.splitlines()
    assert lines, "an error exit must say why"
    for line in lines:
        match = ERROR_LINE.match(line)
        assert match or HINT_LINE.match(line), f"{name}: unexpected stderr line {line!r}"
        if match:
            assert match["path"] == str(spec)
    if name.startswith("payload-"):
        assert proc.returncode == EXIT_INVALID_SPEC
        assert re.match(rf"^{re.escape(str(spec))}:\d+:\d+: error: ", lines[0])
