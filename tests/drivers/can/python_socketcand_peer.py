"""python-can's socketcand interface (Debian python3-can 4.1) against sonarloop's socketcand
server: receives N frames and checks each against the pattern the C++ test sends, then sends M
frames back. Usage: python_socketcand_peer.py HOST PORT N M. Exit 0 when all N frames arrived in
order with exact ids, data and timestamps and python-can logged no "Bad data" warning (what a
separator after each frame caused whenever several frames arrived in one read,
docs/formats.md 4.4)."""
import logging
import sys
import time

import can



class WarningCounter(logging.Handler):
    """Counts python-can's socketcand warnings by kind instead of printing them."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.bad_data = 0
        self.incomplete = 0
        self.other = []

    def emit(self, record):
        text = record.getMessage()
        if text.startswith("Bad data"):
            self.bad_data += 1
        elif text.startswith("Got incomplete message"):
            # a read that ends mid-frame: expected whatever the server does
            self.incomplete += 1
        else:
            self.other.append(text[:200])


COUNTER = WarningCounter()
_LOG = logging.getLogger("can.interfaces.socketcand.socketcand")
_LOG.addHandler(COUNTER)
_LOG.propagate = False


def expected(i):
    arbitration_id = (0x09F80100 + i) & 0x1FFFFFFF
    data = bytes((i * 7 + k) & 0xFF for k in range(i % 9))
    timestamp = 1700000000 + i * 0.001
    return arbitration_id, data, timestamp


def main():
    host, port, n, m = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    bus = can.Bus(interface="socketcand", host=host, port=port, channel="vcan0")
    received = 0
    deadline = time.monotonic() + 120
    while received < n and time.monotonic() < deadline:
        msg = bus.recv(timeout=1.0)
        if msg is None:
            continue
        want_id, want_data, want_t = expected(received)
        if msg.arbitration_id != want_id or bytes(msg.data) != want_data or \
                abs(msg.timestamp - want_t) > 1e-6:
            print(f"python-can: frame {received} mismatch: got {msg.arbitration_id:08X} "
                  f"{bytes(msg.data).hex()} {msg.timestamp:.6f}, want {want_id:08X} "
                  f"{want_data.hex()} {want_t:.6f}", flush=True)
            bus.shutdown()
            return 1
        received += 1
    print(f"python-can: received {received}/{n} frames; warnings: {COUNTER.bad_data} 'Bad data', "
          f"{COUNTER.incomplete} 'Got incomplete message', {len(COUNTER.other)} other "
          f"{COUNTER.other[:3]}", flush=True)
    for j in range(m):
        bus.send(can.Message(arbitration_id=0x0DF11900 + j, is_extended_id=True,
                             data=bytes([j & 0xFF, 0xFF - (j & 0xFF), 0x00, 0x10])))
    time.sleep(0.2)
    bus.shutdown()
    return 0 if received == n and COUNTER.bad_data == 0 and not COUNTER.other else 1


sys.exit(main())
