"""python-can (Debian python3-can 4.1) as a live NMEA 2000 client of `sonarloop run`: starts the
emulator with a socketcand server on an ephemeral loopback port and a recording, connects with
can.Bus(interface="socketcand"), receives frames until the emulator exits, then checks that every
received frame (id, data, timestamp) is in the recorded nav.log, read with CanutilsLogReader.
Usage: python_socketcand_live.py SONARLOOP SCENARIO.yaml OUT_DIR DURATION_S MIN_FRAMES.
Exit 0 when at least MIN_FRAMES frames arrived and all of them match the log."""
import logging
import re
import subprocess
import sys
import threading
import time

import can

logging.getLogger("can.interfaces.socketcand.socketcand").setLevel(logging.ERROR)


def main():
    binary, scenario, out_dir, duration, min_frames = sys.argv[1:6]
    cmd = [binary, "run", scenario, "--duration", duration, "--rate", "realtime",
           "--can", "socketcand:127.0.0.1:0", "--record", out_dir, "--stats-every", "0"]
    proc = subprocess.Popen(cmd, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
    port = None
    lines = []
    deadline = time.monotonic() + 120
    while port is None and time.monotonic() < deadline:
        line = proc.stderr.readline()
        if not line:
            break
        lines.append(line)
        m = re.search(r"socketcand server on 127\.0\.0\.1:(\d+)", line)
        if m:
            port = int(m.group(1))
    if port is None:
        proc.kill()
        print("no socketcand port in the emulator's output:\n" + "".join(lines))
        return 1
    # keep draining stderr so the emulator never blocks on it
    rest = []
    drain = threading.Thread(target=lambda: rest.extend(proc.stderr), daemon=True)
    drain.start()

    bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="vcan0")
    received = []
    quiet_since = None
    while time.monotonic() < deadline:
        msg = bus.recv(timeout=0.2)
        if msg is not None:
            received.append(msg)
            quiet_since = None
            continue
        if proc.poll() is not None:
            quiet_since = quiet_since or time.monotonic()
            if time.monotonic() - quiet_since > 1.0:
                break
    bus.shutdown()
    proc.wait(timeout=60)
    drain.join(timeout=5)
    if proc.returncode != 0:
        print(f"emulator exited with {proc.returncode}:\n" + "".join(lines + rest))
        return 1

    logged = {}
    for msg in can.CanutilsLogReader(f"{out_dir}/nav.log"):
        logged[(round(msg.timestamp * 1e6), msg.arbitration_id)] = bytes(msg.data)
    bad = 0
    for msg in received:
        key = (round(msg.timestamp * 1e6), msg.arbitration_id)
        if logged.get(key) != bytes(msg.data):
            bad += 1
            if bad <= 5:
                print(f"frame not in nav.log: {msg.arbitration_id:08X} {bytes(msg.data).hex()} "
                      f"at {msg.timestamp:.6f}")
    print(f"python-can: received {len(received)} frames live, {bad} not matching nav.log "
          f"({len(logged)} logged)")
    return 0 if bad == 0 and len(received) >= int(min_frames) else 1


sys.exit(main())
