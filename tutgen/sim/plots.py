"""The plots of a simulation (matplotlib, non-interactive Agg): q(t), q_dot(t) and the energy in one
figure, and for a planar system a strip of snapshots of the mechanism.

The snapshots place the bodies with the figure package's numeric pose (:class:`tutgen.figure.pose.Pose`,
the model's joint conventions) at the simulated coordinates: each body is drawn as lines from its
frame's origin (its joint) to the joints of its children and to its parts' centres. A system is
planar here when every such point stays in one coordinate plane (x-y, y-z or z-x) in every snapshot.

Output is the same bytes every run: no date or software version in the PNG, fixed size and dpi, and
labels only from declared names.
"""

from __future__ import annotations

import io
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from tutgen.model.system import System
    from tutgen.sim.run import SimulationResult

__all__ = ["SNAPSHOTS", "plot_png", "snapshot_points", "snapshots_png"]

#: How many snapshots the strip shows.
SNAPSHOTS = 6
_DPI = 100


def _figure(width: float, height: float):  # noqa: ANN202 - matplotlib's Figure, imported lazily
    from matplotlib.figure import Figure

    # fixed margins: constrained layout costs seconds per figure on a loaded machine
    fig = Figure(figsize=(width, height), dpi=_DPI)
    fig.subplots_adjust(left=0.14, right=0.98, top=0.93, bottom=0.09, wspace=0.35, hspace=0.25)
    return fig


def _png(fig: object) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", metadata={"Software": None})  # type: ignore[attr-defined]
    return buf.getvalue()


def plot_png(result: SimulationResult) -> bytes:
    """q(t), q_dot(t) and T, U, E(t), one panel each, as a PNG; for a constrained spec also the
    multipliers lambda(t) and the constraints' residuals |f(t)| (log scale)."""
    tr = result.trajectory
    constrained = result.residuals is not None and result.multipliers is not None
    fig = _figure(7.5, 11.5 if constrained else 8.0)
    if constrained:
        fig.subplots_adjust(top=0.95, bottom=0.06)
    axes = fig.subplots(5 if constrained else 3, 1, sharex=True)
    for i, name in enumerate(result.coordinates):
        axes[0].plot(tr.t, tr.q[:, i], label=name)
        axes[1].plot(tr.t, tr.qd[:, i], label=f"{name}_dot")
    axes[0].set_ylabel("q (m or rad)")
    axes[1].set_ylabel("q_dot (m/s or rad/s)")
    axes[2].plot(tr.t, result.kinetic, label="kinetic T")
    axes[2].plot(tr.t, result.potential, label="potential U")
    axes[2].plot(tr.t, result.total, label="total E = T + U", color="black", linewidth=1.5)
    axes[2].set_ylabel("energy (J)")
    axes[-1].set_xlabel("t (s)")
    if constrained:
        assert result.residuals is not None and result.multipliers is not None
        for k, (name, _) in enumerate(result.constraints):
            axes[3].plot(tr.t, result.multipliers[:, k], label=f"lambda_{k + 1} ({name})")
            # a residual that is exactly 0 has no place on a log scale: drawn at the floor
            axes[4].semilogy(tr.t, np.maximum(np.abs(result.residuals[:, k]), 1e-18), label=name)
        axes[3].set_ylabel("multipliers (N or N m)")
        axes[4].set_ylabel("|constraint residual|")
    if result.drift is not None and result.conservative:
        axes[2].set_title(f"relative energy drift {result.drift:.2g} (tolerance {result.tolerance:.2g})", fontsize=9)
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize=8)
    if tr.stopped is not None:
        fig.suptitle(f"stopped early: {tr.stopped}", fontsize=9, color="darkred")
    return _png(fig)


def _points(system: System, values: dict, q: np.ndarray) -> list[list[np.ndarray]]:
    """For each body, its polyline points (world) at the coordinates ``q``."""
    from tutgen.figure.pose import Numbers, Pose

    table = dict(values)
    for c, v in zip(system.coordinates, q, strict=True):
        table[c.q] = float(v)
    num = Numbers(table)
    pose = Pose(system, num)
    lines = []
    for body in system.bodies:
        origin = pose.frames[body.name][0]
        ends = [pose.joint_at[j.name] for j in system.joints if j.parent == body.name and j.name in pose.joint_at]
        for part in body.parts:
            centre = num.vec(part.at)
            ends.append(pose.point(body.name, centre))
            length = dict(part.dimensions).get("length")
            if part.axis is not None and length is not None and not isinstance(length, tuple):
                # a rod or cylinder: its far end along its axis, so that a hanging link is drawn whole
                half = 0.5 * num(length) * num.vec(part.axis)
                far = max((centre + half, centre - half), key=lambda e: float(np.linalg.norm(e)))
                ends.append(pose.point(body.name, far))
        lines.append([origin, *ends])
    return lines


def snapshot_points(system: System, values: dict, states: np.ndarray) -> tuple[list, tuple[int, int]] | None:
    """The bodies' polylines at each state and the two world axes of the plane, or None when the
    points do not stay in one coordinate plane."""
    frames = [_points(system, values, q) for q in states]
    allpts = np.array([p for frame in frames for line in frame for p in line])
    if allpts.size == 0:
        return None
    extent = float(np.max(np.ptp(allpts, axis=0))) or 1.0
    for normal in (2, 0, 1):
        if np.ptp(allpts[:, normal]) <= 1e-9 * extent:
            plane = tuple(k for k in (0, 1, 2) if k != normal)
            return frames, (plane[0], plane[1])
    return None


def snapshots_png(result: SimulationResult, system: System, values: dict) -> bytes | None:
    """A strip of :data:`SNAPSHOTS` poses at equally spaced sample times, or None for a system that
    does not move in one plane (or has no bodies)."""
    if not system.bodies or not system.joints:
        return None
    tr = result.trajectory
    if len(tr.t) == 0:
        return None
    picks = np.unique(np.linspace(0, len(tr.t) - 1, SNAPSHOTS).round().astype(int))
    found = snapshot_points(system, values, tr.q[picks])
    if found is None:
        return None
    frames, (a, b) = found
    allpts = np.array([p for frame in frames for line in frame for p in line])
    lo, hi = allpts.min(axis=0), allpts.max(axis=0)
    pad = 0.08 * float(max(hi[a] - lo[a], hi[b] - lo[b]) or 1.0)
    # panels as tall as the mechanism's extent needs at their width (between 1.2 and 4 inches), and
    # the figure as tall as its panels and their titles and tick labels: no empty band above or below
    aspect = float((hi[b] - lo[b] + 2 * pad) / max(hi[a] - lo[a] + 2 * pad, 1e-12))
    n = len(picks)
    left, right, wspace = 0.6, 0.1, 0.3  # inches, and the gap as a fraction of a panel's width
    panel = (2.0 * n - left - right) / (n + wspace * (n - 1))
    panel_height = min(4.0, max(1.2, panel * aspect))
    top, bottom = 0.35, 0.5
    height = panel_height + top + bottom
    fig = _figure(2.0 * n, height)
    fig.subplots_adjust(
        left=left / (2.0 * n), right=1 - right / (2.0 * n), top=1 - top / height, bottom=bottom / height, wspace=wspace
    )
    axes = fig.subplots(1, len(picks), squeeze=False)[0]
    axis_names = "xyz"
    for ax, k, frame in zip(axes, picks, frames, strict=True):
        ax.plot([0], [0], marker="^", color="gray", markersize=8)  # the ground frame's origin
        for line in frame:
            pts = np.array(line)
            for end in pts[1:]:
                ax.plot([pts[0][a], end[a]], [pts[0][b], end[b]], color="tab:blue", linewidth=2.5)
            ax.plot(pts[:, a], pts[:, b], "o", color="black", markersize=3)
        ax.set_xlim(lo[a] - pad, hi[a] + pad)
        ax.set_ylim(lo[b] - pad, hi[b] + pad)
        ax.set_aspect("equal")
        ax.set_title(f"t = {tr.t[k]:.3g} s", fontsize=9)
        ax.tick_params(labelsize=7)
        ax.set_xlabel(axis_names[a], fontsize=8)
    axes[0].set_ylabel(axis_names[b], fontsize=8)
    return _png(fig)
