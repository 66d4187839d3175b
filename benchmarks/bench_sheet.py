"""How fast `tutgen sheet` builds the ten-problem tutorial with its variants.

Run from the repository root:
    python benchmarks/bench_sheet.py [--variants 100] [--workers 1 2] [--baseline REV] [--repeat N]

Each measurement is the command a user types, in a fresh process (`python -m tutgen sheet
specs/tutorial-1/sheet.yaml -o OUT -n N -f md -f tex --workers W`): its wall time and its CPU time
(user + system of the command and of its workers, which the load of a shared machine distorts much
less than the wall time), how the command splits its time (the symbolic derivations, once per problem,
and the rest: substituting each variant's numbers, views, keys, templates, in worker seconds), the
speed-up from the first worker count to the others, and whether the outputs are byte-identical. With
``--baseline REV`` the same commands run by the tutgen of git revision REV (extracted with ``git
archive``), in the same run, so that before/after ratios are taken minutes apart on the same machine.
With ``--repeat N`` every command runs N times, the trees and worker counts taking turns (so that a
slow minute of a shared machine falls on all of them), and the figures are the medians. Nothing is
asserted; every ratio is printed. Targets (issue 17): 100 variants in at most 15 s with 2
workers, a speed-up of at least 1.8x from 1 to 2 workers.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import re
import resource
import subprocess
import sys
import tarfile
import tempfile
import time
from io import BytesIO
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))
from installed import installed_env  # noqa: E402  (a sibling module)

SHEET = Path("specs") / "tutorial-1" / "sheet.yaml"
TARGET_SECONDS = 15.0
TARGET_SPEEDUP = 1.8
#: the command's own report: "wrote N files to OUT, 100 variants (derivation 1.5 s, rendering 30.2 s …"
REPORT = re.compile(r"wrote (\d+) files.*\(derivation ([\d.]+) s, rendering ([\d.]+) s")


def digest(out: Path) -> str:
    h = hashlib.sha256()
    for path in sorted(out.rglob("*")):
        if path.is_file():
            h.update(str(path.relative_to(out)).encode() + b"\0" + path.read_bytes())
    return h.hexdigest()


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(
    tree: Path, label: str, variants: int, workers: int, seed: int, tmp: Path, turn: int = 0
) -> dict[str, float | str]:
    """One fresh `tutgen sheet` by the tutgen of ``tree``; its times, its report and its output's digest.

    The output is left where it is until the benchmark ends: ext4 does not give a new file an inode freed
    in the last 30 seconds (``recently_deleted``, checked inode by inode), so a run started within 30 s
    of deleting the previous run's 4 617 files spent 1-3 s of system time finding inodes for its own
    (seen with ``perf``: 60-80 % of the samples of creating 4 600 files) - a cost of the benchmark's
    cleanup, not of the command."""
    out = tmp / f"out-{label}-{workers}-{turn}"
    cmd = [sys.executable, "-m", "tutgen", "sheet", str(tree / SHEET), "-o", str(out), "-n", str(variants)]
    cmd += ["-f", "md", "-f", "tex", "--workers", str(workers), "--seed", str(seed), "--no-progress", "--timeout", "0"]
    env = installed_env(tree)
    cpu = _children_cpu()
    start = time.perf_counter()
    done = subprocess.run(cmd, cwd=tree, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"failed ({done.returncode}): {' '.join(cmd)}\n{done.stderr[-2000:]}")
    report = REPORT.search(done.stderr)
    files, derive, render = (int(report[1]), float(report[2]), float(report[3])) if report else (0, 0.0, 0.0)
    result: dict[str, float | str] = {
        "wall": wall,
        "cpu": _children_cpu() - cpu,
        "derive": derive,
        "render": render,
        "files": files,
        "digest": digest(out),
    }
    return result


def summary(runs: list[dict[str, float | str]]) -> dict[str, float | str]:
    """The medians of ``runs`` of one command (wall, CPU), their wall range, and the digest of the output
    (every run must give the same; otherwise it is given as "differs")."""
    import statistics

    walls = [float(r["wall"]) for r in runs]
    digests = {r["digest"] for r in runs}
    return {
        **runs[0],
        "wall": statistics.median(walls),
        "cpu": statistics.median(float(r["cpu"]) for r in runs),
        "wall_min": min(walls),
        "wall_max": max(walls),
        "digest": digests.pop() if len(digests) == 1 else "differs",
    }


def extract(rev: str, into: Path) -> Path:
    """The tree of git revision ``rev`` of this repository, in ``into``."""
    blob = subprocess.run(["git", "archive", rev], cwd=ROOT, check=True, capture_output=True).stdout
    with tarfile.open(fileobj=BytesIO(blob)) as tar:
        tar.extractall(into, filter="data")
    return into


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", type=int, default=100)
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--baseline", help="git revision to measure the same commands with (before/after)")
    parser.add_argument("--repeat", type=int, default=1, help="runs of each command, taking turns; medians")
    args = parser.parse_args()

    print(f"load average before: {os.getloadavg()[0]:.1f} (other work on the machine slows every figure)")
    print(f"tutgen sheet {SHEET}: {args.variants} variants, md + tex, on {os.cpu_count()} cores, fresh processes")
    print("modules byte-compiled first, as `pip install` leaves them (benchmarks/installed.py)")
    with tempfile.TemporaryDirectory() as tmpdir:
        tmp = Path(tmpdir)
        trees = {"now": ROOT}
        if args.baseline:
            trees["before"] = extract(args.baseline, tmp / "baseline")
        runs: dict[tuple[str, int], list[dict[str, float | str]]] = {}
        for turn in range(args.repeat):
            for label, tree in trees.items():
                for w in args.workers:
                    r = run(tree, label, args.variants, w, args.seed, tmp, turn)
                    runs.setdefault((label, w), []).append(r)
                    print(
                        f"  {label:6s} --workers {w}: {r['wall']:6.1f} s wall, {r['cpu']:6.1f} CPU-s  "
                        f"(derivation {r['derive']:.1f} s, rendering {r['render']:.1f} worker-s; {r['files']} files)"
                        + (f"  [run {turn + 1} of {args.repeat}]" if args.repeat > 1 else ""),
                        flush=True,
                    )
        results = {key: summary(rs) for key, rs in runs.items()}
        if args.repeat > 1:
            print(f"medians of {args.repeat} runs (wall min-max in brackets):")
            for (label, w), r in results.items():
                print(
                    f"  {label:6s} --workers {w}: {r['wall']:6.1f} s wall [{r['wall_min']:.1f}-{r['wall_max']:.1f}], "
                    f"{r['cpu']:6.1f} CPU-s"
                )
        first = args.workers[0]
        for label in trees:
            for w in args.workers[1:]:
                base, other = results[label, first], results[label, w]
                print(
                    f"  {label}: speed-up {first} -> {w} workers: {float(base['wall']) / float(other['wall']):.2f}x "
                    f"wall (target >= {TARGET_SPEEDUP}x); CPU-s {float(other['cpu']) / float(base['cpu']):.2f}x"
                )
            same = len({results[label, w]["digest"] for w in args.workers}) == 1
            print(f"  {label}: outputs byte-identical across worker counts: {'yes' if same else 'NO'}")
        if "before" in trees:
            for w in args.workers:
                before, now = results["before", w], results["now", w]
                print(
                    f"  before / now, --workers {w}: {float(before['wall']) / float(now['wall']):.2f}x wall, "
                    f"{float(before['cpu']) / float(now['cpu']):.2f}x CPU-s; outputs byte-identical: "
                    f"{'yes' if before['digest'] == now['digest'] else 'NO'}"
                )
        best = min(float(results["now", w]["wall"]) for w in args.workers)
        print(
            f"  now, best: {best:.1f} s wall (target <= {TARGET_SECONDS:.0f} s): "
            f"{'ok' if best <= TARGET_SECONDS else 'SLOW'}"
        )


if __name__ == "__main__":
    main()
