"""Hostile (issue 23): opens a TCP connection to 127.0.0.1 at import (the port in
LAB_TEST_PORT, where the test listens); its step is right. The child has a network namespace of
its own and Landlock refuses TCP: nothing arrives, and the file says why on its output."""
import os
import socket

try:
    socket.create_connection(("127.0.0.1", int(os.environ.get("LAB_TEST_PORT", "9"))), 2).close()
    print("CONNECTED")
except OSError as _e:
    print(f"refused: {type(_e).__name__}")


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
