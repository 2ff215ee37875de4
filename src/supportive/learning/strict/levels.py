"""The task graph at one level of compaction, and the graph operations of Algorithms 2–4.

At level 0 every edge of the environment-space task graph performs one subgoal. Compacting a chain or a clique
replaces the edges of its members by one edge per way into it: from the state where it starts to the state where
it is finished. A state in which a compacted node is half done disappears. The conjugate graph of a level (its
subgoals and meta-nodes as vertices, the states between two edges as prerequisites) is the line graph of this
graph, so everything Algorithm 2 asks of the CTG is answered here without materialising it.

Each state keeps the bit mask of the primitive subgoals done, so "is this node done, not started, or half done
in this state" is one ``&``.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field

from supportive.learning.reachability import reachable

__all__ = ["Group", "LevelGraph", "Ordering"]


@dataclass(frozen=True)
class Group:
    """Members to compact into one node: ``ordered`` for a chain (in order), otherwise a clique."""

    members: tuple[int, ...]
    ordered: bool
    mask: int


@dataclass
class Ordering:
    """First-occurrence rank of each node, for deterministic choices and root order."""

    rank: dict[int, int] = field(default_factory=dict)

    def key(self, nodes: Iterable[int]) -> int:
        """The earliest rank among ``nodes``."""
        return min(self.rank[n] for n in nodes)


class LevelGraph:
    """Edges ``src --node--> dst`` between states; ``state_mask`` and ``node_mask`` are shared, read-only."""

    def __init__(
        self,
        by_node: dict[int, list[tuple[int, int]]],
        initial: frozenset[int],
        terminal: frozenset[int],
        state_mask: Sequence[int],
        node_mask: Mapping[int, int],
    ) -> None:
        self.by_node = by_node
        self.initial = initial
        self.terminal = terminal
        self.state_mask = state_mask
        self.node_mask = node_mask
        self.out: dict[int, dict[int, int]] = {}
        self.into: dict[int, dict[int, list[int]]] = {}
        for node, edges in by_node.items():
            for src, dst in edges:
                self.out.setdefault(src, {})[node] = dst
                self.into.setdefault(dst, {}).setdefault(node, []).append(src)

    @property
    def n_edges(self) -> int:
        """Number of edges."""
        return sum(len(edges) for edges in self.by_node.values())

    def signature(self) -> tuple[int, int, int]:
        """Cheap identity for graphs that only ever grow: edge, initial and terminal counts."""
        return self.n_edges, len(self.initial), len(self.terminal)

    # ------------------------------------------------------------------ chains
    def chain_links(self, ignore: dict[int, set[int]] | None = None) -> dict[int, int]:
        """Links ``u -> v`` where u's only CTG successor is v and v's only CTG predecessor is u (§2.1.4).

        ``ignore`` maps a node to successors that do not count (Algorithm 3 drops edges between commutative
        subgoals this way).
        """
        ignore = ignore or {}
        links: dict[int, int] = {}
        for u, edges in self.by_node.items():
            skip = ignore.get(u, set())
            succ: int | None = None
            for _, dst in edges:
                if dst in self.terminal:
                    succ = None
                    break
                following = [v for v in self.out.get(dst, {}) if v not in skip]
                if len(following) != 1 or (succ is not None and following[0] != succ):
                    succ = None
                    break
                succ = following[0]
            if succ is not None and self._only_predecessor(u, succ, ignore):
                links[u] = succ
        return links

    def _only_predecessor(self, u: int, v: int, ignore: dict[int, set[int]]) -> bool:
        for src, _ in self.by_node[v]:
            if src in self.initial:
                return False
            if any(p != u and v not in ignore.get(p, ()) for p in self.into.get(src, {})):
                return False
        return True

    def chains(self, ordering: Ordering, ignore: dict[int, set[int]] | None = None) -> list[Group]:
        """The maximal chains: runs of consecutive links."""
        links = self.chain_links(ignore)
        targets = set(links.values())
        groups = []
        for head in sorted((u for u in links if u not in targets), key=lambda n: ordering.rank[n]):
            members = [head]
            while members[-1] in links:
                members.append(links[members[-1]])
            groups.append(Group(tuple(members), True, self.mask_of(members)))
        return groups

    # ------------------------------------------------------------------ cliques
    def commuting_pairs(self) -> set[tuple[int, int]]:
        """Pairs ``u, v`` seen in both orders from a common state, ending in the same state (§2.1.2's
        commutativity): the 2-cliques meeting §2.1.4's prerequisite conditions. This is the undirected
        simplification the maximal-clique search runs on."""
        pairs = set()
        for outs in self.out.values():
            if len(outs) < 2:
                continue
            items = list(outs.items())
            for i, (u, after_u) in enumerate(items):
                next_u = self.out.get(after_u)
                if not next_u:
                    continue
                for v, after_v in items[i + 1 :]:
                    meet = next_u.get(v)
                    if meet is not None and self.out.get(after_v, {}).get(u) == meet:
                        pairs.add((u, v) if u < v else (v, u))
        return pairs

    def mutual_pairs(self) -> set[tuple[int, int]]:
        """Pairs joined by CTG edges in both directions, whatever their prerequisites (Algorithm 3's C_E)."""
        succ: dict[int, set[int]] = {}
        for u, edges in self.by_node.items():
            after = succ.setdefault(u, set())
            for _, dst in edges:
                after.update(self.out.get(dst, {}))
        return {(u, v) for u, vs in succ.items() for v in vs if u < v and u in succ.get(v, ())}

    def clique_candidates(self, pairs: Iterable[tuple[int, int]], ordering: Ordering) -> list[frozenset[int]]:
        """Maximal cliques (Bron–Kerbosch, networkx) of an undirected simplification, largest first."""
        import networkx as nx  # here: networkx is a fifth of every command's start-up

        graph = nx.Graph()
        graph.add_edges_from(pairs)
        cliques = [frozenset(c) for c in nx.find_cliques(graph) if len(c) > 1]
        return sorted(cliques, key=lambda c: (-len(c), ordering.key(c)))

    def verify_clique(self, members: frozenset[int]) -> dict[int, int] | None:
        """Check a clique candidate against the prerequisite conditions, strengthened so invariants hold.

        * every edge leaving a member carries the post-condition of the whole clique (§2.1.4 asks this of one
          set of exit edges; asking it of all of them is what keeps a subtask contiguous in every execution);
        * from every way in, all orders end in one state (the members commute, §2.1.2);
        * from at least one way in, every member is available in every state until done: the order-agnostic
          claim was observed in full, not guessed from pairs.

        Returns:
            Entry state -> exit state, or None when the candidate is rejected.
        """
        mask = self.mask_of(members)
        entries = set()
        for member in members:
            for src, dst in self.by_node[member]:
                if self.state_mask[src] & mask == 0:
                    entries.add(src)
                if self.state_mask[dst] & mask != mask and (
                    dst in self.terminal or any(n not in members for n in self.out.get(dst, {}))
                ):
                    return None
        exits: dict[int, int] = {}
        observed_in_full = False
        for entry in sorted(entries):
            ends, full = self._explore(entry, members, mask)
            if len(ends) != 1:
                return None
            exits[entry] = ends.pop()
            observed_in_full |= full
        return exits if observed_in_full else None

    def _explore(self, entry: int, members: frozenset[int], mask: int) -> tuple[set[int], bool]:
        seen, stack, ends, full = {entry}, [entry], set(), True
        while stack:
            state = stack.pop()
            done = self.state_mask[state] & mask
            if done == mask:
                ends.add(state)
                continue
            outs = self.out.get(state, {})
            for member in members:
                if self.node_mask[member] & done:
                    continue
                nxt = outs.get(member)
                if nxt is None:
                    full = False
                elif nxt not in seen:
                    seen.add(nxt)
                    stack.append(nxt)
        return ends, full

    # ------------------------------------------------------------------ rewriting
    def mask_of(self, members: Iterable[int]) -> int:
        """The primitive subgoals under ``members``, as one mask."""
        mask = 0
        for member in members:
            mask |= self.node_mask[member]
        return mask

    def chain_exits(self, group: Group) -> dict[int, int]:
        """Entry state -> exit state of a chain (each link leaves one way on)."""
        exits = {}
        for src, dst in self.by_node[group.members[0]]:
            state = dst
            for member in group.members[1:]:
                state = self.out[state][member]
            exits[src] = state
        return exits

    def compact(self, groups: Sequence[tuple[int, Group, dict[int, int]]]) -> LevelGraph:
        """The next level: each ``(node id, group, entry->exit)`` becomes one node with one edge per entry."""
        gone = {m for _, group, _ in groups for m in group.members}
        by_node = {n: edges for n, edges in self.by_node.items() if n not in gone}
        for node, _, exits in groups:
            by_node[node] = sorted(exits.items())
        return LevelGraph(by_node, self.initial, self.terminal, self.state_mask, self.node_mask)

    def restrict(self, groups: Sequence[Group]) -> LevelGraph | None:
        """Keep only the executions in which every group is contiguous (and, for chains, in order).

        Used by ambiguity resolution (Algorithms 3 and 4) to commit to one reading of an ambiguous graph.
        Returns None when no execution is left.
        """
        position = {m: (g, i) for g in groups for i, m in enumerate(g.members)}
        kept: dict[int, list[tuple[int, int]]] = {}
        for node, edges in self.by_node.items():
            mine = position.get(node)
            for src, dst in edges:
                done = self.state_mask[src]
                if any(0 < done & g.mask != g.mask for g in groups if g is not (mine[0] if mine else None)):
                    continue
                if mine is not None and mine[0].ordered:
                    group, index = mine
                    if done & group.mask != self.mask_of(group.members[:index]):
                        continue
                kept.setdefault(node, []).append((src, dst))
        return _trimmed(kept, self)


def _trimmed(by_node: dict[int, list[tuple[int, int]]], like: LevelGraph) -> LevelGraph | None:
    """Drop states that are not on an initial-to-terminal path."""
    out: dict[int, list[int]] = {}
    back: dict[int, list[int]] = {}
    for edges in by_node.values():
        for src, dst in edges:
            out.setdefault(src, []).append(dst)
            back.setdefault(dst, []).append(src)
    forward = reachable(like.initial, out)
    backward = reachable(like.terminal & forward, back)
    alive = forward & backward
    if not alive & like.initial:
        return None
    kept = {n: [(s, d) for s, d in edges if s in alive and d in alive] for n, edges in by_node.items()}
    kept = {n: edges for n, edges in kept.items() if edges}
    return LevelGraph(kept, like.initial & alive, like.terminal & alive, like.state_mask, like.node_mask)
