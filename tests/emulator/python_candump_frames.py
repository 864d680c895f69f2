"""Reads a candump log written by `sonarloop run --record` with python-can's CanutilsLogReader
(Debian python3-can 4.1) and prints every message as "TIMESTAMP_US ID DATA" (decimal
microseconds, 8 hex digits, hex bytes), for the C++ test to decode and compare. Usage:
python_candump_frames.py NAV.LOG. Exit 0 when every line was read as an extended data frame."""
import sys

import can


def main():
    n = 0
    for msg in can.CanutilsLogReader(sys.argv[1]):
        if not msg.is_extended_id or msg.is_error_frame or msg.is_remote_frame:
            print(f"unexpected frame {msg}", file=sys.stderr)
            return 1
        us = round(msg.timestamp * 1e6)
        print(f"{us} {msg.arbitration_id:08X} {bytes(msg.data).hex().upper()}")
        n += 1
    print(f"python-can read {n} frames", file=sys.stderr)
    return 0 if n > 0 else 1


sys.exit(main())
