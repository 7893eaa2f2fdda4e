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


class PendingRing(Ring):
    """A Ring whose appends wait in a list until it is read (values, last) or as many as it
    holds are waiting: then they go in at once, one conversion and at most two slices for the
    lot (a row assigned from a tuple costs ~3k instructions, a list append ~0.1k). For a trail
    appended every physics step and read only when a frame is drawn: the same rows, head and
    count as Ring's after the same appends."""

    def __init__(self, n: int, k: int = 1):
        super().__init__(n, k)
        self.pending: list = []

    def append(self, sample) -> None:
        pending = self.pending
        pending.append(sample)
        if len(pending) >= len(self.data):
            self.flush()

    def flush(self) -> None:
        """Put the waiting samples in, oldest first (at most n of them: append sees to it)."""
        pending = self.pending
        if not pending:
            return
        self.pending = []
        data, head, m = self.data, self.head, len(pending)
        n = len(data)
        rows = np.asarray(pending, dtype=data.dtype).reshape(m, -1)
        first = min(m, n - head)
        data[head:head + first] = rows[:first]
        if m > first:
            data[:m - first] = rows[first:]
        self.head = (head + m) % n
        self.count = min(self.count + m, n)

    def clear(self) -> None:
        self.pending = []
        super().clear()

    def __getstate__(self) -> dict:
        """A copy (deepcopy: a snapshot, which the timeline keeps 61 of) holds the waiting
        samples in the array, as a Ring's copy does: a list of tuples of floats takes ~6x the
        bytes, and the timeline's memory cap would keep a shorter span."""
        self.flush()
        return self.__dict__.copy()

    def __len__(self) -> int:
        return min(self.count + len(self.pending), len(self.data))

    def last(self) -> np.ndarray:
        self.flush()
        return super().last()

    def values(self) -> np.ndarray:
        self.flush()
        return super().values()
