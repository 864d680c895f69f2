#!/usr/bin/python3
"""Hostile clients against `run --web` and `onboard --web` (docs/web.md, issue 29), on loopback.

Starts the command with --web 127.0.0.1:0 and, at once, 8 clients that send their request a byte
every 0.5 s, one that sends an endless header block and one an endless request line; a viewer
asks for /stats.json meanwhile. Prints when the command ends (after --duration, or after SIGINT)
and its peak RSS. Measures; asserts nothing (the tests do: tests/web/web_server_test.cpp,
tests/tools/run_cli_test.cpp, tests/tools/onboard_cli_test.cpp).

usage: scripts/web_hostile.py [BINARY]     (default build/tools/sonarloop)
"""
import re
import signal
import socket
import subprocess
import sys
import threading
import time

BINARY = sys.argv[1] if len(sys.argv) > 1 else "build/tools/sonarloop"


def slow(port, stop, out, i):
    s = socket.create_connection(("127.0.0.1", port))
    s.sendall(b"GET / HTTP/1.1\r\n")
    n = 0
    try:
        while time.time() < stop:
            s.sendall(b"X")
            n += 1
            time.sleep(0.5)
        out[f"slow {i}"] = f"still open after {n} bytes"
    except OSError:
        out[f"slow {i}"] = f"closed after {n} bytes"


def flood(port, stop, out, kind):
    s = socket.create_connection(("127.0.0.1", port))
    sent = 0
    chunk = (b"X-a: b\r\n" if kind == "headers" else b"a") * 8192
    try:
        s.sendall(b"GET / HTTP/1.1\r\n" if kind == "headers" else b"GET /")
        while time.time() < stop:
            s.sendall(chunk)
            sent += len(chunk)
        out[kind] = f"still open after {sent} bytes"
    except OSError:
        try:
            got = s.recv(40)
        except OSError:
            got = b""
        out[kind] = f"closed after {sent} bytes, answer {got[:40]!r}"


def attack(port, seconds):
    stop = time.time() + seconds
    out = {}
    threads = [threading.Thread(target=slow, args=(port, stop, out, i)) for i in range(8)]
    threads += [threading.Thread(target=flood, args=(port, stop, out, k)) for k in ("headers", "line")]
    for t in threads:
        t.start()
    time.sleep(1)
    t0 = time.time()
    try:
        v = socket.create_connection(("127.0.0.1", port), timeout=5)
        v.sendall(b"GET /stats.json HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
        first = v.recv(15)
        out["viewer"] = f"{first!r} in {1000 * (time.time() - t0):.1f} ms"
    except OSError as e:
        out["viewer"] = f"no answer: {e}"
    return threads, out


def start(args):
    p = subprocess.Popen([BINARY] + args, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL,
                         text=True)
    for line in p.stderr:
        m = re.search(r"web view on http://127\.0\.0\.1:(\d+)/", line)
        if m:
            return p, int(m.group(1))
    sys.exit(f"{BINARY} {' '.join(args)} did not start its web view")


def peak_rss(pid, done, out):
    while not done.is_set():
        try:
            with open(f"/proc/{pid}/status") as f:
                for line in f:
                    if line.startswith("VmRSS"):
                        out.append(int(line.split()[1]))
        except OSError:
            return
        time.sleep(0.2)


def report(name, out):
    for k, v in sorted(out.items()):
        print(f"  {name}: {k}: {v}")


p, port = start(["run", "--duration", "8", "--quiet", "--web", "127.0.0.1:0"])
t0 = time.time()
done, rss = threading.Event(), []
threading.Thread(target=peak_rss, args=(p.pid, done, rss)).start()
threads, out = attack(port, 20)
err = p.stderr.read()
p.wait()
t1 = time.time()
done.set()
m = re.search(r"done after [\d.]+ s of simulation in [\d.]+ s", err)
web = re.search(r"  web: .*", err, re.S)
print(f"run --duration 8: exit {p.returncode} {t1 - t0:.2f} s after its URL ({m.group(0) if m else '?'}),"
      f" peak RSS {max(rss) / 1024:.0f} MB")
print(" ", " ".join(web.group(0).split()) if web else "(no web summary)")
for t in threads:
    t.join()
report("run", out)

for args in (["run", "--duration", "60", "--quiet"], ["onboard", "--listen", "127.0.0.1:0"]):
    p, port = start(args + ["--web", "127.0.0.1:0"])
    threads, out = attack(port, 12)
    time.sleep(6)
    t0 = time.time()
    p.send_signal(signal.SIGINT)
    p.stderr.read()
    p.wait()
    print(f"{args[0]} SIGINT under attack: exit {p.returncode} {1000 * (time.time() - t0):.0f} ms after the signal")
    for t in threads:
        t.join()
