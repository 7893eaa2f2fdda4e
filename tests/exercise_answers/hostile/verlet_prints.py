"""Hostile: 20 MB of prints at import, and output at the file-descriptor level and from a
subprocess in every step (once passed through uncapped: 280 MB); the step is right. The grader
shows the first few kB and counts the rest."""
import os
import subprocess

for _ in range(20_000):
    print("x" * 999)


def verlet_step(x, x_prev, a, h, drag):
    os.write(1, b"fd 1, straight from the step\n")
    if x.shape == (4, 2):            # once (the inputs check): a subprocess is slow
        subprocess.run(["echo", "from a subprocess"])
    return x + (1 - drag) * (x - x_prev) + a * h * h, x.copy()
