"""A cache in front of pygame_gui's theming ids (pygame_gui 0.6.14, the newest).

Every pygame_gui element asks its theme for the list of ids it is styled by
(UIAppearanceTheme.build_all_combined_ids). pygame_gui caches that list, but builds the cache's
key with nested str.join calls over the reprs of the four id lists, so the key's length is the
product of theirs: 3,052,501 characters for a button in the panel's scroll bar. Building keys was
a third of opening a scene's panel (442 calls for three scenes, 26 distinct, 0.34 s; measured
2026-11-26), paid again for every element of every scene opened.

The lists depend on the four id lists only (pygame_gui's own cache already returns one shared
list per key), so this cache, keyed by the lists as tuples, answers before pygame_gui's is asked.
"""

from __future__ import annotations

from pygame_gui.core.ui_appearance_theme import UIAppearanceTheme

_ORIGINAL = UIAppearanceTheme.build_all_combined_ids
_IDS: dict[tuple, list[str]] = {}


def _key(ids) -> tuple | None:
    return None if ids is None else tuple(ids)


def build_all_combined_ids(theme, element_base_ids, element_ids, class_ids, object_ids):
    key = (_key(element_base_ids), _key(element_ids), _key(class_ids), _key(object_ids))
    ids = _IDS.get(key)
    if ids is None:
        ids = _IDS[key] = _ORIGINAL(theme, element_base_ids, element_ids, class_ids, object_ids)
    return ids


def install() -> None:
    """Put the cache in front (idempotent)."""
    UIAppearanceTheme.build_all_combined_ids = build_all_combined_ids
