"""Generated tasks whose valid executions are known, and demonstrations with mistakes put in on purpose.

A :class:`KnownTask` is a random chain/clique structure (profiles ``"ikea"`` and ``"uniform"``,
:func:`~supportive.generate.structures.random_structure`) or a random partial order (``"partial order"``:
interleaved chains with cross constraints, :func:`~supportive.generate.partial_orders.random_partial_order`).
It draws executions uniformly among its valid ones and says whether a sequence is one. :func:`inject` then
puts one mistake into some of them, of one of three kinds:

* ``moved``: a step taken from its place and done at a random other place, redrawn until the result is not a
  valid execution (a move that lands where the step may be is no mistake); ``early``: the same, to an earlier
  place only (a step done before what it needs);
* ``repeated``: a step done a second time, at a random later place;
* ``dropped``: a step left out.

Each returns what was put in (:class:`Injected`), so a detector's findings can be scored against it. The
``learner-settings``, ``selection-settings`` and ``mistake-detection`` experiments are built on these.

>>> task = random_known_task("partial order", 6, seed=1)
>>> rng = np.random.default_rng(0)
>>> demos = [task.sample(rng) for _ in range(10)]
>>> all(task.admits(d) for d in demos)
True
>>> noisy, injected = inject(demos, "moved", 0.2, task.admits, rng)
>>> len(injected), all(not task.admits(noisy[i.demonstration]) for i in injected)
(2, True)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from supportive.errors import GenerationError
from supportive.generate.partial_orders import PartialOrderTask, random_partial_order
from supportive.generate.structures import random_structure
from supportive.seeding import Seed, rng_from
from supportive.tasks.htn import Node, admits, allowed_next, sample_ordering, to_leaves

__all__ = ["KINDS", "PROFILES", "Injected", "KnownTask", "MistakeKind", "TaskProfile", "inject", "random_known_task"]

MistakeKind = Literal["moved", "early", "repeated", "dropped"]
KINDS: tuple[MistakeKind, ...] = ("moved", "repeated", "dropped")
"""The kinds of slip the learner is scored on (``learner-settings``); :func:`inject` also puts in ``early``."""

TaskProfile = Literal["ikea", "uniform", "partial order"]
PROFILES: tuple[TaskProfile, ...] = ("ikea", "uniform", "partial order")
"""The kinds of task :func:`random_known_task` draws."""

_MOVE_DRAWS = 200


@dataclass(frozen=True)
class KnownTask:
    """A task whose valid executions are known: a chain/clique ``structure`` or a ``partial`` order."""

    profile: TaskProfile
    structure: Node | None = None
    partial: PartialOrderTask | None = None

    def admits(self, actions: Sequence[str]) -> bool:
        """True when ``actions`` is a valid execution."""
        if self.partial is not None:
            return self.partial.admits(actions)
        assert self.structure is not None
        return admits(self.structure, to_leaves(actions))

    def allowed_next(self, done: Sequence[str]) -> list[str]:
        """The steps a valid execution that began with ``done`` (a valid prefix) may do next, sorted; none
        when it is finished."""
        if self.partial is not None:
            needs = self.partial.precedences
            left = set(self.partial.steps) - set(done)
            return sorted(b for b in left if not any(a in left for a, later in needs if later == b))
        assert self.structure is not None
        return sorted({action for action, _ in allowed_next(self.structure, to_leaves(done))})

    def sample(self, seed: Seed = None) -> list[str]:
        """One valid execution, drawn uniformly among them."""
        rng = rng_from(seed)
        if self.partial is not None:
            return list(self.partial.sample(rng))
        assert self.structure is not None
        return [action for action, _ in sample_ordering(self.structure, rng)]


def random_known_task(profile: TaskProfile, n_actions: int, seed: Seed = None) -> KnownTask:
    """A random task of ``profile`` with ``n_actions`` steps (a partial order of 2–3 chains and 0–2 cross
    constraints, or a normalised chain/clique structure).

    Raises:
        GenerationError: for an unknown profile or too few steps.
    """
    rng = rng_from(seed)
    if profile == "partial order":
        chains = int(rng.integers(2, 4))
        if n_actions < chains:
            raise GenerationError(f"a partial order of {chains} chains needs at least {chains} steps")
        return KnownTask(profile, partial=random_partial_order(n_actions, rng, chains=chains, cross=int(rng.integers(0, 3))))
    if profile not in ("ikea", "uniform"):
        raise GenerationError(f"unknown task profile {profile!r}; expected one of {', '.join(PROFILES)}")
    return KnownTask(profile, structure=random_structure(n_actions, rng, profile=profile))


@dataclass(frozen=True)
class Injected:
    """One mistake put in: in demonstration ``demonstration`` (an index), ``action`` was ``kind``; ``position``
    is where the mistaken step now is (a dropped step: where it should have been, i.e. the index of the step
    done in its place)."""

    demonstration: int
    action: str
    kind: MistakeKind
    position: int


def inject(
    demonstrations: Sequence[Sequence[str]],
    kind: MistakeKind,
    share: float,
    valid: Callable[[Sequence[str]], bool],
    seed: Seed = None,
) -> tuple[list[list[str]], list[Injected]]:
    """Put one mistake of ``kind`` into ``round(share × n)`` (at least one) of the demonstrations, chosen at
    random; return the demonstrations and what was put in, in demonstration order. ``valid`` says whether a
    sequence is a valid execution: a moved step is redrawn until it is not (after many draws that find none,
    the demonstration is left as it was and nothing is reported for it).

    Raises:
        GenerationError: for a share outside (0, 1] or an unknown kind.
    """
    if not 0.0 < share <= 1.0:
        raise GenerationError(f"share must be in (0, 1], got {share}")
    if kind not in (*KINDS, "early"):
        raise GenerationError(f"unknown mistake kind {kind!r}; expected one of {', '.join((*KINDS, 'early'))}")
    rng = rng_from(seed)
    out = [list(d) for d in demonstrations]
    chosen = rng.choice(len(out), size=max(1, round(share * len(out))), replace=False)
    injected: list[Injected] = []
    for index in sorted(int(i) for i in chosen):
        found = _one(out[index], kind, valid, rng)
        if found is not None:
            out[index], action, position = found
            injected.append(Injected(index, action, kind, position))
    return out, injected


def _one(
    demo: list[str], kind: MistakeKind, valid: Callable[[Sequence[str]], bool], rng: np.random.Generator
) -> tuple[list[str], str, int] | None:
    """One mistake of ``kind`` in ``demo``: the new sequence, the action and where it now is."""
    if kind == "dropped":
        i = int(rng.integers(len(demo)))
        return demo[:i] + demo[i + 1 :], demo[i], i
    if kind == "repeated":
        i = int(rng.integers(len(demo)))
        j = int(rng.integers(i + 1, len(demo) + 1))
        return [*demo[:j], demo[i], *demo[j:]], demo[i], j
    earliest = 1 if kind == "early" else 0  # an early step needs a place before it
    if len(demo) <= earliest:
        return None
    for _ in range(_MOVE_DRAWS):
        i = int(rng.integers(earliest, len(demo)))
        rest = demo[:i] + demo[i + 1 :]
        j = int(rng.integers(i if kind == "early" else len(rest) + 1))
        moved = [*rest[:j], demo[i], *rest[j:]]
        if not valid(moved):
            return moved, demo[i], j
    return None
