"""The "ikea" profile: assembly-like structures of parts, connectors, steps and sub-assemblies (§2.1.7.2)."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import numpy as np

from supportive.errors import GenerationError
from supportive.generate.normalise import normalise
from supportive.generate.vocabulary import CONNECTORS, FURNITURE, PARTS
from supportive.seeding import Seed, rng_from
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, Node

__all__ = ["IkeaParams", "ikea_structure"]


@dataclass(frozen=True)
class IkeaParams:
    """Knobs of :func:`ikea_structure`; the defaults are calibrated to §2.1.7.2 (see the package docstring).

    Attributes:
        parts_per_step: Relative chance of a step attaching 1, 2, 3, … identical parts.
        connector_weights: Relative chance of a part having 0, 1, 2, … connectors.
        two_step_probability: Chance that a step's connectors take two steps (insert, then tighten) rather
            than one (fasten).
        step_clique_probability: Chance that a step's parts may be attached in any order.
        subassembly_probability: Chance that a phase of the assembly is a few sub-assemblies built in any
            order rather than one step.
        subassemblies: Least and most sub-assemblies in such a phase.
        parts_per_subassembly: Least and most parts in a sub-assembly (different parts, attached in order).
    """

    parts_per_step: tuple[float, ...] = (0.35, 0.35, 0.15, 0.15)
    connector_weights: tuple[float, ...] = (0.4, 0.4, 0.15, 0.05)
    two_step_probability: float = 0.15
    step_clique_probability: float = 0.85
    subassembly_probability: float = 0.4
    subassemblies: tuple[int, int] = (2, 3)
    parts_per_subassembly: tuple[int, int] = (1, 3)

    def __post_init__(self) -> None:
        for field in ("parts_per_step", "connector_weights"):
            weights = getattr(self, field)
            if not weights or min(weights) < 0 or sum(weights) <= 0:
                raise GenerationError(
                    f"{field} must be non-negative weights with a positive sum, got {weights}"
                )
        for field in ("two_step_probability", "step_clique_probability", "subassembly_probability"):
            value = getattr(self, field)
            if not 0.0 <= value <= 1.0:
                raise GenerationError(f"{field} must be in [0, 1], got {value}")
        low, high = self.subassemblies
        if not 2 <= low <= high:
            raise GenerationError(f"subassemblies must be (low, high) with 2 <= low <= high, got {low, high}")
        low, high = self.parts_per_subassembly
        if not 1 <= low <= high:
            raise GenerationError(
                f"parts_per_subassembly must be (low, high) with 1 <= low <= high, got {low, high}"
            )


def ikea_structure(n_actions: int, seed: Seed = None, params: IkeaParams | None = None) -> Node:
    """A random normalised IKEA-like assembly of exactly ``n_actions`` subgoals.

    * A *part* is the chain ``pick_<part>, place_<part>, <fastening>``; fastening one connector is
      ``fasten_<c>`` or the chain ``insert_<c>, tighten_<c>``, fastening several is a clique of those.
    * A *step* attaches a few identical parts (same kind, same kind of connector): in any order (a clique)
      or in a fixed order (a chain).
    * A *sub-assembly* is a few different parts attached in order (a chain).
    * The assembly is a chain of *phases*: a step, or a clique of sub-assemblies built independently before
      they are joined.

    Parts are drawn until the budget is spent; the last one is cut short to hit ``n_actions`` exactly (a lone
    ``fasten_<c>`` when one action is left). Ids are numbered per kind: ``pick_leg_3``, ``fasten_bolt_12``;
    none repeats. Internal nodes are named (``Mount leg 3``, ``Attach legs``, ``Assemble chair``).

    Args:
        n_actions: Number of subgoals (at least 1).
        seed: Seed or generator (see :mod:`supportive.seeding`).
        params: Knobs; the calibrated defaults when omitted.

    Raises:
        GenerationError: when ``n_actions`` is below 1.
    """
    if n_actions < 1:
        raise GenerationError(f"n_actions must be at least 1, got {n_actions}")
    return normalise(_Builder(n_actions, rng_from(seed), params or IkeaParams()).assembly())


def _probabilities(weights: tuple[float, ...]) -> np.ndarray:
    array = np.asarray(weights, dtype=float)
    return np.asarray(array / array.sum())


class _Builder:
    """Draws one assembly, spending a budget of actions."""

    def __init__(self, n_actions: int, rng: np.random.Generator, params: IkeaParams) -> None:
        self.remaining = n_actions
        self.rng = rng
        self.params = params
        self.counts: Counter[str] = Counter()
        self.parts_p = _probabilities(params.parts_per_step)
        self.connectors_p = _probabilities(params.connector_weights)

    def _number(self, kind: str) -> str:
        self.counts[kind] += 1
        return f"{kind}_{self.counts[kind]}"

    def _pick(self, options: tuple[str, ...]) -> str:
        return options[int(self.rng.integers(len(options)))]

    def _between(self, bounds: tuple[int, int]) -> int:
        return int(self.rng.integers(bounds[0], bounds[1] + 1))

    def assembly(self) -> Node:
        """The root: a chain of phases that spends the whole budget."""
        phases: list[Node] = []
        while self.remaining > 0:
            if self.rng.random() < self.params.subassembly_probability:
                phases.append(self._subassemblies())
            else:
                phases.append(self._step())
        return ChainNode(tuple(phases), f"Assemble {self._pick(FURNITURE)}")

    def _subassemblies(self) -> Node:
        members: list[Node] = []
        for _ in range(self._between(self.params.subassemblies)):
            parts: list[Node] = []
            for _ in range(self._between(self.params.parts_per_subassembly)):
                if self.remaining > 0:
                    parts.append(
                        self._drawn_part(self._pick(PARTS), self._pick(CONNECTORS), self._two_step())
                    )
            if parts:
                self.counts["sub-assembly"] += 1
                members.append(ChainNode(tuple(parts), f"Build sub-assembly {self.counts['sub-assembly']}"))
        return CliqueNode(tuple(members), "Build sub-assemblies")

    def _two_step(self) -> bool:
        return bool(self.rng.random() < self.params.two_step_probability)

    def _drawn_part(self, part: str, connector: str, two_step: bool) -> Node:
        connectors = int(self.rng.choice(len(self.connectors_p), p=self.connectors_p))
        size = min(2 + connectors * (2 if two_step else 1), self.remaining)
        self.remaining -= size
        return self._part(part, connector, size, two_step)

    def _step(self) -> Node:
        part, connector = self._pick(PARTS), self._pick(CONNECTORS)
        count = 1 + int(self.rng.choice(len(self.parts_p), p=self.parts_p))
        two_step = self._two_step()
        parts: list[Node] = []
        for _ in range(count):
            if self.remaining == 0:
                break
            parts.append(self._drawn_part(part, connector, two_step))
        name = f"Attach {part.replace('_', ' ')}s"
        if self.rng.random() < self.params.step_clique_probability:
            return CliqueNode(tuple(parts), name)
        return ChainNode(tuple(parts), name)

    def _part(self, part: str, connector: str, size: int, two_step: bool) -> Node:
        if size == 1:
            return ActionNode(f"fasten_{self._number(connector)}")
        label = self._number(part)
        steps: list[Node] = [ActionNode(f"pick_{label}"), ActionNode(f"place_{label}")]
        fastenings: list[Node] = []
        left = size - 2
        while left > 0:
            unit = self._number(connector)
            if two_step and left >= 2:
                name = unit.replace("_", " ").capitalize()
                fastenings.append(
                    ChainNode((ActionNode(f"insert_{unit}"), ActionNode(f"tighten_{unit}")), name)
                )
                left -= 2
            else:
                fastenings.append(ActionNode(f"fasten_{unit}"))
                left -= 1
        text = label.replace("_", " ")
        if fastenings:
            steps.append(CliqueNode(tuple(fastenings), f"Fasten {text}"))
        return ChainNode(tuple(steps), f"Mount {text}")
