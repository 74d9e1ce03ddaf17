# Prints the power stages of the drive emulator's three drives, on (1) or off
# (0), read over Modbus TCP (status word, register 10, bit 0): used by the
# shell tests that interrupt a moving robot (tests/cli/test_cmd_sample.sh,
# tests/scenario_suite/test_hardware_run.sh). Usage: emulator_drives.py PORT
import socket
import struct
import sys

s = socket.create_connection(("127.0.0.1", int(sys.argv[1])), timeout=10)
on = []
for unit in (1, 2, 3):
    s.sendall(struct.pack(">HHHBBHH", unit, 0, 6, unit, 3, 10, 1))
    r = b""
    while len(r) < 11:
        r += s.recv(64)
    on.append(str(struct.unpack(">H", r[9:11])[0] & 1))
print(" ".join(on))
