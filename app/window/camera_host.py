"""Zoom and pan for the views of a running scene (one scene, or a comparison): the mouse wheel
zooms about the pointer, a middle-button drag pans, key 0 fits the view again; while a button
drags the content, its view holds still. The transform itself is app/draw/view.py's Camera; this
is what the window's views share of it (a mixin: `self.camera`, `self.pane`, `self.dragging`,
`scene_area()` come from the view).
"""

from __future__ import annotations

from typing import Any

import pygame

from app.draw.view import ZOOM_STEP, Camera


class CameraHost:
    """A mixin for SceneView (and CompareView, which overrides layout_at)."""

    def setup_camera(self) -> None:
        self.camera = Camera()              # zoom and pan on top of the fitted view
        self.panning: tuple[int, int] | None = None    # where the middle-button drag is now
        self._pan_layout = None             # the layout of the pane the drag began in
        self.pointer = (0, 0)               # the mouse's last position (the wheel has none)

    def zoom_state(self) -> list[str]:
        """The HUD's word on the zoom while the view is not the fitted one."""
        return [] if self.camera.fitted else [
            f"zoom x{self.camera.zoom:.2g} (0 fits the view again)"]

    def fit_view(self) -> None:
        """0: undo the zoom and the pan (the content fitted to its room again)."""
        self.camera.reset()
        self.panning = None

    # --- zoom and pan (the camera: app/draw/view.py) --------------------------------------------
    def layout_at(self, pos) -> Any:
        """The layout of the pane under the screen point `pos` (None: none there)."""
        layout = self.pane.layout
        return layout if layout is not None and self.scene_area().collidepoint(pos) else None

    def camera_event(self, ev: pygame.event.Event, consumed: bool) -> bool:
        """The mouse wheel zooms about the pointer, a middle-button drag pans: True if `ev`
        was one of those (it never reaches the scene, nor the recording: the world coordinates
        a scene receives are the same at any zoom)."""
        if ev.type == pygame.MOUSEMOTION:
            self.pointer = ev.pos
            if self.panning is not None:
                layout = self._pan_layout
                if layout is not None:
                    self.camera.pan(layout.fitted or layout.view,
                                    (ev.pos[0] - self.panning[0], ev.pos[1] - self.panning[1]))
                self.panning = ev.pos
                return True
            return False
        if ev.type == pygame.MOUSEWHEEL:
            pos = getattr(ev, "pos", None) or self.pointer
            layout = None if consumed else self.layout_at(pos)
            if layout is not None and ev.y:
                self.camera.zoom_at(layout.fitted or layout.view, layout.free, pos,
                                    ZOOM_STEP ** ev.y)
            return True
        if ev.type in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP) and ev.button == 2:
            down = ev.type == pygame.MOUSEBUTTONDOWN
            self._pan_layout = self.layout_at(ev.pos) if down and not consumed else None
            self.panning = ev.pos if self._pan_layout is not None else None
            return True
        return False

    def pane_hold(self) -> None:
        """While a button drags the content, its view holds still (no re-fit under the
        pointer as the cloth swings); it follows the content again on release."""
        for p in getattr(self.pane, "panes", [self.pane]):
            if bool(self.dragging) != (p.held is not None):
                p.hold(bool(self.dragging))



__all__ = ["CameraHost"]
