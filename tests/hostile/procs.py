"""The process table, for the hostile runs: which processes are still running in a directory."""

from __future__ import annotations

import os
import time
from pathlib import Path


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
