"""Hostile, for the live scene: registers an atexit handler that writes to fd 1 and sleeps a
minute, keeps an object whose __del__ sleeps a minute (collected at exit), and asks for input()
in its first step; its step is right otherwise. The headless scene must print its JSON alone and
end at once (the once-hanging exit), the input() read an empty stdin (EOFError, reported)."""
import atexit
import os
import time

STEPS = [0]


@atexit.register
def _goodbye():
    os.write(1, b"atexit: printed after the JSON\n")
    time.sleep(60)


class Sticky:
    def __del__(self):
        time.sleep(60)


_kept = Sticky()


def verlet_step(x, x_prev, a, h, drag):
    STEPS[0] += 1
    if STEPS[0] == 3:
        input("press enter")
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
