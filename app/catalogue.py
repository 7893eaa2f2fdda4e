"""The scene catalogue behind `python -m app --list --json`: every scene with what a teacher or a
script needs to drive it without opening the window: its parameters (name, kind, default, range
or choices, help), its effects and its "try this" cards (label, settings, what to watch for;
`comparisons`: the cards that run variants side by side, each with `compare`, its variants as
--compare takes them).

It is read from the scene classes themselves (the registry, scenes/__init__.py), so it is never
out of date. Plain Python: no pygame, no scene is built.
"""

from __future__ import annotations

import inspect
import shlex
from typing import Any

from app.scene import Effect, Param, Scene, Try, variant_text


def param_entry(prm: Param) -> dict[str, Any]:
    """One parameter: kind is "int", "float", "bool" or "choice"; numbers have a range
    [lo, hi] (inclusive), choices their list; live is false when a change rebuilds the scene."""
    kind = "choice" if prm.choices is not None else prm.kind.__name__
    entry: dict[str, Any] = {"name": prm.name, "kind": kind, "default": prm.default}
    if prm.choices is not None:
        entry["choices"] = list(prm.choices)
    elif prm.kind in (int, float):
        entry["range"] = [prm.lo, prm.hi]
    entry["help"] = prm.help
    entry["live"] = not prm.rebuild
    return entry


def effect_entry(eff: Effect) -> dict[str, Any]:
    return {"name": eff.name, "default": "on" if eff.default else "off", "help": eff.help,
            "strength": eff.amount or None}


def card_entry(card: Try) -> dict[str, Any]:
    """A try card: its settings as `--set` takes them (on/off for effects and switches)."""
    settings = {k: (("on" if v else "off") if isinstance(v, bool) else v)
                for k, v in card.settings.items()}
    entry = {"label": card.label, "settings": settings, "watch": card.watch}
    if card.compare:         # a comparison: each pane's own settings, as --compare takes them
        entry["compare"] = [variant_text(v) for v in card.compare]
    return entry


def scene_entry(cls: type[Scene]) -> dict[str, Any]:
    doc = inspect.cleandoc(cls.__doc__ or "")
    summary = " ".join(doc.split("\n\n")[0].split()) if doc else cls.title
    def entries(cards):
        return [{**card_entry(card),
                 "command": f"python -m app --scene {cls.name} --try {shlex.quote(card.label)}"}
                for card in cards]
    path = getattr(cls, "path", "")       # a scene file (app/scenefile): where it is
    return {"name": cls.name, "title": cls.title, "category": cls.category,
            **({"path": path} if path else {}),
            "summary": summary,
            "params": [param_entry(p) for p in cls.all_params()],
            "effects": [effect_entry(e) for e in cls.effects],
            "tries": entries(cls.tries),
            "comparisons": entries(cls.comparisons)}   # cards that run variants side by side


def catalogue(scenes: list[type[Scene]]) -> list[dict[str, Any]]:
    """Every scene's entry, in the registry's order."""
    return [scene_entry(cls) for cls in scenes]


__all__ = ["catalogue", "scene_entry", "param_entry", "effect_entry", "card_entry"]
