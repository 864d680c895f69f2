"""Reads a candump log with python-can's CanutilsLogReader (Debian python3-can 4.1) and writes
one line per message to OUT: "<timestamp %.6f> <id %X> <extended 0|1> <dlc> <DATA HEX> <channel>".
Usage: python_candump_read.py LOG OUT. Exits non-zero (with python-can's error) if the log does
not parse."""
import sys

import can

with open(sys.argv[2], "w") as out:
    for msg in can.CanutilsLogReader(sys.argv[1]):
        out.write(
            f"{msg.timestamp:.6f} {msg.arbitration_id:X} {int(msg.is_extended_id)} {msg.dlc} "
            f"{msg.data.hex().upper()} {msg.channel}\n"
        )
