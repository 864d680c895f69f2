#!/usr/bin/env python3
"""Charts of a `sonarloop sweep` output folder (Pailhas, Petillot & Capus 2010, Figs. 11/13/15).

usage: python3 tools/plot_sweep.py OUT_DIR
       python3 tools/plot_sweep.py --compare OUT.png LABEL=DIR [LABEL=DIR ...]

Reads OUT_DIR/NAME.csv and NAME_confusion.csv as `sonarloop sweep` writes them and draws, next
to them:
  NAME.png             misidentification (%) per target against the experiment's x (pixel
                       resolution for fig11/13/15), with 95 % Wilson intervals; fig13 adds the
                       mine / non-mine decision error
  aspect.png           error against target aspect, one curve per subspace layout
  NAME_confusion.png   row-normalised confusion matrices, one per condition
  speed_accuracy.png   render and classification time per chip against accuracy, across
                       resolution (fig11) and p
  ablation.png, fusion.png, open_set.png  the variants side by side
--compare draws, for every experiment found in all the folders, the overall misidentification
(and fig13's mine / non-mine error) of each folder on one panel: e.g. a run against the same
run with `--crop auto`.
Only the Python standard library and matplotlib (Agg backend) are used.
"""
import csv
import os
import sys
from collections import OrderedDict, defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DPI = 90
LOG_X = {"train_per_class", "p"}
X_LABEL = {
    "resolution_cm": "pixel resolution (cm)",
    "aspect_deg": "target aspect (deg)",
    "source_level_db": "source level (dB re 1 uPa at 1 m)",
    "altitude_m": "sonar altitude (m)",
    "train_per_class": "training chips per target",
    "burial_pct": "burial (% of the target's height)",
    "p": "subspace dimension p",
    "aspect_sectors": "aspect sectors",
}


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def series_of(rows):
    out = OrderedDict()
    for r in rows:
        out.setdefault(r["series"], []).append(r)
    return out


def curve(rows, cls, x_name):
    pts = [r for r in rows if r["class"] == cls and r["x_name"] == x_name]
    pts.sort(key=lambda r: float(r["x"]))
    x = [float(r["x"]) for r in pts]
    y = [float(r["error_pct"]) for r in pts]
    lo = [float(r["error_pct"]) - float(r["ci_low_pct"]) for r in pts]
    hi = [float(r["ci_high_pct"]) - float(r["error_pct"]) for r in pts]
    return x, y, lo, hi


def distinct(rows, key):
    """The values of column `key`, each once, in order of first appearance."""
    seen = []
    for r in rows:
        if r[key] not in seen:
            seen.append(r[key])
    return seen


def classes_of(rows):
    return distinct(rows, "class")


def finish_error_axis(ax, title, x_name):
    """Title, x label (log where the x is), a 0-100 % misidentification axis, grid, legend."""
    ax.set_title(title)
    ax.set_xlabel(X_LABEL.get(x_name, x_name))
    ax.set_ylabel("misidentification (%)")
    ax.set_ylim(0, 100)
    if x_name in LOG_X:
        ax.set_xscale("log")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)


def plot_error_curves(name, rows, out_dir):
    """One panel per series: error per class against x (fig11/13/15 and the stability runs)."""
    groups = series_of([r for r in rows if r["x_name"] != "aspect_deg"])
    x_name = rows[0]["x_name"]
    mine = any(r["class"] == "mine_vs_non_mine" for r in rows)
    panels = len(groups) + (1 if mine else 0)
    fig, axes = plt.subplots(1, panels, figsize=(6.0 * panels, 4.2), squeeze=False)
    for ax, (series, srows) in zip(axes[0], groups.items()):
        for cls in classes_of(srows):
            if cls == "mine_vs_non_mine":
                continue
            x, y, lo, hi = curve(srows, cls, x_name)
            style = (dict(lw=2.5, color="black") if cls == "all" else
                     dict(lw=1.0, ls="--") if cls.startswith("seabed_") else dict(lw=1.2))
            ax.errorbar(x, y, yerr=[lo, hi], marker="o", ms=3, capsize=2, label=cls, **style)
        finish_error_axis(ax, f"{name} {series}".strip() + ": misidentification", x_name)
    if mine:
        ax = axes[0][-1]
        for series, srows in groups.items():
            x, y, lo, hi = curve(srows, "mine_vs_non_mine", x_name)
            ax.errorbar(x, y, yerr=[lo, hi], marker="o", ms=3, capsize=2, label=series or "all")
        ax.set_title(f"{name}: mine / non-mine decision error")
        ax.set_xlabel(X_LABEL.get(x_name, x_name))
        ax.set_ylabel("error (%)")
        ax.set_ylim(0, None)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, f"{name}.png"), dpi=DPI)
    plt.close(fig)


def plot_seabed(name, path, out_dir):
    """NAME_seabed.csv: one panel per test seabed, each target's error against x (one series:
    the first; the aspect experiment's per-series seabeds are in the CSV)."""
    rows = read_rows(path)
    if not rows:
        return
    first = rows[0]["series"]
    rows = [r for r in rows if r["series"] == first]
    x_name = rows[0]["x_name"]
    seabeds = distinct(rows, "seabed")
    fig, axes = plt.subplots(1, len(seabeds), figsize=(5.0 * len(seabeds), 4.0), squeeze=False)
    for ax, seabed in zip(axes[0], seabeds):
        srows = [r for r in rows if r["seabed"] == seabed]
        for cls in classes_of(srows):
            x, y, lo, hi = curve(srows, cls, x_name)
            ax.errorbar(x, y, yerr=[lo, hi], marker="o", ms=3, capsize=2, label=cls, lw=1.2)
        finish_error_axis(ax, f"{name} {first}".strip() + f": on {seabed}", x_name)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, f"{name}_seabed.png"), dpi=DPI)
    plt.close(fig)


def looks_of(series):
    """The number of looks fused in a series named "N look" / "N looks" (sweep --looks), else None."""
    parts = series.split(" ")
    if len(parts) == 2 and parts[0].isdigit() and parts[1] in ("look", "looks"):
        return int(parts[0])
    return None


def plot_looks(name, rows, out_dir):
    """sweep --looks: one panel per resolution, each target's error (and fig13's mine / non-mine
    decision error, dashed) against the looks fused."""
    rows = [r for r in rows if looks_of(r["series"]) is not None and r["x_name"] == "resolution_cm"
            and not r["class"].startswith("seabed_")]
    xs = distinct(rows, "x")
    fig, axes = plt.subplots(1, len(xs), figsize=(4.5 * len(xs), 4.0), squeeze=False)
    for ax, x in zip(axes[0], xs):
        xrows = [r for r in rows if r["x"] == x]
        for cls in classes_of(xrows):
            pts = sorted((r for r in xrows if r["class"] == cls), key=lambda r: looks_of(r["series"]))
            k = [looks_of(r["series"]) for r in pts]
            y = [float(r["error_pct"]) for r in pts]
            lo = [float(r["error_pct"]) - float(r["ci_low_pct"]) for r in pts]
            hi = [float(r["ci_high_pct"]) - float(r["error_pct"]) for r in pts]
            style = (dict(lw=2.5, color="black") if cls == "all" else
                     dict(lw=2.0, ls="--", color="black") if cls == "mine_vs_non_mine" else
                     dict(lw=1.2))
            ax.errorbar(k, y, yerr=[lo, hi], marker="o", ms=3, capsize=2, label=cls, **style)
        ax.set_xticks(sorted({looks_of(r["series"]) for r in xrows}))
        finish_percent_axis(ax, f"{name} at {x} cm: looks fused", "looks", 7)
        ax.set_xlabel("looks fused")
        ax.set_ylabel("error (%)")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, f"{name}_looks.png"), dpi=DPI)
    plt.close(fig)


def plot_aspect(rows, out_dir):
    groups = series_of([r for r in rows if r["x_name"] == "aspect_deg"])
    if not groups:
        return
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for series, srows in groups.items():
        x, y, lo, hi = curve(srows, "all", "aspect_deg")
        overall = [r for r in rows if r["series"] == series and r["class"] == "all"
                   and r["x_name"] != "aspect_deg"]
        label = series
        if overall:
            label += f" (overall {float(overall[0]['error_pct']):.1f} %)"
        ax.errorbar(x, y, yerr=[lo, hi], marker="o", ms=3, capsize=2, label=label)
    ax.set_xlabel(X_LABEL["aspect_deg"])
    ax.set_ylabel("misidentification (%)")
    ax.set_xticks(range(0, 361, 45))
    ax.set_ylim(0, None)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("error against aspect: one subspace vs aspect-sector subspaces")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "aspect.png"), dpi=DPI)
    plt.close(fig)


def plot_confusion(name, path, out_dir):
    rows = read_rows(path)
    mats = OrderedDict()
    for r in rows:
        key = (r["series"], r["x_name"], float(r["x"]))
        mats.setdefault(key, defaultdict(int))[(r["truth"], r["predicted"])] += int(r["count"])
    if not mats:
        return
    n = len(mats)
    cols = min(n, 5)
    nrows = (n + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(2.6 * cols, 2.6 * nrows), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, ((series, x_name, x), m) in zip(axes.flat, mats.items()):
        truths = list(OrderedDict.fromkeys(t for t, _ in m))
        preds = list(OrderedDict.fromkeys(p for _, p in m))
        # predictions in the truth order, so that the diagonal is the correct answers
        preds = [t for t in truths if t in preds] + [p for p in preds if p not in truths]
        grid = []
        for t in truths:
            total = sum(m[(t, p)] for p in preds) or 1
            grid.append([m[(t, p)] / total for p in preds])
        ax.axis("on")
        ax.imshow(grid, vmin=0, vmax=1, cmap="Blues")
        ax.set_xticks(range(len(preds)))
        ax.set_xticklabels([p[:4] for p in preds], fontsize=6, rotation=90)
        ax.set_yticks(range(len(truths)))
        ax.set_yticklabels([t[:4] for t in truths], fontsize=6)
        for i, row in enumerate(grid):
            for j, v in enumerate(row):
                if v >= 0.05:
                    ax.text(j, i, f"{100 * v:.0f}", ha="center", va="center", fontsize=5,
                            color="white" if v > 0.6 else "black")
        ax.set_title(f"{series} {x_name}={x:g}".strip(), fontsize=7)
    fig.suptitle(f"{name}: confusion (rows: truth, % of row)", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, f"{name}_confusion.png"), dpi=DPI)
    plt.close(fig)


def plot_ablation(rows, out_dir):
    """One panel per resolution: error of each pre-processing variant, overall and per seabed."""
    rows = [r for r in rows if r["x_name"] == "resolution_cm"]
    xs = sorted({float(r["x"]) for r in rows})
    variants = list(series_of(rows).keys())
    kinds = ["all"] + [c for c in classes_of(rows) if c.startswith("seabed_")]
    ncols = min(3, len(xs))
    nrows = (len(xs) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols,
                             figsize=(6.5 * ncols, (0.45 * len(variants) + 1.8) * nrows),
                             squeeze=False, sharey=True)
    for ax in axes.flat[len(xs):]:
        ax.set_visible(False)
    height = 0.8 / len(kinds)
    for ax, x in zip(axes.flat, xs):
        for k, kind in enumerate(kinds):
            ys, vals, errs = [], [], [[], []]
            for i, v in enumerate(variants):
                sel = [r for r in rows if r["series"] == v and r["class"] == kind
                       and float(r["x"]) == x]
                if not sel:
                    continue
                e = float(sel[0]["error_pct"])
                ys.append(i + (k - (len(kinds) - 1) / 2) * height)
                vals.append(e)
                errs[0].append(e - float(sel[0]["ci_low_pct"]))
                errs[1].append(float(sel[0]["ci_high_pct"]) - e)
            style = dict(color="black") if kind == "all" else {}
            ax.barh(ys, vals, height=height, xerr=errs, capsize=2, label=kind, **style)
        ax.set_yticks(range(len(variants)))
        ax.set_yticklabels(variants, fontsize=7)
        ax.invert_yaxis()
        ax.set_xlabel("misidentification (%)")
        ax.set_title(f"ablation at {x:g} cm", fontsize=9)
        ax.grid(alpha=0.3, axis="x")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "ablation.png"), dpi=DPI)
    plt.close(fig)


def finish_percent_axis(ax, title, x_name, legend_size):
    """Title, x label, a 0-based percentage y axis, grid and legend of one panel."""
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(X_LABEL.get(x_name, x_name))
    ax.set_ylabel("%")
    ax.set_ylim(0, None)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=legend_size)


def plot_overall(name, rows, out_dir, extra=()):
    """One panel of the overall error per series against x, then one panel per extra row class
    (e.g. open_set's unknown_accepted and false_reject): for experiments whose series are
    variants of one method (fusion, open_set)."""
    rows = [r for r in rows if r["x_name"] != "aspect_deg"]
    x_name = rows[0]["x_name"]
    kinds = ["all"] + [k for k in extra if any(r["class"] == k for r in rows)]
    fig, axes = plt.subplots(1, len(kinds), figsize=(6.0 * len(kinds), 4.2), squeeze=False)
    titles = {"all": "misidentification", "unknown_accepted": "held-out type accepted",
              "false_reject": "known types rejected"}
    for ax, kind in zip(axes[0], kinds):
        for series, srows in series_of(rows).items():
            x, y, lo, hi = curve(srows, kind, x_name)
            if x:
                ax.errorbar(x, y, yerr=[lo, hi], marker="o", ms=3, capsize=2, label=series)
        finish_percent_axis(ax, f"{name}: {titles.get(kind, kind)}", x_name, 6)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, f"{name}.png"), dpi=DPI)
    plt.close(fig)


def plot_speed_accuracy(tables, out_dir):
    """Render and classification time per chip against accuracy (fig11 across R, p across p)."""
    pts = []  # (label, render_ms, classify_ms, accuracy_pct, kind)
    for name, rows in tables.items():
        if name not in ("fig11", "p"):
            continue
        for r in rows:
            if r["class"] != "all" or r["x_name"] == "aspect_deg":
                continue
            acc = 100.0 - float(r["error_pct"])
            label = (f"{float(r['x']):g} cm" if r["x_name"] == "resolution_cm"
                     else f"p={float(r['x']):g}")
            pts.append((label, float(r["render_ms_per_chip"]), float(r["classify_ms_per_chip"]),
                        acc, name))
    if not pts:
        return
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    for ax, idx, what in ((axes[0], 1, "render"), (axes[1], 2, "classification")):
        for kind, marker in (("fig11", "o"), ("p", "s")):
            sel = [p for p in pts if p[4] == kind]
            if not sel:
                continue
            ax.scatter([p[idx] for p in sel], [p[3] for p in sel], marker=marker,
                       label="across resolution (fig11)" if kind == "fig11" else "across p (5 cm)")
            for p in sel:
                ax.annotate(p[0], (p[idx], p[3]), fontsize=6, xytext=(3, 2),
                            textcoords="offset points")
        ax.set_xscale("log")
        ax.set_xlabel(f"{what} time per chip (ms{', thread-seconds' if idx == 1 else ''})")
        ax.set_ylabel("correct identification (%)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("speed against accuracy", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "speed_accuracy.png"), dpi=DPI)
    plt.close(fig)


def compare(out_png, specs):
    """Overall error of the same experiments in several output folders, one panel each."""
    runs = []
    for spec in specs:
        label, sep, folder = spec.partition("=")
        if not sep or not os.path.isdir(folder):
            print(f"plot_sweep: '{spec}' is not LABEL=DIR with DIR a folder", file=sys.stderr)
            return 2
        runs.append((label, folder))
    names = None
    for _, folder in runs:
        found = {f[:-4] for f in os.listdir(folder)
                 if f.endswith(".csv") and not f.endswith("_confusion.csv")}
        names = found if names is None else names & found
    panels = []
    for name in sorted(names or []):
        panels.append((name, "all"))
        if name == "fig13":
            panels.append((name, "mine_vs_non_mine"))
    if not panels:
        print("plot_sweep: the folders share no experiment", file=sys.stderr)
        return 1
    fig, axes = plt.subplots(1, len(panels), figsize=(6.0 * len(panels), 4.2), squeeze=False)
    for ax, (name, cls) in zip(axes[0], panels):
        for label, folder in runs:
            rows = read_rows(os.path.join(folder, f"{name}.csv"))
            x_name = rows[0]["x_name"]
            for series, srows in series_of(rows).items():
                x, y, lo, hi = curve(srows, cls, x_name)
                tag = label if not series else f"{label}: {series}"
                ax.errorbar(x, y, yerr=[lo, hi], marker="o", ms=3, capsize=2, label=tag)
        what = "mine / non-mine error" if cls == "mine_vs_non_mine" else "misidentification"
        finish_percent_axis(ax, f"{name}: {what}", x_name, 7)
    fig.tight_layout()
    fig.savefig(out_png, dpi=DPI)
    plt.close(fig)
    print(f"chart written to {out_png}")
    return 0


def main(argv):
    if len(argv) >= 4 and argv[1] == "--compare":
        return compare(argv[2], argv[3:])
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 2
    out_dir = argv[1]
    tables = OrderedDict()
    for fname in sorted(os.listdir(out_dir)):
        if fname.endswith(".csv") and not fname.endswith(("_confusion.csv", "_seabed.csv")):
            rows = read_rows(os.path.join(out_dir, fname))
            if rows:
                tables[fname[:-4]] = rows
    for name, rows in tables.items():
        if name == "aspect":
            plot_aspect(rows, out_dir)
        elif name == "ablation":
            plot_ablation(rows, out_dir)
        elif name in ("fusion", "fusion13"):
            plot_overall(name, rows, out_dir)
        elif name == "open_set":
            plot_overall(name, rows, out_dir, extra=("unknown_accepted", "false_reject"))
        else:
            plot_error_curves(name, rows, out_dir)
            if any(looks_of(r["series"]) for r in rows):
                plot_looks(name, rows, out_dir)
        per_seabed = os.path.join(out_dir, f"{name}_seabed.csv")
        if os.path.exists(per_seabed):
            plot_seabed(name, per_seabed, out_dir)
        conf = os.path.join(out_dir, f"{name}_confusion.csv")
        if os.path.exists(conf) and name != "aspect":
            plot_confusion(name, conf, out_dir)
    plot_speed_accuracy(tables, out_dir)
    print(f"charts written to {out_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
