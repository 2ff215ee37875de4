"""What a start does when the board's database and the command line disagree (pure logic, no storage).

* **The task.** A board is made from one task; a database whose board has another structure than the task
  file now gives (an action added, a subtask renamed, …) is refused: :func:`structure_change` says where they
  first differ. Nothing is migrated behind the lab's back: the old board's history stays as it was.
* **Lead-only marks** follow the command line (:func:`reconcile_board`): a subtask named with ``--lead-only``
  is reserved, one no longer named is not.
* **Claims** an agent may no longer hold go back to the pool: an observer holds nothing, an assistant nothing
  of, in or containing a lead-only subtask, and an agent without a working token nothing (nobody could finish
  it). A done subtask keeps its owner.

Each change is an operation of the board's log (``reserve``, ``unreserve``, ``free``; see
:meth:`~supportive.social.board.TaskBoard.apply`), so replaying the log on the initial board still gives the
current one, and a sentence for the banner.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping

from supportive.service.agents import with_article
from supportive.social.board import BoardNode, Role, TaskBoard

__all__ = ["START", "Change", "reconcile_board", "structure_change"]

START = "(start)"
"""The agent a start's own ``reserve`` and ``unreserve`` operations are logged under."""

Change = tuple[str, str, str]
"""One operation of a start: (op, node id, agent)."""


def _shape(node: BoardNode) -> tuple[object, ...]:
    return (node.id, node.name, node.kind, node.parent, node.children, node.action, node.occurrence)


def structure_change(stored: TaskBoard, wanted: TaskBoard) -> str | None:
    """Where the board in the database (``stored``, as it was made) and the one the task file gives now
    (``wanted``) first differ in structure — a subtask's name, kind, place, action — or None when they agree
    (lead-only marks, owners and progress are not structure)."""
    for old, new in zip(stored.nodes, wanted.nodes, strict=False):
        if _shape(old) != _shape(new):
            return f"subtask {old.id} was {old.name!r} ({old.kind}), the task file now gives {new.name!r} ({new.kind})"
    if len(stored.nodes) != len(wanted.nodes):
        return f"the board has {len(stored.nodes)} subtasks, the task file now gives {len(wanted.nodes)}"
    return None


def reconcile_board(
    board: TaskBoard, wanted: TaskBoard, roles: Mapping[str, Role], working: Collection[str]
) -> tuple[TaskBoard, list[Change], list[str]]:
    """Bring ``board`` (the current one) to ``wanted``'s lead-only marks, then give back every claim its owner
    may no longer hold (``roles``: every agent's role now; ``working``: the agents with a working token).

    Returns:
        The board after, the operations done (in order), and one sentence per change.
    """
    changes: list[Change] = []
    said: list[str] = []
    for old, new in zip(board.nodes, wanted.nodes, strict=True):
        if old.lead_only != new.lead_only:
            op = "reserve" if new.lead_only else "unreserve"
            board = board.apply(op, old.id, START, "lead")
            changes.append((op, old.id, START))
            said.append(f"{old.name!r} ({old.id}) is {'now' if new.lead_only else 'no longer'} lead-only")
    freed: set[str] = set()
    for node in board.nodes:  # depth first: a parent before its children
        if node.owner is None or node.done:
            continue
        role = roles.get(node.owner)
        if node.owner in working and role is not None and board.may_hold(node.id, role):
            continue
        board = board.apply("free", node.id, node.owner, "lead")
        changes.append(("free", node.id, node.owner))
        freed.add(node.id)
        if node.parent not in freed:  # one sentence per subtree given back
            why = "has no working token" if node.owner not in working or role is None else f"is {with_article(role)}"
            said.append(f"{node.owner}'s claim of {node.name!r} ({node.id}) went back to the pool: {node.owner} {why}")
    return board, changes, said
