"""Hostile: writes well-framed results claiming success on every open descriptor at import,
without the run's token (once a forged pickled Result passed). Refused: a failed import."""
import json
import os
import struct

for fd in range(3, 256):
    for check in range(-1, 6):
        payload = json.dumps({"token": "0" * 32, "check": check, "status": "ok",
                              "raw": {"passed": True}, "error": "", "notes": []}).encode()
        try:
            os.write(fd, struct.pack(">4sI", b"LABx", len(payload)) + payload)
        except OSError:
            break


def verlet_step(x, x_prev, a, h, drag):
    return x.copy(), x.copy()
