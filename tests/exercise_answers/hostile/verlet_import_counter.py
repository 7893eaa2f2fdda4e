"""Hostile (right answer): counts its imports on its output (a file that slept 9 s at import was
once imported again for every check: 56 s). Imported once per exercise now."""
print("imported", flush=True)


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
