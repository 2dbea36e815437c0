"""results.md of ``bench accuracy``: the headline table (each method at its best budget), the
curves, the spread over seeds and the outcome on every stress target, as Markdown."""
from __future__ import annotations

from .markdown import table

SUMMARY_COLUMNS = (("method", "method", None), ("budget", "best budget (its)", None), ("targets", "targets", None),
                   ("seconds", "time (s)", ".1f"),
                   ("descriptor_loss", "descriptor loss", ".4f"), ("relative_loss", "loss / default's", ".3f"),
                   ("param_error", "param error", ".4f"), ("map_rmse", "map RMSE", ".4f"),
                   ("novel_rmse", "novel-light RMSE", ".4f"), ("peak_mb", "peak MB", ".0f"),
                   ("failure_rate", "failure rate", ".0%"), ("degraded_rate", "degraded", ".0%"))


def _summary_rows(result: dict) -> list[dict]:
    rows = []
    for row in result["summary"]:
        if row.get("budget") == "unavailable":
            rows.append({"method": row["method"], "budget": "unavailable"})
        else:
            rows.append({**row, "failure_rate": row.get("failure_rate"),
                         "budget": row.get("budget")})
    return rows


def _stress_matrix(result: dict) -> str:
    methods = result["config"]["methods"]
    stress_rows = [r for r in result["rows"] if r["group"] in ("stress", "seeds")]
    targets = list(dict.fromkeys(r["target"] for r in stress_rows))
    if not targets:
        return "_no stress targets in this run_"
    lines = ["| target | graph | " + " | ".join(methods) + " |",
             "|" + "|".join("---" for _ in range(len(methods) + 2)) + "|"]
    for t in targets:
        cells = []
        graph = next(r["graph"] for r in stress_rows if r["target"] == t)
        for m in methods:
            hit = [r for r in stress_rows if r["target"] == t and r["method"] == m]
            cells.append(hit[-1]["status"] if hit else "–")
        lines.append(f"| {t} | {graph} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def markdown(result: dict) -> str:
    m = result["machine"]
    cfg = result["config"]
    parts = [
        f"# Speed against accuracy ({cfg['name']} run)",
        "",
        f"Command: `{result['command']}`. Machine: {m['cpu']}, {m['cores']} cores, torch {m['torch']}, "
        f"{m['threads']} torch threads, device {cfg['device']}. Wall time {result['wall_seconds']:.0f} s.",
        "",
        f"Targets rendered and scored at {cfg['size']} px (descriptor scales "
        f"{'/'.join(str(s) for s in sorted({min(s, cfg['size']) for s in (512, 256, 128)}, reverse=True))}); "
        f"fits render at most at {cfg['size']} px. Graphs: {', '.join(cfg['graphs'] or ['all'])}; "
        f"sample indices {', '.join(str(k) for k in cfg['samples'])}, truth noise seed 1234, fit seed 0.",
        "",
        "## Each method at its best budget",
        "",
        "Best budget: the lowest mean of (descriptor loss / the default parameters' loss) over the main targets "
        "(synthetic and real). Time, losses and errors are means over those targets at that budget "
        "(parameter error, map RMSE and novel-light RMSE over the synthetic ones). Failure and degraded rates "
        "count every run of the method: every target, group and budget.",
        "",
        table(_summary_rows(result), SUMMARY_COLUMNS),
        "",
        f"Classification: {result['rule']}",
        "",
        "## Curves (main targets, every budget)",
        "",
        table([{"method": meth, **p} for meth, pts in result["curves"].items() for p in pts],
              (("method", "method", None), ("budget", "budget", None), ("seconds", "time (s)", ".1f"),
               ("iterations", "iterations", ".0f"), ("descriptor_loss", "descriptor loss", ".4f"),
               ("relative_loss", "loss / default's", ".3f"), ("param_error", "param error", ".4f"),
               ("map_rmse", "map RMSE", ".4f"), ("novel_rmse", "novel-light RMSE", ".4f"))),
        "",
        "## Spread over fit seeds",
        "",
        table(result["spread"], (("method", "method", None), ("budget", "budget", None), ("seeds", "seeds", None),
                                 ("loss_min", "loss min", ".4f"), ("loss_max", "loss max", ".4f"),
                                 ("loss_std", "loss std", ".4f"), ("param_error_min", "param err min", ".4f"),
                                 ("param_error_max", "param err max", ".4f"),
                                 ("param_error_std", "param err std", ".4f"))) if result["spread"] else "_none_",
        "",
        "## Stress targets and seeds (outcome per method)",
        "",
        _stress_matrix(result),
        "",
    ]
    unavailable = [r for r in result["summary"] if r.get("budget") == "unavailable"]
    if unavailable:
        parts += ["Unavailable methods: " + "; ".join(f"{r['method']} ({r.get('note', '')})" for r in unavailable), ""]
    failures = [r for r in result["rows"] if r["status"] == "failed" and r.get("error")]
    if failures:
        parts += ["## Errors", ""] + [f"- {r['target']} / {r['method']}: {r['error']}" for r in failures] + [""]
    return "\n".join(parts)
