"""Wrong (fails 'drag loses energy'): drag applied twice: (1 - drag) ** 2."""
import numpy as np


def verlet_step(x: np.ndarray, x_prev: np.ndarray, a: np.ndarray, h: float,
                drag: float) -> tuple[np.ndarray, np.ndarray]:
    x_new = x + (1 - drag) ** 2 * (x - x_prev) + a * h * h
    return x_new, x
