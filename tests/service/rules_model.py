"""An independent model of the board's rules (docs/service.md, "The board's rules"), written from the docs and
not from :mod:`supportive.social.board`: what status each operation gets and what the board holds after it,
and what a start does when the command line changes (roles, lead-only marks, tokens). The property test and
the restart tests compare the service with it."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any


@dataclass
class RulesModel:
    """The board's tree (from ``GET /api/board``'s nodes), and who owns and has done what."""

    parent: dict[str, str | None]
    children: dict[str, list[str]]
    kind: dict[str, str]
    lead_only: set[str] = field(default_factory=set)
    owner: dict[str, str] = field(default_factory=dict)
    done: set[str] = field(default_factory=set)
    progress: dict[str, float] = field(default_factory=dict)

    @classmethod
    def of(cls, nodes: list[dict[str, Any]]) -> RulesModel:
        """The model of a board given as JSON nodes (their structure, lead-only marks, owners, done)."""
        return cls(
            {n["id"]: n["parent"] for n in nodes},
            {n["id"]: list(n["children"]) for n in nodes},
            {n["id"]: n["kind"] for n in nodes},
            {n["id"] for n in nodes if n["lead_only"]},
            {n["id"]: n["owner"] for n in nodes if n["owner"] is not None},
            {n["id"] for n in nodes if n["done"]},
            {n["id"]: float(n["progress"]) for n in nodes},
        )

    def below(self, node: str) -> list[str]:
        """The node and everything under it."""
        out = [node]
        for child in self.children[node]:
            out += self.below(child)
        return out

    def above(self, node: str) -> list[str]:
        """Every ancestor."""
        out = []
        while self.parent[node] is not None:
            node = self.parent[node]  # type: ignore[assignment]
            out.append(node)
        return out

    def touches_lead_only(self, node: str) -> bool:
        """Whether the node is lead-only, holds one, or is inside one."""
        return any(n in self.lead_only for n in (*self.below(node), *self.above(node)))

    def may_hold(self, node: str, role: str) -> bool:
        return role == "lead" or (role == "assistant" and not self.touches_lead_only(node))

    def waiting(self, node: str) -> bool:
        """Whether some earlier sibling in a chain above the node is not done."""
        current = node
        while self.parent[current] is not None:
            up: str = self.parent[current]  # type: ignore[assignment]
            if self.kind[up] == "chain":
                siblings = self.children[up]
                if any(s not in self.done for s in siblings[: siblings.index(current)]):
                    return True
            current = up
        return False

    def step(self, op: str, node: str, agent: str, role: str, value: float = 0.5) -> int:
        """Apply one operation; its HTTP status."""
        if node not in self.kind:
            return 404
        if role == "observer":
            return 403
        if role == "assistant" and op != "release" and self.touches_lead_only(node):
            return 403
        if op == "claim":
            if node in self.done:
                return 409
            if any(self.owner.get(n, agent) != agent and n not in self.done for n in (*self.above(node), *self.below(node))):
                return 409
            for n in self.below(node):
                if n not in self.done:
                    self.owner[n] = agent
            return 200
        if op == "release":
            if node in self.done or self.owner.get(node) != agent:
                return 409
            for n in self.below(node):
                if self.owner.get(n) == agent and n not in self.done:
                    del self.owner[n]
            return 200
        if self.kind[node] != "action" or self.owner.get(node) != agent:
            return 409
        if op == "progress":
            self.progress[node] = value
            return 200
        if node in self.done or self.waiting(node):
            return 409
        self.done.add(node)
        self.progress[node] = 1.0
        for n in self.above(node):
            if all(c in self.done for c in self.children[n]):
                self.done.add(n)
        return 200

    def restart(self, lead_only: set[str], roles: Mapping[str, str], working: set[str]) -> None:
        """A start with these lead-only marks, roles and agents with a working token: the marks are the
        command line's; an unfinished claim its owner may no longer hold goes back to the pool."""
        self.lead_only = set(lead_only)
        for node, agent in list(self.owner.items()):
            if node in self.done:
                continue
            if agent not in working or not self.may_hold(node, roles.get(agent, "observer")):
                del self.owner[node]

    def matches(self, nodes: list[dict[str, Any]]) -> list[str]:
        """How the board given as JSON nodes differs from the model (empty when it does not)."""
        problems = []
        for n in nodes:
            ident = n["id"]
            want = (self.owner.get(ident), ident in self.done, ident in self.lead_only)
            got = (n["owner"], n["done"], n["lead_only"])
            if want != got:
                problems.append(f"{ident}: model (owner, done, lead_only) {want}, board {got}")
        return problems
