"""The Verlet cloth against compiled C: part of `python -m app bench cloth`.

The same step (drag, gravity, the Verlet update, then `iterations` Gauss-Seidel sweeps over the
same batches of rods in the same order: the colour split of app/physics/rods.py) is written in C
below, compiled twice into a temporary directory when a C compiler (cc or gcc) is on the PATH,
and loaded with ctypes:
  * scalar C: -O2 -fno-tree-vectorize, one rod at a time;
  * SIMD C:   -O3 -march=native, the rods of a batch share no particle (`#pragma GCC ivdep`
    says so), so the compiler solves several at once in vector registers.
Each is timed beside the cloth's own step, NumPy and (if numba is installed) the numba kernel,
on the same cloth in the same state, in interleaved rounds; the ratios are cloth / C.
Without a compiler the table says so and no ratio is printed.
"""

from __future__ import annotations

import ctypes
import os
import shutil
import statistics
import signal
import subprocess
import tempfile
import time

import numpy as np

from app.bench import Report
from app.physics import rods_compiled
from app.physics.cloth import Cloth

GOALS = {"simd_128": 3.0, "scalar_32": 2.0}   # issue 28: cloth / C at most this

SOURCE = r"""
#include <math.h>
void cloth_step(float *x, float *xp, const float *freem, int rows, int cols, float dragf,
                float gh2, const long long *meta, int nb, const float *rest, const float *ka,
                const float *kb, int iterations) {
    int n = rows * cols;
    float *X = x, *Y = x + n, *PX = xp, *PY = xp + n;
    for (int i = 0; i < n; i++) {            /* drag, gravity, Verlet */
        float vx = (X[i] - PX[i]) * dragf, vy = (Y[i] - PY[i]) * dragf + gh2;
        vx *= freem[i]; vy *= freem[i];
        PX[i] = X[i]; PY[i] = Y[i];
        X[i] += vx; Y[i] += vy;
    }
    for (int it = 0; it < iterations; it++) {
        for (int b = 0; b < nb; b++) {
            const long long *m = meta + 9 * b;
            long long r0 = m[0], nr = m[1], rs = m[2], c0 = m[3], nc = m[4], cs = m[5];
            long long dr = m[6], dc = m[7], k0 = m[8];
            float rst = rest[b];
            for (long long i = 0; i < nr; i++) {
                long long a0 = (r0 + i * rs) * cols + c0, b0 = a0 + dr * cols + dc;
                const float *KA = ka + k0 + i * nc, *KB = kb + k0 + i * nc;
#pragma GCC ivdep
                for (long long j = 0; j < nc; j++) {
                    long long ia = a0 + j * cs, ib = b0 + j * cs;
                    float dx = X[ib] - X[ia], dy = Y[ib] - Y[ia];
                    float len = sqrtf(dx * dx + dy * dy);
                    len = len > 1e-9f ? len : 1e-9f;
                    float diff = 1.0f - rst / len;
                    dx *= diff; dy *= diff;
                    X[ia] += dx * KA[j]; Y[ia] += dy * KA[j];
                    X[ib] -= dx * KB[j]; Y[ib] -= dy * KB[j];
                }
            }
        }
    }
}
"""

FLAGS = {"scalar C (-O2, no vectorising)": ["-O2", "-fno-tree-vectorize"],
         "SIMD C (-O3 -march=native)": ["-O3", "-march=native"]}


def compiler() -> str | None:
    """The C compiler on the PATH (cc, then gcc), or None."""
    return shutil.which("cc") or shutil.which("gcc")


def compile_c(args: list[str]) -> None:
    """Run the compiler in a process group of its own, ended whole if the bench stops (Ctrl-C):
    cc's linker (collect2, ld) outlived an interrupted bench otherwise (hostile run, seed 27).
    CalledProcessError if it fails."""
    p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    try:
        out, err = p.communicate()
    except BaseException:
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except OSError:
            pass
        p.wait()
        raise
    if p.returncode:
        raise subprocess.CalledProcessError(p.returncode, args, out, err)


_BUILT: dict[tuple, dict[str, ctypes.CDLL]] = {}   # this process's compiled libraries, by build_key


def build_key(cc: str) -> tuple:
    """What decides the libraries build() makes: the compiler (its real path and that file's
    identity: a compiler replaced or upgraded is another key), the source and the flags."""
    real = os.path.realpath(shutil.which(cc) or cc)
    st = os.stat(real)
    return (real, st.st_ino, st.st_size, st.st_mtime_ns, SOURCE,
            tuple((label, tuple(flags)) for label, flags in FLAGS.items()))


def build(cc: str, workdir: str) -> dict[str, ctypes.CDLL]:
    """Compile SOURCE once per flag set; {label: library}. A failed compile raises. A second
    build with the same key (build_key) in one process returns the libraries already loaded
    (~0.45 s of compiling: the tests build them in several places); they stay mapped when the
    first build's folder is gone."""
    key = build_key(cc)
    if key in _BUILT:
        return dict(_BUILT[key])
    src = os.path.join(workdir, "cloth_step.c")
    with open(src, "w") as f:
        f.write(SOURCE)
    libs = {}
    for k, (label, flags) in enumerate(FLAGS.items()):
        out = os.path.join(workdir, f"cloth_step_{k}.so")
        compile_c([cc, *flags, "-shared", "-fPIC", "-o", out, src, "-lm"])
        lib = ctypes.CDLL(out)
        lib.cloth_step.restype = None
        libs[label] = lib
    _BUILT[key] = dict(libs)
    return libs


def make_cloth(n: int, kernel: str = "numpy") -> Cloth:
    """An n x n cloth, structural + shear, top row pinned, gravity and drag, 10 iterations,
    hung for 30 steps (the bench's cloth fills the same area at every size)."""
    c = Cloth(n, n, 480.0 / n, (240.0, 40.0),
              effects={"structural", "shear", "gravity", "drag"})
    c.iterations = 10
    c.kernel = kernel
    for _ in range(30):
        c.step(1 / 60)
    return c


def c_stepper(lib: ctypes.CDLL, cloth: Cloth, h: float):
    """A function doing one C step of h on copies of the cloth's state."""
    x, xp = cloth.x.copy(), cloth.x_prev.copy()
    free = np.ascontiguousarray(cloth.free, dtype=np.float32)
    packed = cloth.compiled_plan()
    meta = np.ascontiguousarray(packed.meta, dtype=np.int64)
    ptr = ctypes.POINTER(ctypes.c_float)
    args = [x.ctypes.data_as(ptr), xp.ctypes.data_as(ptr), free.ctypes.data_as(ptr),
            ctypes.c_int(cloth.rows), ctypes.c_int(cloth.cols),
            ctypes.c_float((1.0 - cloth.drag) ** (h * 60.0)),
            ctypes.c_float(cloth.gravity * h * h),
            meta.ctypes.data_as(ctypes.POINTER(ctypes.c_longlong)), ctypes.c_int(len(meta)),
            packed.rest.ctypes.data_as(ptr), packed.ka.ctypes.data_as(ptr),
            packed.kb.ctypes.data_as(ptr), ctypes.c_int(cloth.iterations)]
    keep = (x, xp, free, meta, packed)           # alive while the stepper is

    def step() -> None:
        lib.cloth_step(*args)
    step.keep = keep
    return step


def interleaved(fns: dict[str, callable], number: int, rounds: int) -> dict[str, list[float]]:
    """Seconds per call of each function, `rounds` times, the functions taking turns."""
    out = {k: [] for k in fns}
    names = list(fns)
    for r in range(rounds):
        for name in names[r % len(names):] + names[:r % len(names)]:
            fn = fns[name]
            t0 = time.perf_counter()
            for _ in range(number):
                fn()
            out[name].append((time.perf_counter() - t0) / number)
    return out


def run(report: Report) -> dict:
    sizes = [32, 64] if report.quick else [32, 64, 128]
    rounds = 2 if report.quick else 9
    cc = compiler()
    h = 1 / 60
    result: dict = {"compiler": cc, "numba": rods_compiled.available(), "sizes": []}
    if cc is None:
        report.say("\nno C compiler (cc or gcc) on the PATH: the cloth is not compared with C")
    kernels = ["numpy"] + (["numba"] if rods_compiled.available() else [])
    if not rods_compiled.available():
        report.say("numba is not installed: the optional numba kernel is not measured")
    with tempfile.TemporaryDirectory(prefix="cloth_c_") as tmp:
        libs = build(cc, tmp) if cc else {}
        rows = []
        for n in sizes:
            report.progress(f"cloth vs C, {n}x{n}")
            fns = {}
            for k in kernels:
                cloth = make_cloth(n, k)
                fns[f"cloth ({k})"] = (lambda c=cloth: c.step(h))
            for label, lib in libs.items():
                fns[label] = c_stepper(lib, make_cloth(n), h)
            number = max(1, int((200 if report.quick else 2000) / (n * n / 16)))
            times = interleaved(fns, number, rounds)
            ms = {k: statistics.median(v) * 1e3 for k, v in times.items()}
            spread = {k: (max(v) - min(v)) * 1e3 for k, v in times.items()}
            entry = {"n": n, "ms": ms, "spread_ms": spread}
            for k in kernels:
                for label in libs:
                    entry[f"{k}/{label}"] = ms[f"cloth ({k})"] / ms[label]
            result["sizes"].append(entry)
            for name in fns:
                ratios = [ms[name] / ms[label] for label in libs]
                rows.append([f"{n}x{n}", name, ms[name], spread[name], *ratios])
        report.table("The Verlet cloth's step against C (structural + shear, 10 iterations, ms "
                     f"per step, median of {rounds} interleaved rounds)",
                     ["cloth", "version", "ms", "spread", *[f"/ {lab}" for lab in libs]], rows)
    if libs:
        simd, scalar = list(libs)[1], list(libs)[0]
        by_n = {e["n"]: e for e in result["sizes"]}
        big = 128 if 128 in by_n else sizes[-1]
        for k in kernels:
            a = by_n[big][f"{k}/{simd}"]
            b = by_n[32][f"{k}/{scalar}"]
            result[f"{k}_vs_simd_{big}"] = a
            result[f"{k}_vs_scalar_32"] = b
            report.say(f"cloth ({k}): {a:.2f}x the SIMD C at {big}x{big} (goal <= "
                       f"{GOALS['simd_128']:g}x), {b:.2f}x the scalar C at 32x32 (goal <= "
                       f"{GOALS['scalar_32']:g}x)")
    return result
