#!/usr/bin/python3
"""Chart of `sonarloop bench` fidelity lines: speed (ms per ping) against accuracy.

usage: sonarloop bench --only fidelity | /usr/bin/python3 tools/plot_bench.py - fidelity.png
       /usr/bin/python3 tools/plot_bench.py bench.jsonl fidelity.png

Left: RMS dB error on the seabed against time per ping, one point per fidelity setting
(marker = seabed grid spacing, label = rays per bin x along-track rays). Right: shadow-edge
error in bins against time per ping. Needs Debian's python3-matplotlib (run with /usr/bin/python3).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


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
            rows.append(obj)
    if not rows:
        sys.stderr.write("plot_bench: no 'fidelity' lines in the input\n")
        return 1
    markers = {0.0125: "o", 0.025: "s", 0.05: "^", 0.1: "D"}
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5))
    for grid in sorted({r["grid_spacing_m"] for r in rows}):
        sel = [r for r in rows if r["grid_spacing_m"] == grid]
        kw = dict(marker=markers.get(grid, "x"), linestyle="none", label=f"grid {grid * 100:g} cm")
        ax1.plot([r["ms_per_ping"] for r in sel], [r["rms_db_error"] for r in sel], **kw)
        ax2.plot([r["ms_per_ping"] for r in sel], [r["shadow_edge_error_bins"] for r in sel], **kw)
        for r in sel:
            label = f'{r["rays_per_bin"]}x{r["along_track_rays"]}'
            ax1.annotate(label, (r["ms_per_ping"], r["rms_db_error"]), fontsize=7,
                         xytext=(3, 3), textcoords="offset points")
    ref = rows[0].get("reference", "")
    ax1.set_xscale("log")
    ax2.set_xscale("log")
    ax1.set_xlabel("time per ping (ms, one thread)")
    ax2.set_xlabel("time per ping (ms, one thread)")
    ax1.set_ylabel("RMS error on the seabed (dB)")
    ax2.set_ylabel("shadow-edge error (bins)")
    ax1.set_title("seabed intensity vs " + ref)
    ax2.set_title("shadow edge vs " + ref)
    for ax in (ax1, ax2):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("sonarloop: speed against accuracy (labels: rays per bin x along-track rays)")
    fig.tight_layout()
    fig.savefig(argv[2], dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
