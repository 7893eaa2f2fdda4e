"""Wrong (fails 'free fall'): returns (x_new, x_prev): the second value is not the old x."""
import numpy as np


def verlet_step(x: np.ndarray, x_prev: np.ndarray, a: np.ndarray, h: float,
                drag: float) -> tuple[np.ndarray, np.ndarray]:
    x_new = x + (1 - drag) * (x - x_prev) + a * h * h
    return x_new, x_prev
