"""Wrong (fails 'free fall'): returns (x, x_new): the pair in the wrong order."""
import numpy as np


def verlet_step(x: np.ndarray, x_prev: np.ndarray, a: np.ndarray, h: float,
                drag: float) -> tuple[np.ndarray, np.ndarray]:
    x_new = x + (1 - drag) * (x - x_prev) + a * h * h
    return x, x_new
