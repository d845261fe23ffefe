"""Plots, from retarget_benchmark's CSV, time against fit error, time against shape change
(scale-free mean edge-length change) and fit error against shape change: one curve per
scene (the eps_tol and voxel sweeps and the presets), presets labelled."""

import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path)))
    by_scene = defaultdict(list)
    for row in rows:
        by_scene[row["scene"]].append(row)
    fig, axes = plt.subplots(1, 3, figsize=(18, 4.8))
    time_label = "wall time, read to certificate (s)"
    fit_label = "mean fit error (avatar units)"
    shape_label = "shape change (scale-free mean edge-length change)"
    panels = [("total_s", time_label, "fit_error_mean", fit_label),
              ("total_s", time_label, "edge_change_mean", shape_label),
              ("edge_change_mean", shape_label, "fit_error_mean", fit_label)]
    for ax, (x_column, x_label, column, label) in zip(axes, panels):
        for scene, scene_rows in sorted(by_scene.items()):
            points = sorted(((float(r[x_column]), float(r[column]), r) for r in scene_rows),
                            key=lambda point: point[:2])
            line, = ax.plot([p[0] for p in points], [p[1] for p in points], "o-", label=scene, alpha=0.8)
            for t, value, r in points:
                if r["preset"] == "1":
                    ax.annotate(r["quality"], (t, value), textcoords="offset points", xytext=(4, 4),
                                fontsize=8, color=line.get_color())
                    ax.plot([t], [value], "s", color=line.get_color(), markersize=8)
        ax.set_xlabel(x_label)
        ax.set_ylabel(label)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("garment-retarget: speed, fit and shape (squares: presets)")
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
