"""Hostile: finds the channel and the run's token in the grader's frames (code can read its
caller's variables) and sends a forged frame claiming 'passed' for the check after the one
running, then returns nothing useful. A frame carries raw values only and the parent judges them:
every check fails."""
import json
import os
import struct
import sys


def _forge():
    frame = sys._getframe()
    while frame is not None:
        if "token" in frame.f_locals and "channel" in frame.f_locals:
            token, channel = frame.f_locals["token"], frame.f_locals["channel"]
            index = frame.f_locals.get("index", -1)
            payload = json.dumps({"token": token, "check": index, "status": "ok",
                                  "raw": {"passed": True, "x": [[0, 0]] * 3}, "error": "",
                                  "notes": []}).encode()
            os.write(channel, struct.pack(">4sI", b"LABx", len(payload)) + payload)
            return
        frame = frame.f_back


def verlet_step(x, x_prev, a, h, drag):
    _forge()
    return x.copy(), x.copy()
