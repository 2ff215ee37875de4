"""The words of generated tasks: furniture, parts, connectors, and the text people read for an action id."""

from __future__ import annotations

__all__ = [
    "CONNECTORS",
    "FURNITURE",
    "PARTS",
    "VERBS",
    "action_text",
]

FURNITURE: tuple[str, ...] = (
    "chair",
    "table",
    "shelf",
    "cabinet",
    "desk",
    "bed",
    "dresser",
    "bench",
    "stool",
)
"""What a generated IKEA-like task assembles (its root's name)."""

PARTS: tuple[str, ...] = (
    "leg",
    "rail",
    "side_panel",
    "shelf",
    "back_panel",
    "door",
    "drawer",
    "top",
    "seat",
    "backrest",
    "frame",
    "support",
    "plinth",
    "divider",
    "handle",
)
"""Kinds of part that are picked up and placed."""

CONNECTORS: tuple[str, ...] = ("bolt", "screw", "dowel", "cam_lock", "peg", "bracket")
"""Kinds of connector that fasten parts."""

VERBS: dict[str, str] = {
    "pick": "pick up",
    "place": "place",
    "fasten": "fasten",
    "insert": "insert",
    "tighten": "tighten",
    "step": "perform step",
}
"""Action-id prefix -> the verb phrase of its text."""


def action_text(action: str) -> str:
    """The text people read for a generated action id: ``pick_side_panel_3 -> "pick up side panel 3"``.

    >>> action_text("pick_side_panel_3"), action_text("fasten_bolt_12"), action_text("step_7")
    ('pick up side panel 3', 'fasten bolt 12', 'perform step 7')
    """
    verb, _, rest = action.partition("_")
    phrase = VERBS.get(verb, verb)
    return f"{phrase} {rest.replace('_', ' ')}".strip()
