#!/usr/bin/python3
"""Tables and charts of survey scores (`sonarloop mission --out DIR`, docs/autonomy.md).

usage: tools/plot_survey.py --out docs/autonomy DIR[=LABEL] ...

Each DIR is a lock-step mission's --out folder (survey.csv, detector_froc.csv and, with a model
that has contact gates, gate_froc.csv). Prints, in Markdown, the pooled table of every DIR (one
row per DIR: probability of detection, identification and mine / non-mine error of the detected,
false contacts per km² and per target, with 95 % Wilson intervals) and the per-seabed rows of all
DIRs pooled together, and writes:
  OUT/survey_froc.png       detection against false contacts per km², over the detector's
                            threshold (dashed) and over the contact gate's (solid), per DIR
  OUT/survey_by_seabed.png  Pd, identification and mine / non-mine error per seabed kind, with
                            their intervals, all DIRs pooled
"""
import argparse
import collections
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

Z95 = 1.959963984540054


def wilson(x, n):
    """The Wilson score interval (atr/confusion.h), as (lo, hi); n = 0 gives (0, 1)."""
    if n == 0:
        return 0.0, 1.0
    p = x / n
    d = 1 + Z95 * Z95 / n
    c = (p + Z95 * Z95 / (2 * n)) / d
    h = Z95 / d * math.sqrt(p * (1 - p) / n + Z95 * Z95 / (4 * n * n))
    return max(0.0, c - h), min(1.0, c + h)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def load(spec):
    path, _, label = spec.partition("=")
    return label or os.path.basename(os.path.normpath(path)), path


def rate(x, n):
    lo, hi = wilson(x, n)
    return "%.1f %% [%.1f, %.1f]" % (100.0 * x / n, 100 * lo, 100 * hi) if n else "-"


COUNTS = ("surveys", "targets", "covered", "detected", "identified", "mine_wrong",
          "false_contacts")


def counts_of(row):
    c = {k: int(row[k]) for k in COUNTS}
    c["area_km2"] = float(row["area_km2"])
    return c


def row_text(label, c):
    return "| %s | %s | %d / %d = %s | %s | %s | %d | %.0f | %.2f |" % (
        label, c["surveys"] or "", c["detected"], c["covered"], rate(c["detected"], c["covered"]),
        rate(c["identified"], c["detected"]), rate(c["mine_wrong"], c["detected"]),
        c["false_contacts"], c["false_contacts"] / c["area_km2"] if c["area_km2"] else 0.0,
        c["false_contacts"] / c["targets"] if c["targets"] else 0.0)


HEADER = ["| | surveys | detected / covered (Pd) | identified (of detected) | "
          "mine / non-mine error | false contacts | per km² | per target |",
          "|---|---|---|---|---|---|---|---|"]


def tables(dirs):
    out = HEADER[:]
    pooled = collections.defaultdict(lambda: collections.Counter())
    for label, d in dirs:
        rows = {r["scope"]: r for r in read_csv(os.path.join(d, "survey.csv"))}
        out.append(row_text(label, counts_of(rows["all"])))
        for scope, r in rows.items():
            if scope.startswith("seabed:") or scope == "all":
                pooled[scope].update(counts_of(r))
    out += ["", "All together, by seabed kind:", ""] + HEADER
    for scope in sorted(pooled):
        out.append(row_text(scope.replace("seabed:", ""), pooled[scope]))
    return "\n".join(out), pooled


def froc_chart(dirs, path):
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for i, (label, d) in enumerate(dirs):
        color = "C%d" % i
        for name, style, what in (("detector_froc.csv", "--", "detector"),
                                  ("gate_froc.csv", "-", "gate")):
            f = os.path.join(d, name)
            if not os.path.exists(f):
                continue
            rows = read_csv(f)
            xs = [float(r["false_per_km2"]) for r in rows]
            ys = [100 * float(r["pd"]) for r in rows]
            ax.plot(xs, ys, style, color=color, label="%s (%s)" % (label, what))
    ax.set_xscale("symlog", linthresh=10)
    ax.set_xlabel("false contacts per km²")
    ax.set_ylabel("targets detected (%)")
    ax.set_ylim(0, 102)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="lower right")
    ax.set_title("FROC: over the detector's threshold (dashed), the contact gate's (solid)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def seabed_chart(pooled, path):
    kinds = sorted(k for k in pooled if k.startswith("seabed:"))
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    width = 0.27
    for j, (key, num, den, name) in enumerate((
            ("pd", "detected", "covered", "detected (Pd)"),
            ("id", "identified", "detected", "identified"),
            ("mine", "mine_wrong", "detected", "mine / non-mine error"))):
        xs, ys, lo, hi = [], [], [], []
        for i, k in enumerate(kinds):
            c = pooled[k]
            n = c[den]
            p = c[num] / n if n else 0.0
            a, b = wilson(c[num], n)
            xs.append(i + (j - 1) * width)
            ys.append(100 * p)
            lo.append(100 * (p - a))
            hi.append(100 * (b - p))
        ax.bar(xs, ys, width, yerr=[lo, hi], capsize=3, label=name)
    ax.set_xticks(range(len(kinds)))
    ax.set_xticklabels([k.replace("seabed:", "") for k in kinds])
    ax.set_ylabel("%")
    ax.set_ylim(0, 105)
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=8)
    ax.set_title("Per seabed kind, all surveys pooled (95 % Wilson intervals)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", required=True, help="folder for the charts")
    p.add_argument("dirs", nargs="+", help="DIR or DIR=LABEL (a mission's --out)")
    a = p.parse_args()
    dirs = [load(s) for s in a.dirs]
    os.makedirs(a.out, exist_ok=True)
    text, pooled = tables(dirs)
    print(text)
    froc_chart(dirs, os.path.join(a.out, "survey_froc.png"))
    seabed_chart(pooled, os.path.join(a.out, "survey_by_seabed.png"))
    print("wrote", os.path.join(a.out, "survey_froc.png"), "and",
          os.path.join(a.out, "survey_by_seabed.png"))


if __name__ == "__main__":
    main()
