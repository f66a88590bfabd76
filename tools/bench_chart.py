"""Draws headlight bench's chart from bench.csv: frame time (x, log) against
error (y) per scene and resolution, every configuration a point, the Pareto
front drawn, the seed spec's default marked. Writes bench.png and bench.svg,
and bench_summary.md: per scene and resolution, the (time, AO RMSE) front
and how far the seed default is from it.

Run by `headlight bench` (embedded in the binary) as
    /usr/bin/python3 - BENCH_CSV OUT_DIR
or by hand the same way. Needs matplotlib (Debian: python3-matplotlib).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METRICS = [("ao_rmse", "AO RMSE vs reference (within R)"),
           ("indirect_rmse", "indirect RMSE vs reference (within R)"),
           ("lit_rel_rmse", "lit relative RMSE vs lit_ref (no R)"),
           ("lit_flip", "lit HDR-FLIP vs lit_ref, mean (no R)")]
MARKERS = {"hemisphere": "o", "radiance": "s", "bitmask": "^"}
COLOURS = {"hemisphere": "C0", "radiance": "C1", "bitmask": "C2"}
SIZES = {"full": 26, "half": 12, "quarter": 6}  # SSGI resolution: full-resolution points are the largest
# Columns are the setting table's row names (bench.csv has one per setting).
METHOD, BLUR, RESOLUTION, FRAMES = "ssgi-method", "ssgi-blur", "ssgi-resolution", "ssgi-frames"
# Columns that differ between two rows of one configuration: its label and its measurements.
CHANGING = {"label", "frame_ms_median", "frame_ms_min", "frame_ms_max", "ssgi_ms_median", "ssgi_ms_min",
            "ssgi_ms_max", "ao_rmse", "ao_mae", "sky_rmse", "sky_mae", "indirect_rmse", "indirect_rel_rmse",
            "lit_rel_rmse", "lit_ssim", "lit_flip", "pareto_ao", "repetitions", "seed_default",
            "frame_gpu_ms_median", "frame_gpu_ms_min", "frame_gpu_ms_max", "ssgi_gpu_ms_median", "ssgi_gpu_ms_min",
            "ssgi_gpu_ms_max", "forms"}


def pareto(points):
    """Indices of points (time, error) that no other point dominates."""
    front = []
    for i, (ti, ei) in enumerate(points):
        dominated = any((tj <= ti and ej <= ei) and (tj < ti or ej < ei)
                        for j, (tj, ej) in enumerate(points) if j != i)
        if not dominated:
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def describe(r):
    """The configuration's swept settings, and the radius it resolved to."""
    return f"{r['label']} (radius {float(r['ssgi-radius']):.3g})"


def summary(rows, groups):
    """Markdown: the AO front per group and the seed default against it."""
    lines = []
    for scene, width, height in groups:
        group = [r for r in rows if (r["scene"], r["width"], r["height"]) == (scene, width, height)]
        points = [(float(r["frame_ms_median"]), float(r["ao_rmse"])) for r in group]
        front = pareto(points)
        lines += [f"### {scene} {width}x{height}", "",
                  "| on the front (fastest first) | frame ms (median) | AO RMSE | indirect RMSE |", "|---|---|---|---|"]
        for i in front:
            r = group[i]
            lines.append(f"| {describe(r)} | {float(r['frame_ms_median']):.2f} | {float(r['ao_rmse']):.4f} | "
                         f"{float(r['indirect_rmse']):.4f} |")
        seeds = [r for r in group if r["seed_default"] == "1"]
        if seeds:
            seed = seeds[0]
            seed_time, seed_error = float(seed["frame_ms_median"]), float(seed["ao_rmse"])
            faster = [group[i] for i in front if float(group[i]["ao_rmse"]) <= seed_error]
            better = [group[i] for i in front if float(group[i]["frame_ms_median"]) <= seed_time]
            lines += ["", f"Seed default ({describe(seed)}): {seed_time:.2f} ms, AO RMSE {seed_error:.4f}"
                      f"{' (on the front)' if seed['pareto_ao'] == '1' else ''}."]
            if faster:
                quickest = min(faster, key=lambda r: float(r["frame_ms_median"]))
                lines.append(f"Fastest front point at least as accurate: {describe(quickest)}, "
                             f"{float(quickest['frame_ms_median']):.2f} ms "
                             f"({seed_time / float(quickest['frame_ms_median']):.2f}x faster).")
            if better:
                best = min(better, key=lambda r: float(r["ao_rmse"]))
                lines.append(f"Most accurate front point no slower: {describe(best)}, AO RMSE "
                             f"{float(best['ao_rmse']):.4f} ({float(best['ao_rmse']) - seed_error:+.4f}).")
        # A CSV from before lit_flip existed has no such column.
        flip = "lit_flip" in group[0]
        lines += ["", "Lowest lit error (lit_ref does not depend on R, so radii compare fairly here):", "",
                  "| configuration | frame ms (median) | lit relative RMSE | lit SSIM |"
                  + (" lit HDR-FLIP |" if flip else ""),
                  "|---|---|---|---|" + ("---|" if flip else "")]
        for r in sorted(group, key=lambda r: float(r["lit_rel_rmse"]))[:3] + seeds[:1]:
            lines.append(f"| {describe(r)}{' (seed default)' if r['seed_default'] == '1' else ''} | "
                         f"{float(r['frame_ms_median']):.2f} | {float(r['lit_rel_rmse']):.4f} | "
                         f"{float(r['lit_ssim']):.3f} |" + (f" {float(r['lit_flip']):.4f} |" if flip else ""))
        lines.append("")
    return "\n".join(lines)


def save_figure(fig, out_dir, stem):
    """<stem>.png and <stem>.svg, each written to a temporary name and renamed."""
    for extension in ("png", "svg"):
        path = os.path.join(out_dir, stem + "." + extension)
        tmp = os.path.join(out_dir, "." + stem + ".tmp." + extension)
        fig.savefig(tmp, dpi=110)
        os.replace(tmp, path)
        print(path)


def frames_chart(rows, out_dir):
    """frames.png/svg when the bench swept ssgi-frames: AO RMSE against the
    number of accumulated frames N, a line per scene and blur setting (the
    other settings of a line held equal), N on a log axis."""
    counts = sorted({int(r[FRAMES]) for r in rows if r.get(FRAMES)})
    if len(counts) < 2:
        return
    lines = {}
    for r in rows:
        if r["seed_default"] == "1":
            continue
        key = tuple((k, v) for k, v in r.items() if k not in CHANGING and k != FRAMES)
        lines.setdefault(key, []).append((int(r[FRAMES]), float(r["ao_rmse"]), r))
    fig, ax = plt.subplots(figsize=(7.0, 4.5))
    for points in lines.values():
        if len(points) < 2:
            continue
        points.sort(key=lambda p: p[0])
        r = points[0][2]
        ax.plot([p[0] for p in points], [p[1] for p in points], marker="o" if r[BLUR] == "on" else "x",
                linestyle="-" if r[BLUR] == "on" else "--",
                label=f"{os.path.basename(r['scene'])} {r['width']}x{r['height']}, blur {r[BLUR]}")
    ax.set_xscale("log", base=2)
    ax.set_xticks(counts, [str(n) for n in counts])
    ax.set_xlabel("frames accumulated, N (ssgi-frames)")
    ax.set_ylabel("AO RMSE vs reference (within R)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.suptitle(f"headlight bench: AO error against N\n{rows[0]['renderer']}", fontsize=9)
    fig.tight_layout()
    save_figure(fig, out_dir, "frames")


def main():
    csv_path, out_dir = sys.argv[1], sys.argv[2]
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    groups = sorted({(r["scene"], r["width"], r["height"]) for r in rows})
    # A CSV from before a metric's column existed is charted without that row.
    metrics = [(column, label) for column, label in METRICS if not rows or column in rows[0]]
    fig, axes = plt.subplots(len(metrics), len(groups), figsize=(max(7.0, 5.2 * len(groups)), 4.2 * len(metrics)),
                             squeeze=False)
    for column, (scene, width, height) in enumerate(groups):
        group = [r for r in rows if (r["scene"], r["width"], r["height"]) == (scene, width, height)]
        for row_index, (metric, label) in enumerate(metrics):
            ax = axes[row_index][column]
            points = [(float(r["frame_ms_median"]), float(r[metric])) for r in group]
            for method, marker in MARKERS.items():
                for blur, fill in (("on", "full"), ("off", "none")):
                    chosen = [(p, r) for p, r in zip(points, group) if r[METHOD] == method and r[BLUR] == blur]
                    if not chosen:
                        continue
                    ax.scatter([p[0] for p, _ in chosen], [p[1] for p, _ in chosen], marker=marker,
                               s=[SIZES.get(r[RESOLUTION], 10) for _, r in chosen],
                               facecolors=None if fill == "full" else "none",
                               edgecolors=COLOURS[method],
                               c=None if fill == "none" else COLOURS[method],
                               label=f"{method}, blur {blur}", alpha=0.8)
            front = pareto(points)
            ax.plot([points[i][0] for i in front], [points[i][1] for i in front], "k-", lw=1, label="Pareto front")
            # The bitmask method's own front beside the kernel methods' (both fronts).
            kernel = [i for i, r in enumerate(group) if r[METHOD] != "bitmask"]
            if len(kernel) < len(group):
                kernel_front = [kernel[i] for i in pareto([points[i] for i in kernel])]
                ax.plot([points[i][0] for i in kernel_front], [points[i][1] for i in kernel_front], "k:", lw=1,
                        label="front without bitmask")
            for p, r in zip(points, group):
                if r["seed_default"] == "1":
                    ax.scatter([p[0]], [p[1]], marker="*", s=220, c="red", zorder=5, label="seed default")
            ax.set_xscale("log")
            ax.set_xlabel("frame time, median (ms, log)")
            ax.set_ylabel(label)
            # A file scene by its name alone: a path does not fit over a panel.
            ax.set_title(f"{os.path.basename(scene)} {width}x{height}")
            ax.grid(True, which="both", alpha=0.3)
            if column == 0 and row_index == 0:
                ax.legend(fontsize=7, title="marker size: SSGI resolution", title_fontsize=7)
    summary_path = os.path.join(out_dir, "bench_summary.md")
    with open(summary_path + ".tmp", "w") as f:
        f.write(summary(rows, groups))
    os.replace(summary_path + ".tmp", summary_path)
    print(summary_path)
    renderer = rows[0]["renderer"] if rows else ""
    fig.suptitle(f"headlight bench: SSGI time against error\n{renderer}", fontsize=9)
    fig.tight_layout()
    save_figure(fig, out_dir, "bench")
    frames_chart(rows, out_dir)


if __name__ == "__main__":
    main()
