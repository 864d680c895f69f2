#!/usr/bin/python3
"""Send sonarloop UDP pose messages (drivers/pose/pose_message.md): an external "vehicle" for
`sonarloop run --pose-from udp:HOST:PORT`.

Sends COUNT messages at RATE Hz, starting at LAT/LON and moving along HEADING at SPEED (a
flat-earth step, good enough for a demonstration over a few kilometres). Attitude, depth and
altitude stay constant; omit --altitude for "no bottom lock" (NaN).

examples:
  tools/send_pose.py 127.0.0.1:5700 --lat 59.9 --lon 10.75 --depth 20 --altitude 8
  tools/send_pose.py 127.0.0.1:5700 --lat 59.9 --lon 10.75 --heading-deg 90 --speed 2 --count 0
"""
import argparse
import math
import socket
import struct
import sys
import time

MAGIC = b"SLPM"
VERSION = 1
SIZE = 80
# magic, version, size, sequence, flags, time_unix_ns, lat, lon, depth, altitude, heading, pitch,
# roll: little-endian, no padding (pose_message.md)
FORMAT = "<4sHHIIqddddddd"
METRES_PER_DEG_LAT = 111_320.0  # flat-earth step for the demo track only
assert struct.calcsize(FORMAT) == SIZE


def encode(sequence, time_unix_ns, lat_deg, lon_deg, depth_m, altitude_m, heading_rad,
           pitch_rad, roll_rad):
    """The 80-byte datagram; pass float('nan') for a field that is not available."""
    return struct.pack(FORMAT, MAGIC, VERSION, SIZE, sequence & 0xFFFFFFFF, 0, time_unix_ns,
                       lat_deg, lon_deg, depth_m, altitude_m, heading_rad, pitch_rad, roll_rad)


def host_port(text):
    host, _, port = text.rpartition(":")
    if not host or not port.isdigit():
        raise argparse.ArgumentTypeError(f"'{text}' is not HOST:PORT (e.g. 127.0.0.1:5700)")
    return host.strip("[]"), int(port)


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("destination", type=host_port, help="the emulator's HOST:PORT")
    p.add_argument("--lat", type=float, required=True, help="start latitude, degrees")
    p.add_argument("--lon", type=float, required=True, help="start longitude, degrees")
    p.add_argument("--depth", type=float, default=float("nan"), help="depth, m (+ down)")
    p.add_argument("--altitude", type=float, default=float("nan"), help="altitude, m")
    p.add_argument("--heading-deg", type=float, default=0.0, help="degrees clockwise from north")
    p.add_argument("--pitch-deg", type=float, default=0.0, help="degrees, + nose up")
    p.add_argument("--roll-deg", type=float, default=0.0, help="degrees, + starboard down")
    p.add_argument("--speed", type=float, default=0.0, help="m/s along the heading")
    p.add_argument("--rate", type=float, default=10.0, help="messages per second")
    p.add_argument("--count", type=int, default=1, help="messages to send (0 = until Ctrl-C)")
    a = p.parse_args()
    if a.rate <= 0:
        p.error("--rate must be > 0")

    family = socket.AF_INET6 if ":" in a.destination[0] else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_DGRAM)
    heading = math.radians(a.heading_deg)
    period = 1.0 / a.rate
    start = time.monotonic()
    sequence = 0
    try:
        while a.count == 0 or sequence < a.count:
            travelled = a.speed * sequence * period
            lat = a.lat + travelled * math.cos(heading) / METRES_PER_DEG_LAT
            lon = a.lon + travelled * math.sin(heading) / (
                METRES_PER_DEG_LAT * math.cos(math.radians(a.lat)))
            sock.sendto(encode(sequence, time.time_ns(), lat, lon, a.depth, a.altitude, heading,
                               math.radians(a.pitch_deg), math.radians(a.roll_deg)),
                        a.destination)
            sequence += 1
            # absolute deadlines: no drift
            delay = start + sequence * period - time.monotonic()
            if delay > 0 and (a.count == 0 or sequence < a.count):
                time.sleep(delay)
    except KeyboardInterrupt:
        pass
    print(f"send_pose: sent {sequence} messages to {a.destination[0]}:{a.destination[1]}",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
