"""Random partial-order tasks: independent chains of steps, optionally with constraints across them.

Real procedures interleave independent strands of work (a recipe boils water while it cuts vegetables), which
no single chain/clique tree admits. A :class:`PartialOrderTask` is such a task: its steps, grouped in chains,
and "a before b" constraints between steps of different chains; an execution is any order of all the steps
that keeps every constraint. Executions are drawn **uniformly** among the valid ones (a uniform interleaving
of the chains, redrawn until it keeps the cross constraints), so they are what a learner should accept
without calling anything a slip.

>>> task = PartialOrderTask((("a1", "a2", "a3"), ("b1", "b2", "b3")))
>>> task.count_executions()  # two chains of three: C(6, 3) interleavings
20
>>> PartialOrderTask(task.chains, (("a1", "b3"),)).count_executions()  # b1 b2 b3 a1 a2 a3 is out
19
>>> all(task.admits(task.sample(seed=s)) for s in range(5))
True
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from supportive.errors import GenerationError
from supportive.seeding import Seed, rng_from

__all__ = ["PartialOrderTask", "random_partial_order"]

_MAX_DRAWS = 10_000


@dataclass(frozen=True)
class PartialOrderTask:
    """Steps in chains plus cross-chain constraints (see the module docstring).

    Attributes:
        chains: The chains, each a sequence of step ids done in that order.
        cross: Extra constraints ``(a, b)``: ``a`` before ``b``, with ``a`` and ``b`` in different chains.
    """

    chains: tuple[tuple[str, ...], ...]
    cross: tuple[tuple[str, str], ...] = ()

    @property
    def steps(self) -> tuple[str, ...]:
        """Every step, chain by chain."""
        return tuple(step for chain in self.chains for step in chain)

    @property
    def precedences(self) -> frozenset[tuple[str, str]]:
        """Every pair ``(a, b)`` with ``a`` before ``b`` in all executions (the transitive closure)."""
        after: dict[str, set[str]] = {step: set() for step in self.steps}
        for chain in self.chains:
            for i, step in enumerate(chain):
                after[step].update(chain[i + 1 :])
        for a, b in self.cross:
            after[a].add(b)
        changed = True
        while changed:
            changed = False
            for step, later in after.items():
                grown = set().union(later, *(after[x] for x in later))
                if grown != later:
                    after[step] = grown
                    changed = True
        return frozenset((a, b) for a, later in after.items() for b in later)

    def admits(self, execution: Sequence[str]) -> bool:
        """True when ``execution`` does every step once and keeps every constraint."""
        if sorted(execution) != sorted(self.steps):
            return False
        position = {step: i for i, step in enumerate(execution)}
        return all(position[a] < position[b] for a, b in self.precedences)

    def sample(self, seed: Seed = None) -> tuple[str, ...]:
        """One execution, uniformly among the valid ones.

        Raises:
            GenerationError: when no valid interleaving turns up in many draws (constraints too tight to
                sample this way).
        """
        rng = rng_from(seed)
        lengths = [len(chain) for chain in self.chains]
        labels = np.repeat(np.arange(len(self.chains)), lengths)
        for _ in range(_MAX_DRAWS):
            order = rng.permutation(labels)
            nexts = [0] * len(self.chains)
            execution = []
            for chain in order:
                execution.append(self.chains[chain][nexts[chain]])
                nexts[chain] += 1
            if not self.cross or self.admits(execution):
                return tuple(execution)
        raise GenerationError("no valid execution found: the cross constraints are too tight to sample")

    def count_executions(self) -> int:
        """How many valid executions there are (dynamic programming over what each chain has done)."""
        count, _ = self._counter()
        return count(tuple(0 for _ in self.chains))

    def counting_sampler(self) -> Callable[[Seed], tuple[str, ...]]:
        """A function drawing one execution at a time, uniformly among the valid ones however tight the
        constraints: each next step is drawn with chance proportional to the valid executions that go on from
        it (the counts of :meth:`count_executions`, worked out once for every draw). :meth:`sample` redraws
        whole interleavings instead, which is quicker for loose constraints and fails for tight ones (a
        recipe's graph as chains of one step each).

        Raises:
            GenerationError: when the constraints admit no execution.

        >>> draw = PartialOrderTask((("a",), ("b",), ("c",)), (("a", "b"), ("a", "c"))).counting_sampler()
        >>> sorted({draw(s) for s in range(20)})
        [('a', 'b', 'c'), ('a', 'c', 'b')]
        """
        count, moves = self._counter()
        start = tuple(0 for _ in self.chains)
        if count(start) == 0:
            raise GenerationError("the constraints admit no execution")

        def draw(seed: Seed = None) -> tuple[str, ...]:
            rng = rng_from(seed)
            done, execution = start, []
            for _ in range(len(self.steps)):
                options = [(c, nxt) for c, nxt in moves(done) if count(nxt)]
                weights = np.array([count(nxt) for _, nxt in options], dtype=float)
                chain, done = options[int(rng.choice(len(options), p=weights / weights.sum()))]
                execution.append(self.chains[chain][done[chain] - 1])
            return tuple(execution)

        return draw

    def _counter(
        self,
    ) -> tuple[Callable[[tuple[int, ...]], int], Callable[[tuple[int, ...]], list[tuple[int, tuple[int, ...]]]]]:
        """The valid executions that go on from what each chain has done (memoised), and the moves from such
        a state: each chain whose next step may come then, with the state after it."""
        lengths = tuple(len(chain) for chain in self.chains)
        index = {step: (c, i) for c, chain in enumerate(self.chains) for i, step in enumerate(chain)}
        needs: dict[tuple[int, int], list[tuple[int, int]]] = {}
        for a, b in self.cross:
            needs.setdefault(index[b], []).append(index[a])

        def moves(done: tuple[int, ...]) -> list[tuple[int, tuple[int, ...]]]:
            return [
                (c, (*done[:c], k + 1, *done[c + 1 :]))
                for c, k in enumerate(done)
                if k < lengths[c] and all(done[ac] > ai for ac, ai in needs.get((c, k), ()))
            ]

        @functools.cache
        def count(done: tuple[int, ...]) -> int:
            if done == lengths:
                return 1
            return sum(count(nxt) for _, nxt in moves(done))

        return count, moves


def random_partial_order(n_steps: int, seed: Seed = None, *, chains: int = 2, cross: int = 0) -> PartialOrderTask:
    """A random partial-order task of ``n_steps`` steps in ``chains`` chains of random lengths (each at
    least one step), with ``cross`` constraints from a step of one chain to a later-starting step of another
    (drawn so that a valid execution exists: each goes from an earlier to a later position of a random
    reference interleaving).

    Raises:
        GenerationError: for fewer steps than chains, or fewer than one chain.
    """
    if chains < 1 or n_steps < chains:
        raise GenerationError(f"need at least one chain and a step per chain, got {n_steps} steps in {chains}")
    if cross < 0:
        raise GenerationError(f"cross constraints must be 0 or more, got {cross}")
    rng = rng_from(seed)
    cuts = sorted(int(c) for c in rng.choice(np.arange(1, n_steps), size=chains - 1, replace=False))
    bounds = [0, *cuts, n_steps]
    names = [f"s{i + 1}" for i in range(n_steps)]
    task_chains = tuple(tuple(names[bounds[c] : bounds[c + 1]]) for c in range(chains))
    reference = PartialOrderTask(task_chains).sample(rng)
    position = {step: i for i, step in enumerate(reference)}
    chain_of = {step: c for c, chain in enumerate(task_chains) for step in chain}
    pairs = [
        (a, b) for a in reference for b in reference if position[a] < position[b] and chain_of[a] != chain_of[b]
    ]
    chosen: tuple[tuple[str, str], ...] = ()
    if pairs and cross:
        picks = rng.choice(len(pairs), size=min(cross, len(pairs)), replace=False)
        chosen = tuple(sorted(pairs[int(i)] for i in picks))
    return PartialOrderTask(task_chains, chosen)

