"""How fast `tutgen sheet` builds the ten-problem tutorial with its variants.

Run from the repository root:  python benchmarks/bench_sheet.py [--variants 100] [--workers 1 2]

For each worker count it builds specs/tutorial-1/sheet.yaml with N variants (questions, solutions and
answer keys, as Markdown and LaTeX) into a temporary directory, through the library the CLI calls,
and prints the wall time, how it splits between the symbolic derivations (once per problem) and the
rest (substituting each variant's numbers, views, templates, keys, concrete specs: "rendering", in
worker seconds), the speed-up over one worker, and whether the outputs are byte-identical. It also
times shipping the derivations to a worker (pickling) against deriving them again there.
Target from the issue: 100 variants in under 60 s on a 2-core machine.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import pickle
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # run from a checkout without installing
SHEET = ROOT / "specs" / "tutorial-1" / "sheet.yaml"
TARGET_SECONDS = 60.0


def digest(out: Path) -> str:
    h = hashlib.sha256()
    for path in sorted(out.rglob("*")):
        if path.is_file():
            h.update(str(path.relative_to(out)).encode() + b"\0" + path.read_bytes())
    return h.hexdigest()


def run(variants: int, workers: int, seed: int) -> dict[str, float | str]:
    from tutgen.api import write_outputs
    from tutgen.sheet.build import build_sheet, derive_problems
    from tutgen.sheet.executor import make_executor
    from tutgen.sheet.run import plan_sheet

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "out"
        cpu0 = os.times()
        start = time.perf_counter()
        plan = plan_sheet(SHEET, str(out), formats=["md", "tex"], variants=variants)
        derivations, derive_s = derive_problems(plan.sheet)
        build = build_sheet(
            plan.sheet,
            formats=plan.formats,
            variants=plan.variants,
            seed=seed,
            executor=make_executor(workers),
            derivations=derivations,
        )
        write_outputs([out / n for n, _ in build.files], [c for _, c in build.files])
        wall = time.perf_counter() - start
        cpu1 = os.times()
        cpu = sum(getattr(cpu1, k) - getattr(cpu0, k) for k in ("user", "system", "children_user", "children_system"))
        return {
            "wall": wall,
            "cpu": cpu,
            "derive": derive_s + build.derive_seconds,
            "render": build.render_seconds,
            "files": len(build.files),
            "rederived": len(build.rederived),
            "digest": digest(out),
        }


def ship_or_rederive() -> tuple[float, float, int]:
    """Seconds to pickle + unpickle the ten derivations, and to derive them again; the pickle's size."""
    from tutgen.sheet.build import derive_problems
    from tutgen.sheet.model import load_sheet

    sheet = load_sheet(SHEET)
    derivations, derive_s = derive_problems(sheet)
    start = time.perf_counter()
    blob = pickle.dumps(derivations)
    pickle.loads(blob)
    return time.perf_counter() - start, derive_s, len(blob)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", type=int, default=100)
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--seed", type=int, default=2026)
    args = parser.parse_args()

    print(f"load average before: {os.getloadavg()[0]:.1f} (other work on the machine slows every figure)")
    print(f"tutgen sheet {SHEET.relative_to(ROOT)}: {args.variants} variants, md + tex, on {os.cpu_count()} cores")
    ship, rederive, size = ship_or_rederive()
    print(
        f"  shipping the 10 derivations to a worker (pickle): {ship:.2f} s, {size / 1e6:.1f} MB; "
        f"deriving them again: {rederive:.2f} s"
    )
    results = {}
    for w in args.workers:
        r = run(args.variants, w, args.seed)
        results[w] = r
        print(
            f"  --workers {w}: {r['wall']:6.1f} s wall, {r['cpu']:6.1f} CPU-s  "
            f"(derivation {r['derive']:.1f} s, rendering "
            f"{r['render']:.1f} worker-s; {r['files']} files; {r['rederived']} problem-variants re-derived)"
        )
    if len(results) > 1:
        base = results[args.workers[0]]["wall"]
        for w in args.workers[1:]:
            print(f"  speed-up {args.workers[0]} -> {w} workers: {base / results[w]['wall']:.2f}x")
        same = len({r["digest"] for r in results.values()}) == 1
        print(f"  outputs byte-identical across worker counts: {'yes' if same else 'NO'}")
    best = min(r["wall"] for r in results.values())
    print(f"  best: {best:.1f} s (target < {TARGET_SECONDS:.0f} s): {'ok' if best < TARGET_SECONDS else 'SLOW'}")


if __name__ == "__main__":
    main()
