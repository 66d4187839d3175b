"""The figure's cost in a solve (issue 16: the figure must add under 0.5 s to a solve).

Run from the repository root:  python benchmarks/bench_figure.py [SPEC ...]

Times are CPU seconds of this process (time.process_time), not wall-clock: the machine is shared,
and CPU time is what the figure itself costs. One measurement per spec, no repetition loop.

For each spec (default: the tutorial's p01-p09 and the symbolic Stanford arm):
- figure in a solve: every call a solve makes into the figure package, timed where it is made, while
  the solve runs as `tutgen solve` does it: load, derive (Lagrange + Newton-Euler), render the
  Markdown solution, the JSON and the LaTeX, and the files beside the Markdown (the schematic's SVG,
  each free body's SVG). The draw_system and free_body_diagram calls (which hold the drawing's
  whole cost: the pose, the projection, the labels) and the SVG and TikZ writers are wrapped;
  nested calls are counted once. The calls column says how many were made and, of the drawings
  asked for, how many were drawn (the rest came from the per-process cache).
- solve: the whole of that run, the figure included.
The fully symbolic Stanford arm's solve takes minutes to print (it is measured in bench_arms.py); for
it (and for any spec given with --figure-only), the solve is replaced by the figure calls a
Markdown + JSON + LaTeX solve makes (figure_view, figure_json, svg_file, free_body_views), on the
freshly loaded system.
Prints one row per spec, then the largest figure time against the 0.5 s target.
"""

from __future__ import annotations

import functools
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

TARGET = 0.5
FIGURE_ONLY = {"stanford", "puma560"}
DEFAULT = [
    *sorted((ROOT / "specs" / "tutorial-1").glob("p0[1-9]-*.yaml")),
    ROOT / "specs" / "arms" / "stanford.yaml",
]


class Meter:
    """CPU time spent inside the wrapped figure functions (outermost calls only)."""

    def __init__(self) -> None:
        self.seconds = 0.0
        self.calls = 0
        self.drawn = 0
        self._depth = 0

    def wrap(self, fn: Callable[..., Any]) -> Callable[..., Any]:
        @functools.wraps(fn)
        def timed(*args: Any, **kwargs: Any) -> Any:
            self.calls += 1
            if self._depth:
                return fn(*args, **kwargs)
            self._depth += 1
            t0 = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                self.seconds += time.process_time() - t0
                self._depth -= 1

        return timed

    def count_drawn(self, fn: Callable[..., Any]) -> Callable[..., Any]:
        @functools.wraps(fn)
        def counted(*args: Any, **kwargs: Any) -> Any:
            self.drawn += 1
            return fn(*args, **kwargs)

        return counted


def instrument(meter: Meter) -> None:
    """Wrap the figure's entry points wherever they were imported (module attributes)."""
    import tutgen.figure.build as build
    import tutgen.figure.freebody as freebody
    import tutgen.figure.svg as svg
    import tutgen.figure.tikz as tikz
    import tutgen.figure.view as view

    draw = meter.wrap(build.draw_system)
    fbd = meter.wrap(freebody.free_body_diagram)
    to_svg, to_tikz = meter.wrap(svg.to_svg), meter.wrap(tikz.to_tikz)
    build.draw_system = view.draw_system = draw  # type: ignore[assignment]
    freebody.free_body_diagram = fbd  # type: ignore[assignment]
    svg.to_svg, tikz.to_tikz = to_svg, to_tikz  # type: ignore[assignment]
    # what is really drawn (not answered from the cache)
    build._draw_system = meter.count_drawn(build._draw_system)  # type: ignore[attr-defined]
    freebody._FreeBodyBuilder.build = meter.count_drawn(freebody._FreeBodyBuilder.build)  # type: ignore[method-assign]


def solve(spec: Path, tmp: Path) -> None:
    from tutgen.api import figure_files, render
    from tutgen.engine.pipeline import derive
    from tutgen.spec.validate import load_system

    d = derive(load_system(spec), "both")
    for fmt in ("md", "json", "tex"):
        render(d, fmt)
    figure_files([spec], [tmp / f"{spec.stem}.md"], force=True, derivations=[d])


def figure_calls(spec: Path) -> None:
    from tutgen.figure.view import figure_json, figure_view, free_body_views, svg_file
    from tutgen.spec.validate import load_system

    system = load_system(spec)
    figure_view(system)
    figure_json(system)
    svg_file(system)
    free_body_views(system)


def main(argv: list[str]) -> int:
    import tempfile

    only = "--figure-only" in argv
    specs = [Path(a) for a in argv if a != "--figure-only"] or DEFAULT
    meter = Meter()
    instrument(meter)
    print(f"{'spec':28} {'solve cpu s':>12} {'figure cpu s':>13} {'share':>6} {'calls (drawn)':>14}")
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for spec in specs:
            meter.seconds, meter.calls, meter.drawn = 0.0, 0, 0
            t0 = time.process_time()
            figure_only = only or spec.stem in FIGURE_ONLY
            if figure_only:
                figure_calls(spec)
            else:
                solve(spec, Path(tmp))
            total = time.process_time() - t0
            worst = max(worst, meter.seconds)
            what = "(figure calls only)" if figure_only else f"{meter.seconds / total:6.1%}"
            print(f"{spec.stem:28} {total:12.3f} {meter.seconds:13.3f} {what:>6} {meter.calls:>8} ({meter.drawn})")
    verdict = "met" if worst < TARGET else "MISSED"
    print(f"largest figure cost in a solve {worst:.3f} s CPU (target < {TARGET} s): {verdict}")
    return 0 if worst < TARGET else 1


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
