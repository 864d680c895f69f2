#!/usr/bin/python3
"""The soak test (issue 11 §2, docs/reliability.md): `sonarloop run` in real time for an hour (or
--duration) on a long survey, with everything a rig attaches, all on 127.0.0.1:

  - the ping stream over UDP to `sonarloop onboard --listen` (the onboard consumer),
  - navigation over a socketcand server to a python-can client (python3-can, interface
    "socketcand") that receives every frame for the whole run,
  - `--record` of pings.xtf, nav.log (candump) and truth.csv,
  - optionally N CPU hogs (busy loops) and `--realtime-priority`, to measure what a busy
    neighbour does to the deadlines, with and without real-time priority.

It samples the resident memory (VmRSS) of the emulator and of the consumer every 10 s, and at
the end checks that everything recorded decodes: every XTF packet (read back by `sonarloop
onboard --xtf`), every candump line (python-can's CanutilsLogReader), every truth.csv line. The
simulated clock's drift against the wall clock is measured outside the emulator: each frame
python-can receives carries its simulation time (UTC of the frame's sim time, the socketcand
timestamp); the smallest (arrival wall time - frame time) of each minute is that minute's
offset, and the drift is the last minute's offset minus the first's.

Writes OUT/soak.json and prints a table. Exit status 0 when nothing was lost or torn (every
recorded ping and frame decodes, the consumer lost no ping, python-can received every frame),
1 otherwise; deadline misses, lateness, RSS and drift are reported, not judged.

usage: /usr/bin/python3 tools/soak.py --out DIR [--duration S] [--scenario YAML]
           [--sonarloop BIN] [--model FILE] [--hogs N] [--realtime-priority N]
           [--lateness-tolerance-ms MS] [--threads N]
examples:
  /usr/bin/python3 tools/soak.py --out out/soak                      # the hour
  /usr/bin/python3 tools/soak.py --out out/hog --duration 300 --hogs 1
  /usr/bin/python3 tools/soak.py --out out/hog_rt --duration 300 --hogs 1 --realtime-priority 50
"""
import argparse
import json
import logging
import os
import re
import signal
import subprocess
import sys
import threading
import time

import can

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
logging.getLogger("can.interfaces.socketcand.socketcand").setLevel(logging.ERROR)


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", required=True, help="output directory (created)")
    p.add_argument("--duration", type=float, default=3600.0, help="simulated = wall seconds")
    p.add_argument("--scenario", default=os.path.join(ROOT, "config", "soak_1km2.yaml"))
    p.add_argument("--sonarloop", default=os.path.join(ROOT, "build", "tools", "sonarloop"))
    p.add_argument("--model", help="classifier model (default: one trained here, ~20 s)")
    p.add_argument("--hogs", type=int, default=0, help="CPU hogs (busy loops) during the run")
    p.add_argument("--realtime-priority", type=int, help="passed to `sonarloop run`")
    p.add_argument("--lateness-tolerance-ms", type=float, help="passed to `sonarloop run`")
    p.add_argument("--threads", type=int, default=2, help="render threads (default 2)")
    return p.parse_args()


def run_checked(cmd, log_path):
    with open(log_path, "w") as log:
        rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT)
    if rc != 0:
        sys.exit(f"soak: {' '.join(cmd)} failed with {rc}; see {log_path}")


def train_model(args):
    chips = os.path.join(args.out, "chips")
    model = os.path.join(args.out, "atr.slpca")
    run_checked([args.sonarloop, "dataset", "--out", chips, "--count", "100", "--resolution-cm",
                 "5", "--seed", "1", "--threads", "2", "--seabed", args.scenario],
                os.path.join(args.out, "dataset.log"))
    run_checked([args.sonarloop, "train", chips, "--out", model, "--aspect-sectors", "4", "--p",
                 "10"], os.path.join(args.out, "train.log"))
    return model


def start_and_wait_for(cmd, err_path, pattern, timeout_s=300):
    """Starts cmd with stderr to err_path; returns (process, match) once pattern appears."""
    err = open(err_path, "w")
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        with open(err_path) as f:
            m = re.search(pattern, f.read())
        if m:
            return proc, m
        if proc.poll() is not None:
            break
        time.sleep(0.05)
    proc.kill()
    with open(err_path) as f:
        sys.exit(f"soak: {cmd[1]} did not start ({pattern!r} not seen):\n{f.read()}")


def rss_kib(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return None


class Sampler(threading.Thread):
    """VmRSS of each named pid every `period_s`, until stopped."""

    def __init__(self, pids, period_s=10.0):
        super().__init__(daemon=True)
        self.pids, self.period_s = pids, period_s
        self.samples = {name: [] for name in pids}
        self.stop = threading.Event()

    def run(self):
        t0 = time.monotonic()
        while not self.stop.is_set():
            for name, pid in self.pids.items():
                r = rss_kib(pid)
                if r is not None:
                    self.samples[name].append((round(time.monotonic() - t0, 1), r))
            self.stop.wait(self.period_s)


class CanClient(threading.Thread):
    """python-can on the socketcand server: counts frames, keeps each minute's smallest
    (arrival wall time - frame time) offset."""

    def __init__(self, port):
        super().__init__(daemon=True)
        self.bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can0")
        self.frames = 0
        self.min_offset_by_minute = {}
        self.first_frame_time = None
        self.stop = threading.Event()

    def run(self):
        while not self.stop.is_set():
            msg = self.bus.recv(timeout=0.2)
            if msg is None:
                continue
            now = time.time()
            self.frames += 1
            if self.first_frame_time is None:
                self.first_frame_time = msg.timestamp
            minute = int((msg.timestamp - self.first_frame_time) // 60)
            offset = now - msg.timestamp
            best = self.min_offset_by_minute.get(minute)
            if best is None or offset < best:
                self.min_offset_by_minute[minute] = offset
        self.bus.shutdown()


def decode_candump(path):
    """Frames python-can reads from a candump log, and lines that are not frames."""
    frames = 0
    with open(path) as f:
        lines = sum(1 for line in f if line.strip())
    for _ in can.CanutilsLogReader(path):
        frames += 1
    return frames, lines


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    model = args.model or train_model(args)
    rec = os.path.join(args.out, "rec")

    onboard, m = start_and_wait_for(
        [args.sonarloop, "onboard", "--listen", "127.0.0.1:0", "--model", model, "--contacts",
         os.path.join(args.out, "contacts.jsonl"), "--stats-json",
         os.path.join(args.out, "onboard.json"), "--scenario", args.scenario],
        os.path.join(args.out, "onboard.err"), r"listening on 127\.0\.0\.1:(\d+) ")
    udp_port = int(m.group(1))

    hogs = [subprocess.Popen(["/usr/bin/python3", "-c", "while True: pass"])
            for _ in range(args.hogs)]
    cmd = [args.sonarloop, "run", args.scenario, "--duration", str(args.duration), "--threads",
           str(args.threads), "--udp", f"127.0.0.1:{udp_port}", "--can",
           "socketcand:127.0.0.1:0", "--record", rec, "--stats-json",
           os.path.join(args.out, "run.json"), "--stats-every", "60"]
    if args.realtime_priority is not None:
        cmd += ["--realtime-priority", str(args.realtime_priority)]
    if args.lateness_tolerance_ms is not None:
        cmd += ["--lateness-tolerance-ms", str(args.lateness_tolerance_ms)]
    started = time.monotonic()
    run, m = start_and_wait_for(cmd, os.path.join(args.out, "run.err"),
                                r"socketcand server on 127\.0\.0\.1:(\d+)")
    client = CanClient(int(m.group(1)))
    client.start()
    sampler = Sampler({"run": run.pid, "onboard": onboard.pid})
    sampler.start()
    try:
        run_rc = run.wait()
    except KeyboardInterrupt:
        run.send_signal(signal.SIGINT)
        run_rc = run.wait()
    wall_s = time.monotonic() - started
    for h in hogs:
        h.kill()
        h.wait()
    time.sleep(2.0)  # the last datagrams and frames on their way
    client.stop.set()
    client.join(timeout=10)
    sampler.stop.set()
    sampler.join(timeout=15)
    onboard.send_signal(signal.SIGINT)
    onboard_rc = onboard.wait(timeout=120)

    with open(os.path.join(args.out, "run.json")) as f:
        rs = json.load(f)
    with open(os.path.join(args.out, "onboard.json")) as f:
        ob = json.load(f)
    # read back: every ping of the recording (the consumer on the file), every candump line
    file_stats = os.path.join(args.out, "onboard_file.json")
    run_checked([args.sonarloop, "onboard", "--xtf", os.path.join(rec, "pings.xtf"), "--model",
                 model, "--contacts", os.path.join(args.out, "contacts_file.jsonl"),
                 "--stats-json", file_stats, "--scenario", args.scenario],
                os.path.join(args.out, "onboard_file.log"))
    with open(file_stats) as f:
        fs = json.load(f)
    nav_frames, nav_lines = decode_candump(os.path.join(rec, "nav.log"))
    with open(os.path.join(rec, "truth.csv")) as f:
        truth_lines = [line for line in f]
    truth_torn = sum(1 for line in truth_lines if not line.endswith("\n"))

    offsets = client.min_offset_by_minute
    minutes = sorted(offsets)
    drift_ms = (offsets[minutes[-1]] - offsets[minutes[0]]) * 1e3 if len(minutes) > 1 else None

    def rss_summary(samples):
        if not samples:
            return {}
        # start: the first sample after the first minute (the scene and the first views made)
        after = [r for t, r in samples if t >= 60.0] or [r for _, r in samples]
        return {"start_mib": round(after[0] / 1024, 1), "end_mib": round(samples[-1][1] / 1024, 1),
                "max_mib": round(max(r for _, r in samples) / 1024, 1),
                "samples": len(samples)}

    sizes = {name: os.path.getsize(os.path.join(rec, name))
             for name in ("pings.xtf", "nav.log", "truth.csv")}
    pings, nav = rs["pings"], rs["nav"]
    receiver = ob["receiver"]
    report = {
        "duration_s": args.duration,
        "wall_s": round(wall_s, 3),
        "hogs": args.hogs,
        "realtime": rs.get("realtime", "normal"),
        "run_exit": run_rc,
        "onboard_exit": onboard_rc,
        "pings": {k: pings[k] for k in ("due", "sent", "late", "late_render", "dropped",
                                        "deadline_misses", "deadline_tolerance_ms")},
        "lateness_ms": pings["lateness"],
        "nav": {"frames": nav["frames"], "skipped": nav["skipped"], "lateness_ms": nav["lateness"]},
        "render_mean_ms": pings["render_mean_ms"],
        "render_max_ms": pings["render_max_ms"],
        "tiles_made": rs["scene"]["tiles_made"],
        "cpu_percent": rs["cpu_percent"],
        "rss": {"run": rss_summary(sampler.samples["run"]),
                "onboard": rss_summary(sampler.samples["onboard"])},
        "rss_samples": sampler.samples,
        "files_bytes": sizes,
        "recorded_pings": rs["recorded_pings"],
        "xtf_read_back": {"pings": fs["receiver"]["pings"],
                          "malformed": fs["receiver"]["malformed"]},
        "candump_read_back": {"frames": nav_frames, "lines": nav_lines},
        "truth_lines": len(truth_lines),
        "truth_torn_lines": truth_torn,
        "onboard_udp": {k: receiver[k] for k in ("pings", "lost", "late", "malformed")},
        "contacts": ob["detector"]["reported"] if "detector" in ob else None,
        "python_can_frames": client.frames,
        "clock_drift_ms": drift_ms,
        "minutes_measured": len(minutes),
    }
    with open(os.path.join(args.out, "soak.json"), "w") as f:
        json.dump(report, f, indent=2)

    problems = []
    if run_rc != 0:
        problems.append(f"sonarloop run exited {run_rc}")
    if fs["receiver"]["pings"] != rs["recorded_pings"] or fs["receiver"]["malformed"]:
        problems.append("recorded pings that do not decode")
    if nav_frames != nav_lines or nav_frames != nav["frames"]:
        problems.append(f"nav.log: {nav_frames} frames read of {nav_lines} lines, "
                        f"{nav['frames']} published")
    if truth_torn:
        problems.append("torn truth.csv lines")
    if receiver["lost"] or receiver["malformed"]:
        problems.append("the consumer lost or could not read pings")
    if client.frames != nav["frames"]:
        problems.append(f"python-can received {client.frames} of {nav['frames']} frames")

    lat = pings["lateness"]
    print(f"soak: {args.duration:.0f} s, {args.hogs} hogs, publisher {report['realtime']}")
    print(f"  pings {pings['sent']} sent of {pings['due']}, deadline misses "
          f"{pings['deadline_misses']} ({pings['late']} late > {pings['deadline_tolerance_ms']} "
          f"ms, {pings['late_render']} of them not rendered in time; {pings['dropped']} dropped); "
          f"lateness p50 {lat['p50_ms']:.3f} p99 "
          f"{lat['p99_ms']:.3f} max {lat['max_ms']:.3f} ms")
    print(f"  rss run {report['rss']['run']}, onboard {report['rss']['onboard']}")
    print(f"  files {sizes}; read back: {fs['receiver']['pings']} of {rs['recorded_pings']} "
          f"pings, {nav_frames} of {nav_lines} candump lines, {len(truth_lines)} truth lines")
    print(f"  consumer {report['onboard_udp']}, python-can {client.frames} of {nav['frames']} "
          f"frames; clock drift {drift_ms if drift_ms is None else round(drift_ms, 3)} ms over "
          f"{len(minutes)} minutes")
    for p in problems:
        print("  PROBLEM: " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
