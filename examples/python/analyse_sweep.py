#!/usr/bin/env python3
"""Summarize one metric of a campo sweep per group of runs, and plot it.

    analyse_sweep.py SWEEP_DIR --metric path_ratio [--by FIELD] --out plot.png

Reads SWEEP_DIR (what `campo sweep --out SWEEP_DIR` wrote) with campo.read_results, prints per value of FIELD (an
axis, `scene`, `planner` or `seed`; default: the sweep's first axis, else `scene`) the runs, the failed ones, the
success rate and the metric's n, mean and standard deviation, and draws every run's value per group with the
group's mean and standard deviation. METRIC is a key of run.json's `metrics` or `success`; `METRIC@reached` is
over the runs that reached their goal only, as in `campo table`. Run from the build tree with
PYTHONPATH=build/python.
"""

import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import campo  # noqa: E402

REACHED_SUFFIX = "@reached"
# Fields of every run to group by, besides the sweep's axes.
RUN_FIELDS = ("scene", "planner", "seed")
# Unit of a metric or field from its name's suffix, as `campo plot` labels its axes.
UNITS = {"_m": "m", "_s": "s", "_ms": "ms", "_mps": "m/s", "_deg": "deg", "_radps": "rad/s", "_hz": "Hz"}


def unit_label(name: str) -> str:
    """The name with its unit, for an axis label: "min_clearance_m (m)"."""
    if name == "path_ratio":
        return "normalized path length"
    if name == "success":
        return "success rate (%)"
    for suffix, unit in sorted(UNITS.items(), key=lambda item: -len(item[0])):
        if name.endswith(suffix):
            return f"{name} ({unit})"
    return name


def metric_kind(runs: pd.DataFrame, metric: str) -> str:
    """"rate" for success and boolean metrics (summarized as the rate of true), "number" for numbers, else ""."""
    base = metric.removesuffix(REACHED_SUFFIX)
    if base == "success":
        return "rate"
    if base not in runs.attrs["metrics"]:
        return ""
    dtype = runs[base].dtype
    if dtype == bool or str(dtype) == "boolean":
        return "rate"
    return "number" if dtype.kind in "iuf" else ""


def fail(message: str) -> None:
    print(f"error: {message}", file=sys.stderr)
    sys.exit(2)


def metric_values(runs: pd.DataFrame, metric: str) -> pd.Series:
    """One value per run: 1.0/0.0 for success (failed runs not reached) and booleans, NaN where a run has none."""
    base = metric.removesuffix(REACHED_SUFFIX)
    values = (runs["success"] if base == "success" else runs[base]).astype("float64")
    if metric.endswith(REACHED_SUFFIX):
        values = values.where(runs["outcome"] == "reached")
    return values


def summarize(runs: pd.DataFrame, field: str, metric: str) -> pd.DataFrame:
    values = metric_values(runs, metric)
    rows = []
    for group, members in runs.groupby(field, sort=False, dropna=False):
        group_values = values.loc[members.index].dropna()
        rows.append({field: group, "runs": len(members), "failed": int((members["status"] == "failed").sum()),
                     "success_rate": members["success"].mean(), "n": len(group_values),
                     "mean": group_values.mean() if len(group_values) else np.nan,
                     "sd": group_values.std(ddof=1) if len(group_values) > 1 else np.nan})
    return pd.DataFrame(rows).set_index(field)


def plot(runs: pd.DataFrame, field: str, metric: str, summary: pd.DataFrame, title: str, out: pathlib.Path) -> None:
    values = metric_values(runs, metric)
    figure, axes = plt.subplots(figsize=(8, 5), dpi=150)
    positions = np.arange(len(summary))
    if metric_kind(runs, metric) == "rate":
        # A rate: one bar per group.
        axes.bar(positions, 100.0 * summary["mean"], color="tab:blue", width=0.6)
        axes.set_ylim(0, 105)
    else:
        for position, (group, members) in zip(positions, runs.groupby(field, sort=False, dropna=False)):
            group_values = values.loc[members.index].dropna().to_numpy()
            # Spread the runs' points sideways (fixed offsets, not random: the same results give the same figure).
            offsets = np.linspace(-0.15, 0.15, len(group_values)) if len(group_values) > 1 else np.zeros(1)
            axes.plot(position + offsets[:len(group_values)], group_values, "o", color="tab:gray", alpha=0.6,
                      markersize=5, label="run" if position == 0 else None)
        axes.errorbar(positions, summary["mean"], yerr=summary["sd"].fillna(0.0), fmt="s", color="tab:red",
                      capsize=6, markersize=8, label="mean ± sd")
        if metric.removesuffix(REACHED_SUFFIX) == "path_ratio":
            axes.axhline(1.0, color="black", linestyle="--", linewidth=1, label="ideal (1)")
        axes.legend()
    axes.set_xlim(-0.5, len(summary) - 0.5)
    axes.set_xticks(positions)
    axes.set_xticklabels([f"{group}\n(n={n})" for group, n in zip(summary.index, summary["n"])])
    # Which runs a value is over, as campo plot says it; success is always over every run, failed ones not reached.
    over = "" if metric == "success" else ", reached runs" if metric.endswith(REACHED_SUFFIX) else ", all runs"
    axes.set_xlabel(unit_label(field))
    axes.set_ylabel(unit_label(metric.removesuffix(REACHED_SUFFIX)) + over)
    failed = int((runs["status"] == "failed").sum())
    axes.set_title(f"{title}\n{len(runs)} runs, {failed} failed; n: runs with a value")
    axes.grid(axis="y", alpha=0.3)
    figure.tight_layout()
    figure.savefig(out)
    plt.close(figure)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sweep_dir", type=pathlib.Path, help="a sweep directory (campo sweep --out DIR)")
    parser.add_argument("--metric", default="path_ratio", help="a run.json metric, success, or METRIC@reached")
    parser.add_argument("--by", help="the field to group by: an axis, scene, planner or seed")
    parser.add_argument("--out", type=pathlib.Path, required=True, help="the PNG to write")
    args = parser.parse_args()

    try:
        runs = campo.read_results(args.sweep_dir)
    except campo.ResultsError as error:
        fail(str(error))
    if runs.empty:
        fail(f"{args.sweep_dir}: no runs recorded yet")
    axes, metrics = runs.attrs["axes"], runs.attrs["metrics"]
    field = args.by or (axes[0] if axes else "scene")
    if field not in list(RUN_FIELDS) + axes:
        fail(f"--by: expected a field of the runs ({', '.join(list(RUN_FIELDS) + axes)}), got \"{field}\"")
    if not metric_kind(runs, args.metric) or args.metric == "success" + REACHED_SUFFIX:
        known = [name for name in ["success"] + metrics if metric_kind(runs, name)]
        fail(f"--metric: expected a metric of the runs ({', '.join(known)}, or one of them followed by "
             f"{REACHED_SUFFIX}), got \"{args.metric}\"")

    summary = summarize(runs, field, args.metric)
    print(f"{args.metric} by {field} ({len(runs)} runs in {args.sweep_dir}):")
    with pd.option_context("display.float_format", "{:.4g}".format, "display.width", 120):
        print(summary.to_string())
    title = f"{runs.attrs['sweep']}: {args.metric} by {field}"
    try:
        plot(runs, field, args.metric, summary, title, args.out)
    except OSError as error:
        fail(f"{args.out}: cannot write: {error.strerror or error}")
    print(f"plot written to {args.out}")


if __name__ == "__main__":
    main()
