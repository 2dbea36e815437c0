"""PNG charts of ``bench accuracy`` (matplotlib, Agg backend: the ``bench`` extra).

- ``speed_accuracy_chart``: one panel per error measure, error against wall time, one curve per
  method through its budgets, the Pareto front over every point drawn as a dashed step line with
  its points circled;
- ``convergence_chart``: loss against time of whole fits (``FitResult.history``), with markers
  for the losses the benchmark measured at each budget;
- ``recovery_chart`` (``bench recovery``): each target's distance to the truth against seconds.
"""
from __future__ import annotations

import math
from pathlib import Path

from .accuracy_metrics import pareto_front


def _pyplot():
    # matplotlib is optional (the bench extra): imported only when a chart is drawn
    try:
        import matplotlib
    except ImportError as exc:  # pragma: no cover - the bench extra installs it
        raise RuntimeError("charts need matplotlib: pip install 'blender-match[bench]'") from exc
    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt  # after use(): pyplot picks its backend on import

    return plt


def _finite(points):
    return [(x, y) for x, y in points if x is not None and y is not None
            and math.isfinite(x) and math.isfinite(y) and x > 0]


def _colour(plt, label: str, order: list[str]):
    return plt.get_cmap("tab10")(order.index(label) % 10)


def speed_accuracy_chart(path: Path, panels: list[tuple[str, dict[str, list[tuple[float, float]]]]],
                         title: str = "Speed against accuracy", order: list[str] | None = None) -> Path:
    """``panels``: [(y label, {method: [(seconds, error), ...]})]; writes ``path``. ``order``:
    method names in the order that picks their colours (the same in every chart)."""
    plt = _pyplot()
    fig, axes = plt.subplots(1, len(panels), figsize=(6.2 * len(panels), 4.8), squeeze=False)
    methods = list(order or sorted({m for _, curves in panels for m in curves}))
    methods += sorted({m for _, curves in panels for m in curves} - set(methods))
    for ax, (label, curves) in zip(axes[0], panels):
        everything = []
        for method in methods:
            points = sorted(_finite(curves.get(method, [])))
            if not points:
                continue
            colour = _colour(plt, method, methods)
            ax.plot([p[0] for p in points], [p[1] for p in points], "-o", color=colour, label=method,
                    markersize=4, linewidth=1.4)
            everything.extend(points)
        front = [everything[i] for i in pareto_front(everything)]
        if front:
            xs, ys = [p[0] for p in front], [p[1] for p in front]
            ax.step(xs, ys, where="post", color="black", linestyle="--", linewidth=1, label="Pareto front")
            ax.scatter(xs, ys, s=90, facecolors="none", edgecolors="black", linewidths=1.2, zorder=5)
        ax.set_xscale("log")
        ax.set_xlabel("wall time (s, log)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def convergence_chart(path: Path, series: dict[str, list[tuple[float, float]]],
                      markers: dict[str, list[tuple[float, float]]] | None = None,
                      title: str = "Convergence", order: list[str] | None = None) -> Path:
    """``series``: {label: [(seconds, loss)]} drawn as lines; ``markers``: {label: [(seconds,
    loss)]} drawn as points of the same colour when the label matches a series."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    labels = list(series) + [m for m in (markers or {}) if m not in series]
    order = list(order or labels) + [m for m in labels if m not in (order or labels)]
    for label in labels:
        colour = _colour(plt, label, order)
        line = _finite(series.get(label, []))
        if line:
            ax.plot([p[0] for p in line], [p[1] for p in line], "-", color=colour, linewidth=1.2, label=label)
        dots = _finite((markers or {}).get(label, []))
        if dots:
            ax.plot([p[0] for p in dots], [p[1] for p in dots], "D", color=colour, markersize=6,
                    markeredgecolor="black", label=None if line else label)
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("descriptor loss")
    ax.set_yscale("log")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def recovery_chart(path: Path, rows: list[dict], presets, measures) -> Path:
    """``bench recovery``: per measure, each target's ratio to the truth's against the preset's
    seconds (log scales), the start marked at 0.5 s."""
    plt = _pyplot()
    fig, axes = plt.subplots(1, len(measures), figsize=(5 * len(measures), 4.2))
    colours = plt.get_cmap("tab10")
    for ax, m in zip(axes, measures):
        for i, preset in enumerate(presets):
            mine = [r for r in rows if r["preset"] == preset]
            ax.scatter([r["seconds"] for r in mine], [r[f"{m}_ratio"] for r in mine], color=colours(i), label=preset)
            ax.scatter([0.5] * len(mine), [r[f"{m}_start_ratio"] for r in mine], color=colours(i), marker="x", s=14)
        ax.axhline(1.0, color="grey", lw=0.8, ls="--")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("seconds (x at 0.5 s: the start)")
        ax.set_ylabel(f"{m}: distance / truth's")
    axes[0].legend()
    fig.suptitle("bench recovery: distance to the truth against time")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
