"""Hostile: waits for keyboard input at import. The child's stdin is /dev/null: EOFError, a
failed import at once, not a wait for a key nobody presses."""
answer = input("press Enter to continue ")


def verlet_step(x, x_prev, a, h, drag):
    return x, x
