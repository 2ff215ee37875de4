"""The household world of §3.5 as a model: maps, dynamics, distances, novice agents. The caregiver
(:mod:`supportive.safety`) reasons over it; the RL environments over it (the ``envs`` extra:
:class:`~supportive.envs.household.gym_env.NoviceEnv`, registered as ``supportive/Household-v0``, and
:class:`~supportive.envs.household.parallel_env.HouseholdParallelEnv`) live in :mod:`supportive.envs.household`."""

from supportive.worlds.household.distances import CellGraph, MapDistances
from supportive.worlds.household.grid_map import (
    MOVES,
    Cell,
    GridMap,
    Terrain,
    load_map,
    map_names,
    parse_map,
    read_map,
)
from supportive.worlds.household.novice import NOVICE_TYPES, EpsilonGreedyNovice
from supportive.worlds.household.world import (
    CAREGIVER_ACTIONS,
    DAMAGE,
    NOVICE_ACTIONS,
    Collision,
    HouseholdWorld,
)

__all__ = [
    "CAREGIVER_ACTIONS",
    "DAMAGE",
    "MOVES",
    "NOVICE_ACTIONS",
    "NOVICE_TYPES",
    "Cell",
    "CellGraph",
    "Collision",
    "EpsilonGreedyNovice",
    "GridMap",
    "HouseholdWorld",
    "MapDistances",
    "Terrain",
    "load_map",
    "map_names",
    "parse_map",
    "read_map",
]
