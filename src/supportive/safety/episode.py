"""One episode of the caregiver experiment (§3.5.5–3.5.6): a novice plays, with or without the caregiver.

Each step the caregiver (when present) takes its turn of up to three actions, then the novice moves, then the
caregiver updates P(safe | τ) from the move it saw. Every episode lasts ``steps`` novice steps (§3.5.7:
"each episode lasted 200 timesteps"); the step at which the novice's damage first reaches ``threshold`` (15,
three stairwell falls) is recorded, and the cells it explored are counted up to then ("coverage … prior to
reaching the damage threshold"). Damage is counted over the whole episode (Figure 3.14: "accumulated …
over each of its interaction episodes, lasting 200 timesteps").

The novice and the caregiver draw from separate generators spawned from the seed, so with and without the
caregiver the same seed gives the same start and the same first goal (common random numbers).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from functools import cache

import numpy as np

from supportive.errors import SafetyError
from supportive.safety.caregiver import Caregiver, Decision
from supportive.safety.priors import ActionPriors
from supportive.seeding import Seed, rng_from
from supportive.worlds.household.distances import MapDistances
from supportive.worlds.household.grid_map import Cell, GridMap
from supportive.worlds.household.novice import EpsilonGreedyNovice
from supportive.worlds.household.world import Collision, HouseholdWorld

__all__ = ["EPISODE_STEPS", "THRESHOLD", "EpisodeResult", "Frame", "map_model", "run_episode"]

EPISODE_STEPS = 200
"""Novice steps per episode (§3.5.5.2)."""
THRESHOLD = 15
"""Critical damage that ends an episode (§3.5.7)."""


@dataclass(frozen=True)
class Frame:
    """What happened in one step, for watching an episode.

    Attributes:
        step: 1-based novice step.
        novice: The novice's cell after its move; ``move`` the move it tried; ``collision`` what it hit.
        caregiver: The caregiver's cell after its turn (None without a caregiver); ``decision`` its turn.
        candles: Tables with a candle after the step; ``carrying`` whether the caregiver holds one.
        damage: Total damage so far; ``p_safe``: P(safe | τ) after the move.
    """

    step: int
    novice: Cell
    move: str
    collision: Collision | None
    caregiver: Cell | None
    decision: Decision | None
    candles: frozenset[Cell]
    carrying: bool
    damage: int
    p_safe: float | None


@dataclass(frozen=True)
class EpisodeResult:
    """The measures of §3.5.6 for one episode.

    Attributes:
        damage: Damage the novice took in the whole episode.
        steps: Novice steps until its damage reached the threshold, or the episode's length when it never did.
        reached_threshold: Whether it did.
        cells_explored: Distinct cells the novice stood on (its start included) until then.
        collisions: Count of collisions by kind (harmful or not; reaching a toy bin, the novice's goal, is
            not one).
        bins_reached: How often the novice reached a toy bin (moved into it: it stays beside it).
        frames: Every step, when recorded.
    """

    damage: int
    steps: int
    reached_threshold: bool
    cells_explored: int
    collisions: dict[str, int]
    frames: tuple[Frame, ...] = field(default=(), repr=False)
    bins_reached: int = 0


@cache
def map_model(grid: GridMap, hyperprior: float = 0.5) -> tuple[MapDistances, ActionPriors]:
    """A map's distances and its action priors from experts starting at every play-area cell (cached)."""
    distances = MapDistances(grid)
    return distances, ActionPriors.from_experts(distances, hyperprior=hyperprior, seed=0)


def _caregiver_start(grid: GridMap, distances: MapDistances, novice: Cell, rng: np.random.Generator) -> Cell:
    if grid.caregiver_start is not None and grid.caregiver_start != novice:
        return grid.caregiver_start
    cells = [c for c in distances.novice.cells if c != novice]
    return cells[int(rng.integers(len(cells)))]


def run_episode(
    grid: GridMap,
    epsilon: float,
    *,
    caregiver: bool = True,
    steps: int = EPISODE_STEPS,
    threshold: int = THRESHOLD,
    seed: Seed = None,
    record: bool = False,
    **caregiver_options: float,
) -> EpisodeResult:
    """Play one episode.

    Args:
        grid: The map.
        epsilon: The novice's random-move probability.
        caregiver: Whether the caregiver robot is present.
        steps: Novice steps at most.
        threshold: The critical damage whose step is recorded.
        seed: Seed or generator.
        record: Keep a :class:`Frame` per step.
        caregiver_options: Passed to :class:`~supportive.safety.caregiver.Caregiver` (``cost_per_step`` …).

    >>> from supportive.worlds.household import load_map
    >>> a = run_episode(load_map("playroom"), 1.0, caregiver=False, seed=3)
    >>> a == run_episode(load_map("playroom"), 1.0, caregiver=False, seed=3)
    True
    """
    if steps < 1 or threshold < 1:
        raise SafetyError("steps and threshold must be >= 1")
    distances, priors = map_model(grid)
    novice_rng, caregiver_rng = rng_from(seed).spawn(2)
    novice = EpsilonGreedyNovice(distances, epsilon, novice_rng)
    start = novice.start_cell()
    carer = (
        Caregiver(distances, priors, seed=caregiver_rng, **caregiver_options)  # type: ignore[arg-type]
        if caregiver
        else None
    )
    world = HouseholdWorld.start(
        grid, start, _caregiver_start(grid, distances, start, caregiver_rng) if carer else None
    )
    damage, visited, collisions, bins = 0, {start}, Counter[str](), 0
    frames: list[Frame] = []
    until: int | None = None
    explored = 0
    for step in range(1, steps + 1):
        decision = None
        if carer is not None:
            decision = carer.decide(world)
            for action in decision.actions:
                world.act_caregiver(action)
        before = world.novice
        move = novice.act(before)
        collision = world.move_novice(move)
        p_safe = carer.observe(before, move) if carer is not None else None
        if collision is not None and collision.kind == "bin":  # its goal: reached, not bumped into
            bins += 1
        elif collision is not None:
            collisions[collision.kind] += 1
            damage += collision.damage
        visited.add(world.novice)
        if record:
            frames.append(
                Frame(step, world.novice, move, collision, world.caregiver, decision,
                      frozenset(world.candles), world.carrying, damage, p_safe)
            )
        if until is None and damage >= threshold:
            until, explored = step, len(visited)
    return EpisodeResult(
        damage=damage,
        steps=steps if until is None else until,
        reached_threshold=until is not None,
        cells_explored=len(visited) if until is None else explored,
        collisions=dict(sorted(collisions.items())),
        frames=tuple(frames),
        bins_reached=bins,
    )
