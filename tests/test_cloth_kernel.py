"""The cloth's optional numba kernel (app/physics/rods_compiled.py): the same physics as the NumPy
batches, and refused with one line where numba is missing."""

import numpy as np
import pytest

from app.physics import rods_compiled
from app.physics.cloth import Cloth
from app.scene import InputEvent, ParamError
from scenes.cloth import ClothScene

needs_numba = pytest.mark.skipif(not rods_compiled.available(), reason="numba not installed")


def twins(**kw) -> tuple[Cloth, Cloth]:
    out = []
    for kernel in ("numpy", "numba"):
        c = Cloth(12, 16, 20.0, (100.0, 50.0), kw.get("pins", "top"),
                  kw.get("effects", {"structural", "shear", "bending", "gravity", "drag"}))
        c.kernel = kernel
        out.append(c)
    return out[0], out[1]


@needs_numba
def test_the_numba_kernel_moves_every_particle_as_the_numpy_batches_do():
    a, b = twins(pins="corners")
    for k in range(120):
        if k == 30:                       # a grab, a drag and a release change the weights
            for c in (a, b):
                c.grab((11, 8), (300.0, 400.0))
        if k == 40:
            for c in (a, b):
                c.move_grab((500.0, 450.0))
        if k == 60:
            for c in (a, b):
                c.release()
        for c in (a, b):
            c.step(1 / 60)
    assert np.allclose(a.x, b.x, atol=1e-3) and np.abs(a.x - a.rest_x).max() > 50


@needs_numba
def test_the_numba_kernel_sees_torn_rods_and_easing_rods():
    a, b = twins(effects={"structural", "gravity", "tearing"})
    for c in (a, b):
        c.tear_ratio = 1.05
        c.grab((11, 15), (900.0, 700.0))        # yanked far: rods tear
    for k in range(40):
        if k == 20:                             # shear on mid-run: its rods ease in (NumPy)
            for c in (a, b):
                c.set_effects(c.on | {"shear"})
        for c in (a, b):
            c.step(1 / 60)
    assert a.torn_count() == b.torn_count() > 0
    assert np.allclose(a.x, b.x, atol=1e-3)


@needs_numba
def test_the_hud_names_the_numba_kernel():
    scene = ClothScene({"rows": 8, "cols": 8, "kernel": "numba"})
    scene.advance()
    assert "numba kernel" in scene.hud_lines()[0]
    scene.set("kernel", "numpy")
    scene.handle_event(InputEvent("mouse_move", (10.0, 10.0), 0))
    scene.advance()
    assert "numba" not in scene.hud_lines()[0] and scene.cloth.kernel == "numpy"


def test_without_numba_the_kernel_is_refused_in_one_line(monkeypatch):
    monkeypatch.setattr(rods_compiled, "numba", None)
    with pytest.raises(ParamError, match="needs numba"):
        ClothScene({"kernel": "numba"})
    scene = ClothScene({"rows": 4, "cols": 4})
    with pytest.raises(ParamError, match="needs numba"):
        scene.set("kernel", "numba")
    assert scene.p["kernel"] == "numpy"
