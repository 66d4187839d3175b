"""The figure's cost against a solve (issue 16: the figure must add under 0.5 s to a solve).

Run from the repository root:  python benchmarks/bench_figure.py [SPEC ...]

For each spec (default: every spec under specs/ except the fully symbolic PUMA and Stanford arms, whose
solve takes minutes to print), once, timed with time.perf_counter:
- figure: draw_system + to_svg + to_tikz on the freshly loaded system, timed first (sympy's caches
  cold for this spec's expressions): what the figure adds to a solve (the SVG beside the .md and
  the TikZ in a LaTeX solution);
- free bodies: the free-body diagram of every body (tutgen/figure/freebody.py), all of them together,
  for the planar specs (what the Newton-Euler step's diagrams would add);
- solve: load, derive (Lagrange + Newton-Euler, as `tutgen solve` does) and render the Markdown
  solution (which draws the figure once more, now warm).
Prints one row per spec with both times and figure/solve, then the largest figure time against the
0.5 s target. No repetition loop: one measurement per spec, on a machine that may be loaded.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

HEAVY = {"puma560", "stanford"}
TARGET = 0.5


def main(argv: list[str]) -> int:
    from tutgen.api import render
    from tutgen.engine.pipeline import derive
    from tutgen.figure.build import draw_system
    from tutgen.figure.freebody import free_body_diagram
    from tutgen.figure.svg import to_svg
    from tutgen.figure.tikz import to_tikz
    from tutgen.spec.validate import load_system

    specs = [Path(a) for a in argv] or sorted(
        p for p in (ROOT / "specs").rglob("*.yaml") if "sheet" not in p.stem and p.stem not in HEAVY
    )
    print(f"{'spec':32} {'solve s':>9} {'figure s':>9} {'ratio':>7} {'free bodies s':>14}")
    worst = 0.0
    for spec in specs:
        t0 = time.perf_counter()
        system = load_system(spec)
        loaded = time.perf_counter()
        drawing = draw_system(system)  # first, while sympy's caches are cold for this spec
        to_svg(drawing, system.title)
        to_tikz(drawing)
        figure = time.perf_counter() - loaded
        t_fb = time.perf_counter()
        planar = drawing.view == "planar"
        for body in system.bodies if planar else ():
            free = free_body_diagram(system, body.name)
            to_svg(free, system.title)
            to_tikz(free)
        free_bodies = time.perf_counter() - t_fb
        t1 = time.perf_counter()
        render(derive(system, "both"), "md")
        solve = (loaded - t0) + (time.perf_counter() - t1)
        worst = max(worst, figure, free_bodies)
        fb = f"{free_bodies:14.3f}" if planar else f"{'-':>14}"
        print(f"{spec.stem:32} {solve:9.3f} {figure:9.3f} {figure / solve:7.3f} {fb}")
    verdict = "met" if worst < TARGET else "MISSED"
    print(f"largest figure (or all free bodies) time {worst:.3f} s (target < {TARGET} s): {verdict}")
    return 0 if worst < TARGET else 1


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
