#!/usr/bin/python3
"""Chart of `sonarloop bench` fidelity lines: speed (ms per ping) against accuracy, both
renderers on one chart.

usage: sonarloop bench --only fidelity | /usr/bin/python3 tools/plot_bench.py - fidelity.png
       /usr/bin/python3 tools/plot_bench.py bench.jsonl fidelity.png

One point per fidelity setting; colour = renderer (profile / raytrace), marker = seabed grid
spacing. Labels: raytrace "rays per bin x along-track rays"; profile "along-track lines,
march step (cm)" (and the heightfield level's spacing when coarser than the grid). Left: RMS dB
error on the seabed; middle: target shadow-edge error (bins); right: terrain shadow-edge error
(bins), all against time per ping on one thread. Needs Debian's python3-matplotlib (run with
/usr/bin/python3).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"profile": "tab:blue", "raytrace": "tab:red"}
MARKERS = {0.0125: "o", 0.025: "s", 0.05: "^", 0.1: "D"}


def label_of(r):
    if r.get("renderer") == "profile":
        text = f'{r["along_track_rays"]}, {r["march_step_m"] * 100:g}'
        if r.get("heightfield_spacing_m", r["grid_spacing_m"]) > r["grid_spacing_m"] + 1e-9:
            text += f' @{r["heightfield_spacing_m"] * 100:g}'
        return text
    return f'{r["rays_per_bin"]}x{r["along_track_rays"]}'


def main(argv):
    if len(argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    src = sys.stdin if argv[1] == "-" else open(argv[1], encoding="utf-8")
    rows = []
    for n, line in enumerate(src, 1):
        line = line.strip()
        if not line:
            continue
        try:
            obj = json.loads(line)
        except json.JSONDecodeError as e:
            sys.stderr.write(f"plot_bench: line {n} is not JSON: {e}\n")
            return 1
        if obj.get("bench") == "fidelity":
            obj.setdefault("renderer", "raytrace")  # lines of older versions
            rows.append(obj)
    if not rows:
        sys.stderr.write("plot_bench: no 'fidelity' lines in the input\n")
        return 1
    metrics = [("rms_db_error", "RMS error on the seabed (dB)"),
               ("shadow_edge_error_bins", "target shadow-edge error (bins)"),
               ("terrain_edge_error_bins", "terrain shadow-edge error (bins)")]
    metrics = [m for m in metrics if any(m[0] in r for r in rows)]
    fig, axes = plt.subplots(1, len(metrics), figsize=(6 * len(metrics), 5.5))
    if len(metrics) == 1:
        axes = [axes]
    for renderer in sorted({r["renderer"] for r in rows}):
        for grid in sorted({r["grid_spacing_m"] for r in rows}):
            sel = [r for r in rows if r["grid_spacing_m"] == grid and r["renderer"] == renderer]
            if not sel:
                continue
            kw = dict(marker=MARKERS.get(grid, "x"), linestyle="none",
                      color=COLOURS.get(renderer, "k"),
                      label=f"{renderer}, grid {grid * 100:g} cm")
            for ax, (key, _) in zip(axes, metrics):
                ax.plot([r["ms_per_ping"] for r in sel], [r.get(key, 0.0) for r in sel], **kw)
                for r in sel:
                    ax.annotate(label_of(r), (r["ms_per_ping"], r.get(key, 0.0)), fontsize=7,
                                xytext=(3, 3), textcoords="offset points",
                                color=COLOURS.get(renderer, "k"))
    ref = rows[0].get("reference", "")
    for ax, (key, title) in zip(axes, metrics):
        ax.set_xscale("log")
        ax.set_xlabel("time per ping (ms, one thread)")
        ax.set_ylabel(title)
        ax.set_title(title.split(" (")[0] + " vs " + ref, fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("sonarloop: speed against accuracy (raytrace: rays per bin x along-track rays; "
                 "profile: along-track lines, march step cm)")
    fig.tight_layout()
    fig.savefig(argv[2], dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
