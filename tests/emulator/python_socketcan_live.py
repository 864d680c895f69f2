"""python-can on a real SocketCAN interface: receives NMEA 2000 frames that `sonarloop run --can
IFACE` publishes. Usage: python_socketcan_live.py IFACE SECONDS MIN_FRAMES. Prints how many
frames of the emulator's source address (0x23) arrived; exit 0 when at least MIN_FRAMES did."""
import sys
import time

import can


def main():
    iface, seconds, min_frames = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
    bus = can.Bus(interface="socketcan", channel=iface)
    n = 0
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        msg = bus.recv(timeout=0.2)
        if msg is not None and msg.is_extended_id and (msg.arbitration_id & 0xFF) == 0x23:
            n += 1
    bus.shutdown()
    print(f"python-can: {n} frames from source 0x23 on {iface}")
    return 0 if n >= min_frames else 1


sys.exit(main())
