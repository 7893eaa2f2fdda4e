"""Wrong (fails 'free fall'): returns Python lists instead of arrays."""
import numpy as np


def verlet_step(x: np.ndarray, x_prev: np.ndarray, a: np.ndarray, h: float,
                drag: float) -> tuple[np.ndarray, np.ndarray]:
    x_new = x + (1 - drag) * (x - x_prev) + a * h * h
    return x_new.tolist(), x.tolist()
