"""Hostile: crashes its own process (SIGSEGV, through ctypes) in the step: each check fails with
'killed by signal 11', a new child going on with the next."""
import ctypes


def verlet_step(x, x_prev, a, h, drag):
    ctypes.string_at(0)
