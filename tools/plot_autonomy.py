#!/usr/bin/python3
"""Charts and tables of `sonarloop mission` reports (docs/autonomy.md).

usage: tools/plot_autonomy.py --out docs/autonomy REPORT.json[=LABEL] ...

Prints the with/without table (Markdown) of the reports and writes OUT/accuracy_vs_time.png:
per scenario, the fraction of targets confirmed right and identified against the mission's
duration relative to its survey's, one point per report (e.g. the survey without re-looks and
the mission with them, or one per re-look setting). A lock-step report of several seeds counts
them all (its pooled "summary"; mission times are then per mission, the mean over the seeds).
"""
import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def pool(missions):
    """The missions' summaries added up, as `mission` pools them (mission/mission_report.cpp)."""
    s = {}
    for m in missions:
        for key, value in m["summary"].items():
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                continue
            s[key] = s.get(key, 0) + value
    n = max(1, s.get("relooks_passed", 0))
    for key in ("aspect_change_mean_deg", "pass_range_mean_m"):
        s[key] = sum(m["summary"][key] * m["summary"]["relooks_passed"] for m in missions) / n
    s["latency_mean_s"] = sum(m["summary"]["latency_mean_s"] * m["summary"]["relooks"]
                              for m in missions) / max(1, s.get("relooks", 0))
    s["latency_max_s"] = max(m["summary"]["latency_max_s"] for m in missions)
    return s


def load(spec):
    path, _, label = spec.partition("=")
    with open(path) as f:
        report = json.load(f)
    agent = report["agent"] if "agent" in report else report["missions"][0]["agent"]
    if not label:
        run = report.get("run", {})
        label = "no re-looks" if not run.get("relooks", True) else (
            "threshold %g" % agent["threshold"])
    # per mission: the pooled times over the missions (a report without the pooled summary,
    # written before it had one: its missions' summaries added up)
    s = dict(report["summary"]) if "summary" in report else pool(report["missions"])
    n = len(report.get("missions", [])) or 1
    for key in ("mission_time_s", "distance_m", "relook_distance_m", "relook_time_s",
                "wall_time_s"):
        s[key] = s[key] / n
    s["missions"] = n
    report = dict(report, summary=s)
    return label, report


def pct(n, d):
    return "%d / %d (%.0f %%)" % (n, d, 100.0 * n / d) if d else "-"


def table(reports):
    rows = [
        ("targets detected", lambda s: pct(s["detected"], s["targets"])),
        ("correctly identified (final class)", lambda s: pct(s["identified"], s["targets"])),
        ("confirmed and correctly identified", lambda s: pct(s["confirmed_correct"], s["targets"])),
        ("correctly mine / non-mine", lambda s: pct(s["mine_correct"], s["targets"])),
        ("objects confirmed / reported", lambda s: "%d / %d" % (s["confirmed"], s["objects"])),
        ("false contacts (objects at no target)", lambda s: "%d" % s["false_contacts"]),
        ("re-looks (passed, object seen again)", lambda s: "%d (%d, %d)" % (
            s["relooks"], s["relooks_passed"], s["relooks_second_look"])),
        ("aspect change / pass range of re-looks", lambda s: "%.1f° / %.1f m" % (
            s["aspect_change_mean_deg"], s["pass_range_mean_m"]) if s["relooks_passed"] else "-"),
        ("mission time (distance), per mission", lambda s: "%.0f s (%.0f m)" % (
            s["mission_time_s"], s["distance_m"])),
        ("extra distance and time on re-looks, per mission", lambda s: "%.0f m, %.0f s" % (
            s["relook_distance_m"], s["relook_time_s"])),
        ("latency ping abeam -> new waypoint, mean (max)", lambda s: "%.1f s (%.1f s)" % (
            s["latency_mean_s"], s["latency_max_s"]) if s["relooks"] else "-"),
        ("missions (seeds)", lambda s: "%d" % s["missions"]),
        ("wall time", lambda s: "%.0f s" % s["wall_time_s"] if s["wall_time_s"] else
         "- (lock-step)"),
    ]
    out = ["| | " + " | ".join(label for label, _ in reports) + " |",
           "|---|" + "---|" * len(reports)]
    for name, f in rows:
        out.append("| " + name + " | " + " | ".join(f(r["summary"]) for _, r in reports) + " |")
    return "\n".join(out)


def chart(reports, path):
    """Per scenario (the reports' run.scenario), its reports joined in order of mission time:
    the share of targets confirmed and right, and identified, against the mission time relative
    to the scenario's shortest report (its survey without re-looks)."""
    groups = {}
    for label, r in reports:
        name = r.get("run", {}).get("scenario", label)
        groups.setdefault(name, []).append((label, r))
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharex=True)
    keys = [("confirmed_correct", "confirmed and correctly identified"),
            ("identified", "correctly identified (final class)")]
    for ax, (key, title) in zip(axes, keys):
        for name, members in groups.items():
            pts = sorted((r["summary"]["mission_time_s"], r["summary"][key] / r["summary"]["targets"])
                         for _, r in members)
            t0 = pts[0][0]
            ax.plot([p[0] / t0 for p in pts], [100 * p[1] for p in pts], marker="o", label=name)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("mission time / the survey's")
        ax.set_ylim(0, 105)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("targets (%)")
    # issue 24's goal: 95 % confirmed and right within 1.5 times the survey's time
    axes[0].axhline(95, color="gray", ls="--", lw=1)
    axes[0].axvline(1.5, color="gray", ls=":", lw=1)
    axes[1].legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", required=True, help="folder for accuracy_vs_time.png")
    p.add_argument("reports", nargs="+", help="REPORT.json or REPORT.json=LABEL")
    a = p.parse_args()
    reports = [load(s) for s in a.reports]
    os.makedirs(a.out, exist_ok=True)
    print(table(reports))
    chart(reports, os.path.join(a.out, "accuracy_vs_time.png"))
    print("wrote", os.path.join(a.out, "accuracy_vs_time.png"))


if __name__ == "__main__":
    main()
