"""A ring buffer of the last n samples, for trails and plots that are redrawn every frame.

One preallocated (n, k) array: appending overwrites the oldest row, and the plots read the samples
as an array, oldest first, where a deque of tuples would cost an element-by-element conversion
every frame.

    trail = Ring(360, 2)          # the last 360 positions (x, y)
    trail.append(body.position)
    pts = trail.values()          # (count, 2), oldest first
"""

from __future__ import annotations

import numpy as np


class Ring:
    """The last n samples of k numbers in one preallocated array."""

    def __init__(self, n: int, k: int = 1):
        self.data = np.zeros((n, k))
        self.head = 0           # where the next sample goes
        self.count = 0          # samples stored so far (at most n)

    def append(self, sample) -> None:
        head = self.head
        self.data[head] = sample
        head += 1
        n = len(self.data)
        self.head = head if head < n else 0
        if self.count < n:
            self.count += 1

    def clear(self) -> None:
        self.head = 0
        self.count = 0

    def __len__(self) -> int:
        return self.count

    def last(self) -> np.ndarray:
        """The newest sample, shape (k,)."""
        return self.data[self.head - 1]

    def values(self) -> np.ndarray:
        """The samples, oldest first, shape (count, k)."""
        if self.count < len(self.data):
            return self.data[:self.count]
        return np.concatenate((self.data[self.head:], self.data[:self.head]))   # unrolled
