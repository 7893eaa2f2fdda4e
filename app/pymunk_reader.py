"""Reading every body of a pymunk space in one C call, into buffers kept between reads: the
rows (x, y, angle, vx, vy, w) that PymunkScene's checks, state hash and non-finite guard share
(app/pymunk_scene.py, state_rows)."""

from __future__ import annotations

import numpy as np
import pymunk
import pymunk.batch

try:          # the batch API's own C entry points (pymunk 7), to read the bodies without the
    from pymunk._chipmunk import ffi as _ffi, lib as _lib     # ~1.3 us a call of its wrapper
    _BATCH_GET, _EACH_BODY = (_ffi.addressof(_lib, "pmSpaceBodyGetIteratorFuncBatched"),
                              _lib.cpSpaceEachBody)
except (ImportError, AttributeError):      # (another pymunk: the public wrapper, same data)
    _ffi = _lib = _BATCH_GET = _EACH_BODY = None

# The fields read for the state hash and the finiteness check, all at once.
_STATE_FIELDS = (pymunk.batch.BodyFields.POSITION | pymunk.batch.BodyFields.ANGLE
                 | pymunk.batch.BodyFields.VELOCITY | pymunk.batch.BodyFields.ANGULAR_VELOCITY)
_STATE_ID = _STATE_FIELDS | pymunk.batch.BodyFields.BODY_ID   # (an enum's | costs a few us)


class _StateReader:
    """Reads _STATE_ID of every body into a buffer of its own, as pymunk.batch.get_space_bodies
    does, with its C call's arguments made once (the same C function and data). Two buffers, one
    read into each in turn: the rows of a read stay good through the next read (a scene may keep
    them a step without a copy: `keep`). While as many bodies are read as in a buffer's last
    read, the views of that read are returned again (refilled in place)."""

    def __init__(self) -> None:
        self.buffers = (pymunk.batch.Buffer(), pymunk.batch.Buffer())
        self.cur = 1              # the buffer of the last read
        self.last: list = [None, None]   # a buffer's (n, its arrays, (ids, rows), flat) last
        self.room: list = [None, None]   # a buffer's (arrays, bodies they hold, ids, flat)
        self.flat = np.empty(0)   # the rows of the last read as one flat view (n * 6,)
        self.reads = 0            # reads made (PymunkScene.finite_read names one of them)
        # (buffer, callback): the rows of that buffer's read are kept by a scene; a read about
        # to refill it calls callback first (to copy what it keeps), then forgets it
        self.keep: tuple | None = None
        self.arrays = []          # each buffer's (float array, int array, the C call's data)
        for buf in self.buffers if _lib is not None else ():
            data, floats, ints = _ffi.new("pmBatchedData *"), buf._float_arr, buf._int_arr
            data.fields, data.floatArray, data.intArray = _STATE_ID.value, floats, ints
            self.arrays.append((floats, ints, data))

    def read(self, space: pymunk.Space) -> tuple[np.ndarray, np.ndarray]:
        self.reads += 1
        i = self.cur = 1 - self.cur
        keep = self.keep
        if keep is not None and keep[0] == i:
            self.keep = None
            keep[1]()
        if _lib is None:
            buf = self.buffers[i]
            buf.clear()
            pymunk.batch.get_space_bodies(space, _STATE_ID, buf)
            ids = np.frombuffer(buf.int_buf(), dtype=np.int64)
            self.flat = np.frombuffer(buf.float_buf(), dtype=np.float64)
            return ids, self.flat.reshape(len(ids), 6)
        floats, ints, data = self.arrays[i]
        floats.num = ints.num = 0
        _EACH_BODY(space._space, _BATCH_GET, data)
        n, last = ints.num, self.last[i]
        if last is not None and last[0] == n:
            # as many bodies as this buffer's last read: the same pushes, so Chipmunk grew no
            # array (pm*ArrayPush grows one only when nearly full): the same views (~1.5k saved)
            self.flat = last[4]
            return last[3]
        int_arr, float_arr = ints.arr, floats.arr
        # views of the arrays' whole room, made again when Chipmunk moves them (grown by half)
        room = self.room[i]
        if room is None or room[0] != int_arr or room[1] != float_arr or room[2] < n:
            size = min(ints.max, floats.max // 6)
            room = self.room[i] = (int_arr, float_arr, size,
                                   np.frombuffer(_ffi.buffer(int_arr, 8 * size), dtype=np.int64),
                                   np.frombuffer(_ffi.buffer(float_arr, 48 * size)))
        ids, flat = room[3][:n], room[4][:6 * n]
        self.flat = flat
        rows = ids, flat.reshape(n, 6)
        self.last[i] = (n, int_arr, float_arr, rows, flat)
        return rows
