#!/usr/bin/env python3
"""The live web view in a real browser (docs/web.md).

Starts `sonarloop run --rate 1 --web 127.0.0.1:0`, drives headless Chromium over the Chrome
DevTools protocol (a minimal WebSocket client below: the standard library has none) to load the
page, waits for waterfall lines, and checks that
  - the waterfall canvas in a screenshot holds a non-uniform image (many colours, spread levels),
    and the map shows the track;
  - the statistics text updates, also while the scroll is paused, and the paused waterfall does
    not scroll (its lines are held) until resumed;
  - the run ends normally and its summary reports the web view.
Skips (exit 77, with the reason) where no Chromium is installed.

usage: browser_test.py SONARLOOP WORK_DIR [--keep-screenshot FILE] [--lines N] [--run-args ARGS]
  (the last three make the screenshot of docs/web.md: e.g. --lines 500 --run-args
  "--rate 2 --classify out/atr.slpca")
"""
import argparse
import atexit
import base64
import json
import os
import re
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request
import zlib

# every wait is bounded by this (a hang fails instead of blocking ctest)
WAIT_S = 30.0
# lines the page must have drawn before the screenshot (2 s of the default sonar)
MIN_LINES = 30


def fail(why):
    print("FAIL: " + why)
    sys.exit(1)


def wait_for(what, poll, timeout=WAIT_S):
    """Calls poll() until it returns a true value; fails naming `what` after timeout."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        v = poll()
        if v:
            return v
        time.sleep(0.25)
    fail("timed out waiting for " + what)


class WebSocket:
    """Just enough of RFC 6455 for the DevTools protocol: text frames, client-side masking."""

    def __init__(self, url):
        m = re.match(r"ws://([^/:]+):(\d+)(/.*)", url)
        self.sock = socket.create_connection((m.group(1), int(m.group(2))), timeout=WAIT_S)
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall(("GET %s HTTP/1.1\r\nHost: %s:%s\r\nUpgrade: websocket\r\n"
                           "Connection: Upgrade\r\nSec-WebSocket-Key: %s\r\n"
                           "Sec-WebSocket-Version: 13\r\n\r\n" %
                           (m.group(3), m.group(1), m.group(2), key)).encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(1)
            if not chunk:
                fail("DevTools closed the WebSocket handshake")
            head += chunk
        if b" 101 " not in head.split(b"\r\n")[0]:
            fail("DevTools refused the WebSocket: " + head.decode(errors="replace"))

    def _exact(self, n):
        buf = b""
        while len(buf) < n:
            chunk = self.sock.recv(n - len(buf))
            if not chunk:
                fail("DevTools closed the WebSocket")
            buf += chunk
        return buf

    def send(self, text):
        data = text.encode()
        head = bytes([0x81])  # FIN, text
        if len(data) < 126:
            head += bytes([0x80 | len(data)])
        elif len(data) < 65536:
            head += bytes([0x80 | 126]) + struct.pack(">H", len(data))
        else:
            head += bytes([0x80 | 127]) + struct.pack(">Q", len(data))
        mask = os.urandom(4)
        self.sock.sendall(head + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(data)))

    def recv(self):
        message = b""
        while True:
            b0, b1 = self._exact(2)
            n = b1 & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._exact(2))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._exact(8))[0]
            payload = self._exact(n)
            if b0 & 0x0F in (0x9, 0xA):  # ping / pong: not part of a message
                continue
            message += payload
            if b0 & 0x80:
                return message.decode()


class DevTools:
    def __init__(self, ws_url):
        self.ws = WebSocket(ws_url)
        self.next_id = 0

    def call(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            reply = json.loads(self.ws.recv())
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    fail("%s: %s" % (method, reply["error"]))
                return reply["result"]

    def js(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True)
        if "exceptionDetails" in r:
            fail("script error in %r: %s" % (expression, r["exceptionDetails"]))
        return r["result"].get("value")


def decode_png(data):
    """RGB(A) 8-bit non-interlaced PNG -> (width, height, channels, rows of bytes)."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail("the screenshot is not a PNG")
    pos, idat = 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    if depth != 8 or colour not in (2, 6) or interlace:
        fail("unexpected PNG format (depth %d, colour %d)" % (depth, colour))
    ch = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = w * ch
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b = prev[i]
            c = prev[i - ch] if i >= ch else 0
            if f == 1:
                line[i] = (line[i] + a) & 0xFF
            elif f == 2:
                line[i] = (line[i] + b) & 0xFF
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 0xFF
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 0xFF
        rows.append(bytes(line))
        prev = line
    return w, h, ch, rows


def region(png, rect, scale):
    """Pixels (r, g, b) of a CSS-pixel rectangle of the screenshot."""
    w, h, ch, rows = png
    x0, y0 = int(rect["x"] * scale) + 1, int(rect["y"] * scale) + 1
    x1 = min(w, int((rect["x"] + rect["width"]) * scale) - 1)
    y1 = min(h, int((rect["y"] + rect["height"]) * scale) - 1)
    return [tuple(rows[y][x * ch:x * ch + 3]) for y in range(y0, y1) for x in range(x0, x1)]


def find_chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


class StderrLines:
    """Reads a child's stderr on a thread of its own, so that the child never blocks on a full
    pipe and a wait sees every line printed so far (not one line per poll), and keeps the lines
    (copying them to `log` when given)."""

    def __init__(self, stream, log=None):
        self._lines = []
        self._lock = threading.Lock()
        self._log = log
        self._thread = threading.Thread(target=self._drain, args=(stream,), daemon=True)
        self._thread.start()

    def _drain(self, stream):
        for line in stream:
            with self._lock:
                self._lines.append(line)
            if self._log:
                self._log.write(line)

    def search(self, pattern):
        """The first match of `pattern` in the lines read so far, or None."""
        with self._lock:
            lines = list(self._lines)
        for line in lines:
            m = re.search(pattern, line)
            if m:
                return m
        return None

    def text(self, last=None):
        with self._lock:
            return "".join(self._lines[-last:] if last else self._lines)

    def finish(self, timeout=WAIT_S):
        """Waits for the end of the stream (the child has exited) and returns all of it."""
        self._thread.join(timeout)
        return self.text()


def start_sonarloop(binary, run_args, log_path):
    log = open(log_path, "w")
    proc = subprocess.Popen([binary, "run"] + run_args +
                            ["--web", "127.0.0.1:0", "--stats-every", "0"],
                            stderr=subprocess.PIPE, stdout=log, text=True)
    err = StderrLines(proc.stderr, log)
    # a failure (sys.exit) must not leave the run behind for the rest of its --duration
    atexit.register(lambda: proc.poll() is None and proc.kill())

    def url():
        m = err.search(r"web view on (http://\S+)")
        if not m and proc.poll() is not None:
            fail("sonarloop run ended early:\n" + err.finish())
        return m.group(1) if m else None

    return proc, wait_for("the web view's URL", url), log, err


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("sonarloop")
    ap.add_argument("work_dir")
    ap.add_argument("--keep-screenshot")
    ap.add_argument("--lines", type=int, default=MIN_LINES)
    ap.add_argument("--run-args", default="--rate 1 --duration 45 --threads 1")
    a = ap.parse_args()
    binary, work, keep = a.sonarloop, a.work_dir, a.keep_screenshot
    chromium = find_chromium()
    if not chromium:
        print("SKIPPED: no Chromium installed (Debian package chromium)")
        sys.exit(77)
    os.makedirs(work, exist_ok=True)

    run, url, run_log, run_err = start_sonarloop(binary, a.run_args.split(),
                                                 os.path.join(work, "run.log"))
    profile = tempfile.mkdtemp(prefix="sonarloop-chromium-")
    browser = subprocess.Popen(
        [chromium, "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-extensions", "--user-data-dir=" + profile, "--remote-debugging-port=0",
         "--window-size=1500,1000", "--force-device-scale-factor=1", "about:blank"],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        browser_err = StderrLines(browser.stderr)

        def devtools_url():
            m = browser_err.search(r"DevTools listening on ws://([^/]+)/")
            if not m and browser.poll() is not None:
                fail("chromium ended:\n" + browser_err.finish())
            return m.group(1) if m else None

        try:
            host = wait_for("chromium's DevTools port", devtools_url)
        except SystemExit:
            print("chromium's last lines on stderr:\n" + browser_err.text(last=20))
            raise
        targets = json.load(urllib.request.urlopen("http://%s/json/list" % host, timeout=WAIT_S))
        page = next(t for t in targets if t["type"] == "page")
        dt = DevTools(page["webSocketDebuggerUrl"])
        dt.call("Page.enable")
        dt.call("Page.navigate", url=url)

        lines = lambda: int(dt.js("Number((document.body && document.body.dataset.lines) || 0)"))
        stats = lambda: dt.js("document.getElementById('stats').innerText")
        wait_for("%d waterfall lines" % a.lines, lambda: lines() >= a.lines,
                 timeout=WAIT_S + a.lines / 10.0)
        state = dt.js("document.getElementById('state').textContent")
        if state != "live":
            fail("the page's stream state is '%s' after %d lines" % (state, lines()))

        # the statistics update
        first = stats()
        wait_for("the statistics to change", lambda: stats() != first)

        # the screenshot: the waterfall holds a non-uniform image, the map the track
        shot = base64.b64decode(dt.call("Page.captureScreenshot", format="png")["data"])
        with open(os.path.join(work, "screenshot.png"), "wb") as f:
            f.write(shot)
        if keep:
            shutil.copyfile(os.path.join(work, "screenshot.png"), keep)
        png = decode_png(shot)
        scale = png[0] / dt.js("window.innerWidth")
        rect = lambda id: json.loads(dt.js(
            "JSON.stringify(document.getElementById('%s').getBoundingClientRect())" % id))
        wf = region(png, rect("waterfall"), scale)
        colours = len(set(wf))
        lum = [0.299 * r + 0.587 * g + 0.114 * b for r, g, b in wf]
        mean = sum(lum) / len(lum)
        sd = (sum((v - mean) ** 2 for v in lum) / len(lum)) ** 0.5
        print("waterfall: %d pixels, %d colours, luminance mean %.1f sd %.1f" %
              (len(wf), colours, mean, sd))
        if colours < 50 or sd < 5.0:
            fail("the waterfall looks uniform (%d colours, sd %.1f)" % (colours, sd))
        track = sum(1 for p in region(png, rect("map"), scale) if p == (79, 163, 255))
        print("map: %d track pixels" % track)
        if track < 10:
            fail("the map shows no track")

        # pause: the scroll stops, lines are held, the statistics go on; resume draws them
        dt.js("document.getElementById('pause').click()")
        drawn = lines()
        before = stats()
        wait_for("the statistics to change while paused", lambda: stats() != before)
        held = dt.js("document.getElementById('held').textContent")
        print("paused: %s; lines drawn %d then %d" % (held, drawn, lines()))
        if lines() != drawn or not held.endswith("lines held"):
            fail("the waterfall scrolled while paused")
        dt.js("document.getElementById('pause').click()")
        wait_for("lines drawn after resuming", lambda: lines() > drawn)
    finally:
        browser.terminate()
        browser.wait()
        shutil.rmtree(profile, ignore_errors=True)

    # the run goes on to a normal end (stopped early here, as Ctrl-C would)
    run.send_signal(signal.SIGINT)
    if run.wait(timeout=WAIT_S) != 0:
        fail("sonarloop run exited with %d:\n%s" % (run.returncode, run_err.finish()))
    rest = run_err.finish()
    run_log.close()
    m = re.search(r"web: (\d+) viewers .* (\d+) events sent", rest)
    if not m or int(m.group(1)) < 1 or int(m.group(2)) < MIN_LINES:
        fail("no web summary with a viewer in:\n" + rest)
    print("PASS: " + m.group(0))


if __name__ == "__main__":
    main()
