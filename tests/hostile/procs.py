"""Hostile runs of the real CLI, and the process table: what is still running, what was left behind."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _state(pid: str) -> str:
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            stat = fh.read().decode(errors="replace")
    except OSError:
        return "gone"
    return stat[stat.rindex(")") + 2 :].split()[0]


def processes_in(directory: Path) -> list[tuple[int, str]]:
    """(pid, command line) of every process whose working directory is ``directory`` or below it
    (also once that directory is deleted: the kernel then shows the old path plus " (deleted)").
    Zombies (dead, waiting to be reaped by whoever inherited them) are not running and not counted."""
    root = str(directory.resolve())
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            cwd = os.readlink(f"/proc/{entry}/cwd")
            with open(f"/proc/{entry}/cmdline", "rb") as fh:
                cmd = fh.read().replace(b"\0", b" ").decode(errors="replace").strip()
        except OSError:  # gone meanwhile, or not ours to look at
            continue
        if (cwd == root or cwd.startswith(root + "/")) and _state(entry) not in ("Z", "X", "gone"):
            found.append((int(entry), cmd))
    return found


def settle(probe: object, seconds: float = 3.0) -> list:
    """``probe()`` until it returns an empty list or ``seconds`` pass (a killed process takes a few
    milliseconds to die); its last answer."""
    assert callable(probe)
    ends = time.monotonic() + seconds
    while True:
        left = probe()
        if not left or time.monotonic() > ends:
            return left
        time.sleep(0.05)


def children_of(pid: int) -> list[int]:
    """Every living descendant of ``pid`` (by the parent links in /proc/*/stat)."""
    parents: dict[int, int] = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as fh:
                stat = fh.read().decode(errors="replace")
        except OSError:
            continue
        # the command name is in parentheses and may hold spaces: the fields after the last ')'
        fields = stat[stat.rindex(")") + 2 :].split()
        if fields[0] != "Z":
            parents[int(entry)] = int(fields[1])
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        kids = [c for c, pp in parents.items() if pp == p]
        out += kids
        todo += kids
    return out


def _default_sigint() -> None:
    """Ctrl-C as from a terminal: a test run started in the background of a shell (``pytest &``) hands
    its children SIGINT ignored, and the interrupt tests would then test nothing."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@dataclass
class Outcome:
    """A finished run of the CLI: exit status, output, how long it took."""

    returncode: int
    stdout: str
    stderr: str
    seconds: float


class Runner:
    """Runs ``python -m tutgen`` for a hostile test, in a directory of its own.

    ``work`` is the run's working directory and ``TMPDIR``, so anything it leaves behind (a file, a
    temporary directory, a process still running there, such as a pool worker or latexmk) is seen by
    :meth:`leftovers`; ``inputs`` holds the files it reads.
    """

    def __init__(self, root: Path) -> None:
        self.work = root / "work"
        self.inputs = root / "inputs"
        self.tmp = self.work / "tmp"
        for d in (self.work, self.inputs, self.tmp):
            d.mkdir(parents=True, exist_ok=True)
        self.env = {**os.environ, "PYTHONPATH": str(ROOT), "TMPDIR": str(self.tmp), "NO_COLOR": "1"}

    def start(self, *args: str | Path) -> subprocess.Popen[str]:
        return subprocess.Popen(
            [sys.executable, "-m", "tutgen", *map(str, args)],
            cwd=self.work,
            env=self.env,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            preexec_fn=_default_sigint,
        )

    def run(self, *args: str | Path, limit: float = 90) -> Outcome:
        start = time.monotonic()
        proc = self.start(*args)
        try:
            out, err = proc.communicate(timeout=limit)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
            raise AssertionError(f"tutgen {' '.join(map(str, args))} ran past {limit} s") from None
        return Outcome(proc.returncode, out, err, time.monotonic() - start)

    def finish(self, proc: subprocess.Popen[str], limit: float = 60) -> Outcome:
        start = time.monotonic()
        try:
            out, err = proc.communicate(timeout=limit)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
            raise AssertionError(f"tutgen did not stop within {limit} s") from None
        return Outcome(proc.returncode, out, err, time.monotonic() - start)

    def files(self) -> set[str]:
        """Every path under ``work`` (relative), the output's included."""
        return {str(p.relative_to(self.work)) for p in self.work.rglob("*")} - {"tmp"}

    def leftovers(self, allowed: set[str] = frozenset()) -> tuple[set[str], list[tuple[int, str]]]:  # type: ignore[assignment]
        """(files under ``work`` not in ``allowed`` and not below one of them, processes still
        running there); both empty for a clean run."""
        files = {f for f in self.files() if not any(f == a or f.startswith(a + "/") for a in allowed)}
        return files, settle(lambda: processes_in(self.work))


def wait_for(probe: object, seconds: float) -> bool:
    """Poll ``probe()`` until it is true or ``seconds`` pass; whether it became true."""
    assert callable(probe)
    ends = time.monotonic() + seconds
    while time.monotonic() < ends:
        if probe():
            return True
        time.sleep(0.02)
    return False
