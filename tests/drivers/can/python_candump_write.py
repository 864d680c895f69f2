"""Writes a candump log with python-can's CanutilsLogWriter (Debian python3-can 4.1): the
python-can writer style ("(%f) CHANNEL ID#DATA R") that sonarloop's reader must accept.
Usage: python_candump_write.py LOG"""
import sys

import can

messages = [
    can.Message(timestamp=1699999999.123456, arbitration_id=0x09F80123, is_extended_id=True,
                data=bytes.fromhex("00E6B523B1AC6A06")),
    can.Message(timestamp=1699999999.5, arbitration_id=0x123, is_extended_id=False,
                data=b"\x01\x02", is_rx=False),
    can.Message(timestamp=1700000000.0, arbitration_id=0x18FF0001, is_extended_id=True, data=b""),
    can.Message(timestamp=1700000001.25, arbitration_id=0x7FF, is_extended_id=False,
                is_remote_frame=True, dlc=3),
    can.Message(timestamp=1700000002.0, arbitration_id=0x0DF11923, is_extended_id=True,
                is_fd=True, bitrate_switch=True, data=bytes(range(12))),
]
writer = can.CanutilsLogWriter(sys.argv[1], channel="vcan0")
for m in messages:
    writer.on_message_received(m)
writer.stop()
