"""Plots, from dense_benchmark's CSV, CPU time, Newton steps and peak memory against the
garment's faces, on log-log axes, one curve per scene and variant (factor-reuse threshold,
proxy size), with a line of slope 1 (linear cost) through the coarsest run of each curve
that runs as the preset does, for comparison."""

import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    by_scene = defaultdict(list)
    for row in csv.DictReader(open(csv_path)):
        parts = [row["scene"]]
        reuse = row.get("reuse_gflops", "preset")
        proxy = row.get("proxy_faces", "preset")
        if reuse != "preset":
            parts.append(f"reuse {reuse} GFLOP")
        if proxy != "preset":
            parts.append("direct" if proxy == "0" else f"proxy {proxy}")
        by_scene[", ".join(parts)].append(row)
    panels = [("cpu_seconds", "CPU time (s)"),
              (None, "the garment's own Newton steps (inflate + fit)"),
              ("peak_memory_mb", "peak resident memory (MB)")]
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.6))
    for ax, (column, label) in zip(axes, panels):
        for scene, rows in sorted(by_scene.items()):
            rows.sort(key=lambda r: int(r["faces"]))
            faces = [int(r["faces"]) for r in rows]
            if column is None:
                values = [int(r["newton_inflate"]) + int(r["newton_fit"]) for r in rows]
            else:
                values = [float(r[column]) for r in rows]
            line, = ax.plot(faces, values, "o-", label=scene)
            preset_like = "reuse 0 " not in scene + " " and "direct" not in scene
            if column == "cpu_seconds" and preset_like:
                ax.plot(faces, [values[0] * f / faces[0] for f in faces], "--",
                        color=line.get_color(), alpha=0.5, label=f"{scene}, linear")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("garment faces")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Dense garments: cost against size (dense_benchmark)")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_dense.py results.csv plot.png")
    main(sys.argv[1], sys.argv[2])
