"""The circuit-building world of §3.2.9, modelled on SnapCircuits: the piece catalogue, placement on the snap
board, nets, DC analysis and goal predicates."""

from supportive.envs.circuits.analysis import CircuitState, analyze, analyze_netlist, supply_batteries
from supportive.envs.circuits.board import Board, BoardPose, Placement, Point
from supportive.envs.circuits.goals import CircuitGoal, GoalReport, series_count
from supportive.envs.circuits.netlist import Element, Netlist, Terminal, netlist
from supportive.envs.circuits.pieces import PIECE_TYPES, PieceType, piece_type

__all__ = [
    "PIECE_TYPES",
    "Board",
    "BoardPose",
    "CircuitGoal",
    "CircuitState",
    "Element",
    "GoalReport",
    "Netlist",
    "PieceType",
    "Placement",
    "Point",
    "Terminal",
    "analyze",
    "analyze_netlist",
    "netlist",
    "piece_type",
    "series_count",
    "supply_batteries",
]
