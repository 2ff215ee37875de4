"""The shared task board's model (§3.4.3): a CC-HTN as a tree of subtasks that agents claim, release, make
progress on and complete — pure logic, no storage.

* Claiming a node claims its descendants; a claim conflicts when the node, an ancestor or a descendant is
  owned by another agent, or when the node is done.
* Releasing returns a node's unfinished subtasks to the pool.
* Only leaves (actions) are completed, by their owner (or the owner of an ancestor), and only once their
  prerequisites are done: every earlier sibling of every chain the leaf is in. A chain or clique is done
  when all its children are.
* Authority is asymmetric (the thesis's lead/assistant): an assistant may not claim, complete or report progress
  on a node the board reserves for leads (``lead_only``), nor on any node containing one or inside one (its
  ancestors are checked as well as its subtree); observers only read.

Every operation either returns the changed board or raises :class:`~supportive.errors.BoardError` with a reason
(invalid, forbidden, missing, conflict) and a message; boards are immutable.

>>> from supportive.tasks.htn import ActionNode, ChainNode
>>> board = TaskBoard.from_node("demo", ChainNode((ActionNode("a"), ActionNode("b")), name="A then B"))
>>> board = board.claim("n0", "robot", "assistant").complete("n1", "robot", "assistant")
>>> [(n.id, n.owner, n.done) for n in board.nodes]
[('n0', 'robot', False), ('n1', 'robot', True), ('n2', 'robot', False)]
>>> board.complete("n2", "robot", "assistant").nodes[0].done
True
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any, Literal

from supportive.errors import BoardError
from supportive.tasks.htn import ActionNode, ChainNode, Node

__all__ = ["ROLES", "BoardNode", "Role", "TaskBoard"]

Role = Literal["lead", "assistant", "observer"]
ROLES: tuple[Role, ...] = ("lead", "assistant", "observer")
"""The roles an agent may have."""


@dataclass(frozen=True)
class BoardNode:
    """One subtask on the board.

    Attributes:
        id: Stable id (``n0`` is the root; ids follow a depth-first walk).
        name: For people: a named subtask's name, or the action's text.
        kind: ``action``, ``chain`` or ``clique``.
        parent: The parent's id (None for the root).
        children: The children's ids, in order.
        action: The action id of a leaf.
        lead_only: Reserved for leads (assistants may not claim or complete it).
        owner: The agent who claimed it, or None.
        done: Completed.
        progress: Reported progress of a leaf, 0–1.
        occurrence: Which performance of its action a leaf is (1 unless the task repeats an action).
    """

    id: str
    name: str
    kind: str
    parent: str | None
    children: tuple[str, ...]
    action: str | None = None
    lead_only: bool = False
    owner: str | None = None
    done: bool = False
    progress: float = 0.0
    occurrence: int = 1


@dataclass(frozen=True)
class TaskBoard:
    """A task tree with claims (see the module docstring)."""

    task: str
    nodes: tuple[BoardNode, ...]

    @classmethod
    def from_node(
        cls,
        task: str,
        root: Node,
        texts: Mapping[str, str] | None = None,
        lead_only: Iterable[str] = (),
    ) -> TaskBoard:
        """The board of a hierarchy: one node per chain, clique and action, depth first.

        Args:
            task: The task's name.
            root: The hierarchy (a learned HTN's root or a task file's structure).
            texts: Words for action ids (default: the ids).
            lead_only: Names (or action ids) of nodes reserved for leads.

        Raises:
            BoardError: (invalid) for a lead_only name that is no node's.
        """
        texts = texts or {}
        reserved = set(lead_only)
        nodes: list[BoardNode] = []

        def add(node: Node, parent: str | None) -> str:
            index = len(nodes)
            ident = f"n{index}"
            nodes.append(BoardNode(ident, "", "", parent, ()))
            if isinstance(node, ActionNode):
                name = texts.get(node.action, node.action)
                nodes[index] = BoardNode(
                    ident,
                    name,
                    "action",
                    parent,
                    (),
                    node.action,
                    bool({name, node.action} & reserved),
                    occurrence=node.occurrence,
                )
                return ident
            children = tuple(add(child, ident) for child in node.children)
            kind = "chain" if isinstance(node, ChainNode) else "clique"
            name = node.name or _describe(kind, [nodes[int(c[1:])].name for c in children])
            nodes[index] = BoardNode(ident, name, kind, parent, children, None, name in reserved)
            return ident

        add(root, None)
        unknown = reserved - {n.name for n in nodes} - {n.action for n in nodes if n.action}
        if unknown:
            raise BoardError("invalid", f"lead-only names that are no subtask's: {', '.join(sorted(unknown))}")
        return cls(task, tuple(nodes))

    # -- reading ---------------------------------------------------------------------------------------------

    def node(self, ident: str) -> BoardNode:
        """The node ``ident``.

        Raises:
            BoardError: (missing) for an unknown id.
        """
        index = _index(ident)
        if index is None or index >= len(self.nodes):
            raise BoardError("missing", f"no subtask {ident!r} on the board")
        return self.nodes[index]

    def subtree(self, ident: str) -> list[BoardNode]:
        """The node and all its descendants, depth first."""
        out = [self.node(ident)]
        for child in out[0].children:
            out += self.subtree(child)
        return out

    def ancestors(self, ident: str) -> list[BoardNode]:
        """The node's ancestors, nearest first."""
        out: list[BoardNode] = []
        parent = self.node(ident).parent
        while parent is not None:
            out.append(self.node(parent))
            parent = out[-1].parent
        return out

    def prerequisites(self, ident: str) -> list[BoardNode]:
        """What must be done before ``ident`` can be completed: every earlier sibling in every chain above it."""
        out: list[BoardNode] = []
        current = self.node(ident)
        while current.parent is not None:
            parent = self.node(current.parent)
            if parent.kind == "chain":
                position = parent.children.index(current.id)
                out += [self.node(sibling) for sibling in parent.children[:position]]
            current = parent
        return out

    def ready(self, ident: str) -> bool:
        """Whether every prerequisite of ``ident`` is done."""
        return all(node.done for node in self.prerequisites(ident))

    @property
    def done_leaves(self) -> frozenset[tuple[str, int]]:
        """The (action, occurrence) leaves completed so far: the task's state."""
        return frozenset((n.action, n.occurrence) for n in self.nodes if n.done and n.action is not None)

    # -- changing ----------------------------------------------------------------------------------------------

    def claim(self, ident: str, agent: str, role: Role) -> TaskBoard:
        """``agent`` claims ``ident`` and its unfinished descendants.

        Raises:
            BoardError: forbidden for an observer, or an assistant and a lead-only node; missing for an unknown
                node; conflict when it is done or another agent owns it, an ancestor or a descendant.
        """
        node = self.node(ident)
        self._may_act(node, role, "claim")
        if node.done:
            raise BoardError("conflict", f"{node.name!r} is already done")
        for other in (*self.ancestors(ident), *self.subtree(ident)):
            if other.owner is not None and other.owner != agent and not other.done:
                raise BoardError("conflict", f"{other.name!r} is claimed by {other.owner}")
        return self._set({n.id: replace(n, owner=agent) for n in self.subtree(ident) if not n.done})

    def release(self, ident: str, agent: str, role: Role) -> TaskBoard:
        """``agent`` gives up ``ident``: its unfinished subtasks go back to the pool.

        Raises:
            BoardError: forbidden for an observer; missing for an unknown node; conflict when it is done or
                ``agent`` does not own it.
        """
        node = self.node(ident)
        self._may_act(node, role, "release", reserved=False)
        if node.done:
            raise BoardError("conflict", f"{node.name!r} is already done: there is nothing to give back")
        if node.owner != agent:
            raise BoardError("conflict", f"{node.name!r} is not claimed by {agent}")
        return self._set(
            {n.id: replace(n, owner=None) for n in self.subtree(ident) if n.owner == agent and not n.done}
        )

    def report(self, ident: str, agent: str, role: Role, progress: float) -> TaskBoard:
        """``agent`` reports progress (0–1) on a leaf it owns.

        Raises:
            BoardError: invalid for progress outside [0, 1]; forbidden, missing, conflict as for complete.
        """
        node = self._owned_leaf(ident, agent, role, "report progress on")
        if not 0.0 <= progress <= 1.0:
            raise BoardError("invalid", f"progress must be between 0 and 1, got {progress}")
        return self._set({ident: replace(node, progress=progress)})

    def complete(self, ident: str, agent: str, role: Role) -> TaskBoard:
        """``agent`` completes a leaf it owns whose prerequisites are done; finished parents complete too.

        Raises:
            BoardError: forbidden when not allowed; missing for an unknown node; conflict for an internal node,
                one not owned by ``agent``, already done, or a prerequisite not done.
        """
        node = self._owned_leaf(ident, agent, role, "complete")
        if node.done:
            raise BoardError("conflict", f"{node.name!r} is already done")
        waiting = [n.name for n in self.prerequisites(ident) if not n.done]
        if waiting:
            raise BoardError("conflict", f"{node.name!r} must wait for {', '.join(repr(w) for w in waiting[:3])}")
        changes = {ident: replace(node, done=True, progress=1.0)}
        board = self._set(changes)
        for ancestor in self.ancestors(ident):
            if all(board.node(child).done for child in ancestor.children):
                board = board._set({ancestor.id: replace(board.node(ancestor.id), done=True)})
        return board

    def mark(self, ident: str, lead_only: bool) -> TaskBoard:
        """The board with ``ident`` reserved for leads (or no longer): how a start brings the board to the
        ``--lead-only`` subtasks it was given (no agent's operation; it does not touch claims).

        Raises:
            BoardError: (missing) for an unknown id.
        """
        return self._set({ident: replace(self.node(ident), lead_only=lead_only)})

    def free(self, ident: str) -> TaskBoard:
        """The board with ``ident``'s claim returned to the pool (only that node; a done one keeps its owner):
        how a start takes back what an agent may no longer hold (a role lowered, a subtask reserved, an agent
        without a working token).

        Raises:
            BoardError: (missing) for an unknown id.
        """
        node = self.node(ident)
        return self if node.done else self._set({ident: replace(node, owner=None)})

    def may_hold(self, ident: str, role: Role) -> bool:
        """Whether an agent of ``role`` may own ``ident``: an observer nothing, an assistant nothing of, in or
        containing a lead-only subtask, a lead anything."""
        if role == "observer":
            return False
        try:
            self._may_act(self.node(ident), role, "hold")
        except BoardError:
            return False
        return True

    def apply(self, op: str, ident: str, agent: str, role: Role, progress: float | None = None) -> TaskBoard:
        """The operation named ``op`` (``claim``, ``release``, ``progress``, ``complete``), for replaying a log;
        and a start's own changes: ``reserve`` and ``unreserve`` (:meth:`mark`), ``free`` (:meth:`free`),
        which no role limits.

        Raises:
            BoardError: as the operation does, and invalid for an unknown operation.
        """
        if op in ("reserve", "unreserve"):
            return self.mark(ident, op == "reserve")
        if op == "free":
            return self.free(ident)
        if op == "claim":
            return self.claim(ident, agent, role)
        if op == "release":
            return self.release(ident, agent, role)
        if op == "complete":
            return self.complete(ident, agent, role)
        if op == "progress":
            return self.report(ident, agent, role, 0.0 if progress is None else progress)
        raise BoardError("invalid", f"unknown operation {op!r}")

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> TaskBoard:
        """The board :meth:`as_dict` wrote (``ready`` is recomputed, not read)."""
        return cls(
            str(data["task"]),
            tuple(
                BoardNode(
                    str(n["id"]),
                    str(n["name"]),
                    str(n["kind"]),
                    n["parent"],
                    tuple(n["children"]),
                    n["action"],
                    bool(n["lead_only"]),
                    n["owner"],
                    bool(n["done"]),
                    float(n["progress"]),
                    int(n.get("occurrence", 1)),
                )
                for n in data["nodes"]
            ),
        )

    def as_dict(self) -> dict[str, Any]:
        """Plain JSON data: the task and every node."""
        return {
            "task": self.task,
            "nodes": [
                {
                    "id": n.id,
                    "name": n.name,
                    "kind": n.kind,
                    "parent": n.parent,
                    "children": list(n.children),
                    "action": n.action,
                    "lead_only": n.lead_only,
                    "owner": n.owner,
                    "done": n.done,
                    "progress": n.progress,
                    "occurrence": n.occurrence,
                    "ready": ready,
                }
                for n, ready in zip(self.nodes, self._readiness(), strict=True)
            ],
        }

    def _readiness(self) -> list[bool]:
        """:meth:`ready` of every node in one pass down the tree: a node is ready when its parent is and, in
        a chain, every earlier sibling is done."""
        ready = [True] * len(self.nodes)
        for index, node in enumerate(self.nodes):  # depth first: a parent comes before its children
            if node.kind == "action":
                continue
            earlier_done = True
            for child in node.children:
                position = int(child[1:])
                ready[position] = ready[index] and (earlier_done or node.kind != "chain")
                earlier_done = earlier_done and self.nodes[position].done
        return ready

    # -- helpers ---------------------------------------------------------------------------------------------

    def _may_act(self, node: BoardNode, role: Role, verb: str, *, reserved: bool = True) -> None:
        if role == "observer":
            raise BoardError("forbidden", f"observers may not {verb} subtasks")
        if not reserved or role != "assistant":
            return
        if node.lead_only or any(n.lead_only for n in self.subtree(node.id)):
            raise BoardError("forbidden", f"{node.name!r} is reserved for leads: an assistant may not {verb} it")
        above = next((n for n in self.ancestors(node.id) if n.lead_only), None)
        if above is not None:
            raise BoardError(
                "forbidden", f"{node.name!r} is part of {above.name!r}, reserved for leads: an assistant may not {verb} it"
            )

    def _owned_leaf(self, ident: str, agent: str, role: Role, verb: str) -> BoardNode:
        node = self.node(ident)
        self._may_act(node, role, verb)
        if node.kind != "action":
            raise BoardError("conflict", f"{node.name!r} is not a single action: {verb} its actions one by one")
        if node.owner != agent:
            raise BoardError("conflict", f"{node.name!r} is not claimed by {agent}")
        return node

    def _set(self, changes: Mapping[str, BoardNode]) -> TaskBoard:
        return TaskBoard(self.task, tuple(changes.get(n.id, n) for n in self.nodes))


def _index(ident: str) -> int | None:
    number = ident[1:]
    if ident[:1] != "n" or not (number.isascii() and number.isdigit()):  # "n²" is no id
        return None
    return int(ident[1:])


def _describe(kind: str, names: Sequence[str]) -> str:
    shown = [name if len(name) <= 24 else name[:23] + "…" for name in names[:3]]
    more = f", +{len(names) - 3}" if len(names) > 3 else ""
    return (" → ".join(shown) if kind == "chain" else "{" + ", ".join(shown) + "}") + more
