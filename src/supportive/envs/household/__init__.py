"""The household world of §3.5: maps, dynamics, novice agents. With the ``envs`` extra (gymnasium,
pettingzoo) also the RL environments: :class:`~supportive.envs.household.gym_env.NoviceEnv` (registered as
``supportive/Household-v0``) and :class:`~supportive.envs.household.parallel_env.HouseholdParallelEnv`; import
them from those modules."""

from supportive.envs.household.distances import CellGraph, MapDistances
from supportive.envs.household.grid_map import (
    MOVES,
    Cell,
    GridMap,
    Terrain,
    load_map,
    map_names,
    parse_map,
    read_map,
)
from supportive.envs.household.novice import NOVICE_TYPES, EpsilonGreedyNovice
from supportive.envs.household.world import (
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
