#!/usr/bin/env python3
"""Stability of the onboard consumer against navigation error and altitude (issue 9, Sec. 4).

usage: /usr/bin/python3 tools/onboard_stability.py SCENARIO.yaml MODEL.slpca OUT_DIR
           [--sonarloop PATH] [--seeds N] [--study nav_noise|nav_drift|altitude ...]

For each level of a study, the scenario is rewritten (one key changed), flown with
`sonarloop run --rate max --classify MODEL` for seeds 1..N (the scenario's `seed`: navigation
noise, speckle, clutter), and every contact is matched to the nearest placed target within
MATCH_RADIUS_M of it (positions from the contacts' latitude / longitude, taken to the
scenario's plane by a local flat-earth approximation, millimetre-exact over a few hundred
metres). Per level it reports:
  detected        targets with a matched contact (of targets x seeds)
  identified      of those, with the right class
  mine_ok         of those, with the right mine / non-mine decision
  false_contacts  contacts matched to no target (per run)
  position_error  median and 90th percentile of the matched contacts' horizontal error (m)
Studies:
  nav_noise   vehicle.nav.position_noise_m 0, 0.1, 0.3, 1, 3 m (white; drift 0)
  nav_drift   vehicle.nav.position_drift_m_per_sqrt_s 0, 0.05, 0.2, 0.5, 1 (noise 0.1 m)
  altitude    vehicle.trajectory.depth.altitude_m 3, 5, 7.5, 10, 15 m (terrain following)
  roll        vehicle.trajectory.attitude.roll_amplitude_deg 0, 2, 5, 10, 20 (waves, 8 s period)
  pitch       vehicle.trajectory.attitude.pitch_amplitude_deg 0, 1, 2, 5, 10 (waves, 8 s period)
  range       the straight track moved sideways (start_m east -40 .. 40 m in 10 m steps), so
              that each target is seen at another ground range; reported per 10 m bin of the
              target's ground range from the track (0-10, ..., 40-50 m), not per offset
Writes OUT_DIR/onboard_stability.csv and, with matplotlib, onboard_stability.png.

example:
  build/tools/sonarloop dataset --out out/chips --count 320 --resolution-cm 5
  build/tools/sonarloop train out/chips --out out/atr.slpca --crop 0.4
  /usr/bin/python3 tools/onboard_stability.py config/default.yaml out/atr.slpca out/stab
Needs PyYAML (Debian python3-yaml).
"""
import argparse
import copy
import csv
import json
import math
import os
import subprocess
import sys

import yaml

MATCH_RADIUS_M = 3.0
DEFAULT_ORIGIN = (55.9, -3.2)  # config/reference.yaml: origin of a scenario that gives none
WGS84_A = 6378137.0
WGS84_F = 1.0 / 298.257223563
MINE_LIKE = {"manta", "rockan", "cylinder", "cuboid"}

STUDIES = {
    "nav_noise": ("position_noise_m", [0.0, 0.1, 0.3, 1.0, 3.0],
                  lambda s, v: nav(s).update(position_noise_m=v, position_drift_m_per_sqrt_s=0.0)),
    "nav_drift": ("position_drift_m_per_sqrt_s", [0.0, 0.05, 0.2, 0.5, 1.0],
                  lambda s, v: nav(s).update(position_noise_m=0.1, position_drift_m_per_sqrt_s=v)),
    "altitude": ("altitude_m", [3.0, 5.0, 7.5, 10.0, 15.0],
                 lambda s, v: s["vehicle"]["trajectory"].setdefault("depth", {}).update(
                     mode="altitude", altitude_m=v)),
    "roll": ("roll_amplitude_deg", [0.0, 2.0, 5.0, 10.0, 20.0],
             lambda s, v: attitude(s).update(roll_amplitude_deg=v, wave_period_s=8.0)),
    "pitch": ("pitch_amplitude_deg", [0.0, 1.0, 2.0, 5.0, 10.0],
              lambda s, v: attitude(s).update(pitch_amplitude_deg=v, wave_period_s=8.0)),
    "range": ("track_east_m", [-40.0, -30.0, -20.0, -10.0, 0.0, 10.0, 20.0, 30.0, 40.0],
              lambda s, v: straight(s).update(start_m=[straight(s).get("start_m", [0.0, 0.0])[0], v])),
}
# the range study's bins of target ground range (m): [lo, hi)
RANGE_BINS = [(0.0, 10.0), (10.0, 20.0), (20.0, 30.0), (30.0, 40.0), (40.0, 50.0)]


def attitude(s):
    return s["vehicle"]["trajectory"].setdefault("attitude", {})


def straight(s):
    t = s["vehicle"]["trajectory"]
    if t.get("kind", "straight") != "straight":
        raise SystemExit("the range study needs a straight trajectory (vehicle.trajectory.kind)")
    return t


def ground_range_m(scenario, position):
    """Horizontal distance from a target to the straight track's line."""
    t = scenario["vehicle"]["trajectory"]
    n0, e0 = t.get("start_m", [0.0, 0.0])
    h = math.radians(t.get("heading_deg", 0.0))
    dn, de = position[0] - n0, position[1] - e0
    return abs(-dn * math.sin(h) + de * math.cos(h))


def nav(s):
    return s["vehicle"].setdefault("nav", {})


def to_plane(lat, lon, lat0, lon0):
    """Latitude / longitude to north / east metres about (lat0, lon0), flat earth with the WGS84
    meridian and prime-vertical radii at lat0."""
    e2 = WGS84_F * (2.0 - WGS84_F)
    s = math.sin(math.radians(lat0))
    w = math.sqrt(1.0 - e2 * s * s)
    r_meridian = WGS84_A * (1.0 - e2) / (w ** 3)
    r_normal = WGS84_A / w
    north = math.radians(lat - lat0) * r_meridian
    east = math.radians(lon - lon0) * r_normal * math.cos(math.radians(lat0))
    return north, east


def run_once(sonarloop, scenario, model, workdir, tag):
    path = os.path.join(workdir, f"{tag}.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(scenario, f, sort_keys=False)
    contacts = os.path.join(workdir, f"{tag}.jsonl")
    cmd = [sonarloop, "run", path, "--rate", "max", "--quiet", "--classify", model,
           "--contacts", contacts]
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {done.stderr.strip()[-500:]}")
    with open(contacts) as f:
        return [json.loads(line) for line in f if line.strip()]


def score(scenario, contacts):
    origin = scenario.get("origin") or {}
    # the loader's defaults (config/reference.yaml)
    lat0 = origin.get("latitude_deg", DEFAULT_ORIGIN[0])
    lon0 = origin.get("longitude_deg", DEFAULT_ORIGIN[1])
    targets = [(t["type"], t["position_m"]) for t in scenario.get("targets", [])]
    best = {}  # target index -> (error, contact)
    false_contacts = 0
    for c in contacts:
        if c.get("latitude_deg") is None:
            continue
        n, e = to_plane(c["latitude_deg"], c["longitude_deg"], lat0, lon0)
        errs = [math.hypot(n - p[0], e - p[1]) for _, p in targets]
        i = min(range(len(errs)), key=errs.__getitem__) if errs else -1
        if i < 0 or errs[i] > MATCH_RADIUS_M:
            false_contacts += 1
            continue
        if i not in best or errs[i] < best[i][0]:
            best[i] = (errs[i], c)
    rows = []
    for i, (kind, _) in enumerate(targets):
        if i not in best:
            rows.append((kind, False, False, False, None))
            continue
        err, c = best[i]
        cls = c.get("class")
        mine = c.get("mine_like")
        rows.append((kind, True, cls == kind, mine is not None and mine == (kind in MINE_LIKE), err))
    return rows, false_contacts


def quantile(v, q):
    v = sorted(v)
    if not v:
        return float("nan")
    k = min(len(v) - 1, max(0, int(math.ceil(q * len(v))) - 1))
    return v[k]


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__)
    ap.add_argument("scenario")
    ap.add_argument("model")
    ap.add_argument("out_dir")
    ap.add_argument("--sonarloop", default="build/tools/sonarloop")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--study", action="append", choices=sorted(STUDIES))
    a = ap.parse_args(argv[1:])
    if a.seeds < 1:
        ap.error("--seeds must be >= 1")
    with open(a.scenario) as f:
        base = yaml.safe_load(f)
    os.makedirs(a.out_dir, exist_ok=True)
    work = os.path.join(a.out_dir, "runs")
    os.makedirs(work, exist_ok=True)
    out_rows = []

    def report(study, key, level, runs, results, falses):
        n = len(results)
        det = [r for r in results if r[1]]
        errs = [r[4] for r in det]
        row = {
            "study": study, "key": key, "level": level, "runs": runs, "targets": n,
            "detected": len(det), "identified": sum(r[2] for r in det),
            "mine_ok": sum(r[3] for r in det),
            "false_contacts_per_run": falses / runs,
            "position_error_median_m": quantile(errs, 0.5),
            "position_error_p90_m": quantile(errs, 0.9),
        }
        out_rows.append(row)
        print(f"{study:9s} {key}={level:<5g} detected {row['detected']}/{n}, identified "
              f"{row['identified']}, mine/non-mine right {row['mine_ok']}, false "
              f"{row['false_contacts_per_run']:.1f}/run, position error median "
              f"{row['position_error_median_m']:.2f} m, p90 {row['position_error_p90_m']:.2f} m",
              flush=True)

    for study in a.study or ["nav_noise", "nav_drift", "altitude"]:
        key, levels, apply = STUDIES[study]
        by_bin = {b: ([], 0) for b in RANGE_BINS}  # range study: (results, runs seen)
        falses_all, runs_all = 0, 0
        for level in levels:
            results, falses = [], 0
            for seed in range(1, a.seeds + 1):
                sc = copy.deepcopy(base)
                sc["seed"] = seed
                apply(sc, level)
                rows, f = score(sc, run_once(a.sonarloop, sc, a.model, work,
                                             f"{study}_{level:g}_{seed}"))
                results += rows
                falses += f
                if study == "range":
                    for (kind, pos), r in zip([(t["type"], t["position_m"])
                                               for t in sc.get("targets", [])], rows):
                        g = ground_range_m(sc, pos)
                        for b in RANGE_BINS:
                            if b[0] <= g < b[1]:
                                by_bin[b][0].append(r)
            if study != "range":
                report(study, key, level, a.seeds, results, falses)
            falses_all += falses
            runs_all += a.seeds
        if study == "range":
            for b in RANGE_BINS:
                if by_bin[b][0]:
                    report(study, "ground_range_m", 0.5 * (b[0] + b[1]), runs_all, by_bin[b][0],
                           falses_all)
    csv_path = os.path.join(a.out_dir, "onboard_stability.csv")
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(out_rows[0].keys()))
        w.writeheader()
        w.writerows(out_rows)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"wrote {csv_path} (no matplotlib: no chart)")
        return 0
    studies = list(dict.fromkeys(r["study"] for r in out_rows))
    fig, axes = plt.subplots(2, len(studies), figsize=(5.0 * len(studies), 7.0), squeeze=False)
    for j, study in enumerate(studies):
        rows = [r for r in out_rows if r["study"] == study]
        x = [r["level"] for r in rows]
        ax = axes[0][j]
        for k, label in (("detected", "detected"), ("identified", "identified"),
                         ("mine_ok", "mine / non-mine right")):
            ax.plot(x, [100.0 * r[k] / r["targets"] for r in rows], marker="o", label=label)
        ax.set_ylim(0, 105)
        ax.set_ylabel("% of targets")
        ax.set_title(f"onboard: {study}", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        ax = axes[1][j]
        ax.plot(x, [r["position_error_median_m"] for r in rows], marker="o", label="median")
        ax.plot(x, [r["position_error_p90_m"] for r in rows], marker="s", label="90 %")
        ax.set_xlabel(rows[0]["key"])
        ax.set_ylabel("contact position error (m)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    png = os.path.join(a.out_dir, "onboard_stability.png")
    fig.savefig(png, dpi=90)
    print(f"wrote {csv_path} and {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
