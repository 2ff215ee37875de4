"""The layout search: every circuit it returns meets the goal on a real board; the greedy order matters."""

from __future__ import annotations

from collections import Counter

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.envs.circuits.board import Board, BoardPose
from supportive.envs.circuits.goals import CircuitGoal
from supportive.envs.circuits.layout import LayoutSearch, Loop, Segment, required_pieces
from supportive.envs.circuits.pieces import PIECE_TYPES
from supportive.errors import CircuitError, PlanningError, SearchLimitError

GOAL = CircuitGoal(batteries_in_series=2, switch_controls=True)
BASE = {"battery": 2, "switch": 1, "led": 1}


@given(
    extra=st.dictionaries(
        st.sampled_from(["wire2", "wire3", "wire4", "lamp", "resistor"]), st.integers(1, 2)
    ),
    ranks=st.lists(st.floats(0, 10), min_size=len(PIECE_TYPES) * 4, max_size=len(PIECE_TYPES) * 4),
)
def test_every_loop_meets_the_goal_whatever_the_order(extra: dict[str, int], ranks: list[float]) -> None:
    kinds = list(PIECE_TYPES)
    search = LayoutSearch(6, 5, GOAL, max_pieces=6)

    def order(kind: str, pose: BoardPose) -> float:
        return ranks[kinds.index(kind) * 4 + pose.rotation]

    inventory = Counter(BASE) + Counter(extra)
    for count, loop in enumerate(search.loops(inventory, order=order)):
        board = loop.board(6, 5)
        assert GOAL.satisfied(board)
        used = Counter(piece.kind for piece in loop.pieces)
        assert all(used[k] <= inventory[k] for k in used) and used >= required_pieces(GOAL)
        assert len(loop.pieces) % 2 == 0 and [p.pose.level for p in loop.pieces] == [
            i % 2 for i in range(len(loop.pieces))
        ]
        if count == 5:
            break


def test_the_minimal_circuit_is_four_components_round_a_square() -> None:
    search = LayoutSearch(4, 4, GOAL)
    loops = list(search.loops(BASE))
    assert len(loops) == 12  # B, B, S, L on the four sides from the fixed corner: 4! / 2! orders
    assert {len(loop.pieces) for loop in loops} == {4}
    assert all(Counter(p.kind for p in loop.pieces) == Counter(BASE) for loop in loops)


def test_without_two_cells_there_is_no_circuit() -> None:
    assert list(LayoutSearch(6, 5, GOAL).loops({"battery": 1, "switch": 1, "led": 1, "wire3": 3})) == []


def test_a_search_completes_what_is_on_the_board() -> None:
    board = Board(6, 5).place("w", "wire3", BoardPose(0, 0, 0, 0))
    search = LayoutSearch(6, 5, GOAL)
    loops = list(search.loops({**BASE, "wire3": 1}, board))
    assert loops and all(
        any(p.kind == "wire3" and p.pose == BoardPose(0, 0, 0, 0) for p in loop.pieces) for loop in loops
    )
    assert not list(LayoutSearch(6, 5, GOAL).loops(BASE, board))  # five pieces cannot alternate levels
    elsewhere = Board(6, 5).place("w", "wire3", BoardPose(1, 1, 0, 0))
    assert not list(LayoutSearch(6, 5, GOAL).loops({**BASE, "wire3": 1}, elsewhere))


def test_the_greedy_order_takes_the_cheapest_kinds_first() -> None:
    def wires_first(kind: str, pose: BoardPose) -> float:
        return 0.0 if kind.startswith("wire") else 1.0

    inventory = {**BASE, "wire2": 2, "wire3": 2}
    first = next(LayoutSearch(6, 5, GOAL, max_pieces=8).loops(inventory, order=wires_first))
    assert first.pieces[0].kind.startswith("wire") and len(first.pieces) > 4
    components = next(
        LayoutSearch(6, 5, GOAL, max_pieces=8).loops(inventory, order=lambda k, p: -wires_first(k, p))
    )
    wires = [sum(p.kind.startswith("wire") for p in loop.pieces) for loop in (first, components)]
    assert components.pieces[0].kind in BASE and wires[0] > wires[1]


def test_search_limits_and_bad_input() -> None:
    with pytest.raises(PlanningError, match="max_pieces"):
        LayoutSearch(6, 5, GOAL, max_pieces=3)
    with pytest.raises(PlanningError, match="start"):
        LayoutSearch(6, 5, GOAL, start=(9, 0))
    with pytest.raises(CircuitError, match="unknown"):
        next(LayoutSearch(6, 5, GOAL).loops({"capacitor": 1}))
    with pytest.raises(SearchLimitError, match="the circuit search tried 50 pieces, its limit"):
        list(LayoutSearch(7, 6, GOAL, max_pieces=8, node_limit=50).loops({**BASE, "wire2": 3, "wire3": 3}))


def _brute_force_loops(
    columns: int, rows: int, goal: CircuitGoal, inventory: dict[str, int], max_pieces: int, fixed: frozenset[Segment]
) -> set[tuple[Segment, ...]]:
    """Every loop from (0, 0), found without the search: each rectangle that fits the board, each way of
    filling its four sides with pieces end to end (any kinds at hand, the fixed pieces besides), levels
    alternating, kept when it is a valid board holding every fixed piece that meets the goal."""
    spans = {kind: PIECE_TYPES[kind].span for kind in set(inventory) | {s.kind for s in fixed}}
    found: set[tuple[Segment, ...]] = set()

    def fill(sides: list[int], side: int, point: tuple[int, int], left: int, laid: list[Segment], stock: Counter[str]) -> None:
        if side == 4:
            if len(laid) % 2 == 0 and fixed <= set(laid):
                loop = Loop(tuple(laid))
                try:
                    board = loop.board(columns, rows)
                except CircuitError:
                    return
                if goal.satisfied(board):
                    found.add(loop.pieces)
            return
        if left == 0:
            fill(sides, side + 1, point, sides[side + 1] if side < 3 else 0, laid, stock)
            return
        if len(laid) == max_pieces:
            return
        for kind, span in sorted(spans.items()):
            if span > left:
                continue
            pose = BoardPose(point[0], point[1], side, len(laid) % 2)
            segment = Segment(kind, pose)
            if stock[kind] <= 0 and segment not in fixed:
                continue
            dc, dr = ((1, 0), (0, 1), (-1, 0), (0, -1))[side]
            taken = Counter() if segment in fixed else Counter({kind: 1})
            fill(sides, side, (point[0] + span * dc, point[1] + span * dr), left - span, [*laid, segment], stock - taken)

    for width in range(1, columns):
        for height in range(1, rows):
            fill([width, height, width, height], 0, (0, 0), width, [], Counter(inventory))
    return {loop for loop in found if Counter(s.kind for s in loop) >= required_pieces(goal)}


@settings(max_examples=25, deadline=None)
@given(
    extra=st.dictionaries(st.sampled_from(["wire2", "wire3", "wire4", "lamp"]), st.integers(1, 2), max_size=3),
    columns=st.integers(3, 5),
    rows=st.integers(3, 4),
    max_pieces=st.sampled_from([4, 6]),
    placed=st.booleans(),
)
def test_the_search_finds_exactly_the_loops_a_brute_force_enumeration_finds(
    extra: dict[str, int], columns: int, rows: int, max_pieces: int, placed: bool
) -> None:
    inventory = dict(Counter(BASE) + Counter(extra))
    board = Board(columns, rows).place("w", "battery", BoardPose(0, 0, 0, 0)) if placed else None
    fixed = frozenset({Segment("battery", BoardPose(0, 0, 0, 0))}) if placed else frozenset()
    if placed:
        inventory["battery"] -= 1
    search = LayoutSearch(columns, rows, GOAL, max_pieces=max_pieces)
    loops = [loop.pieces for loop in search.loops(inventory, board)]
    assert len(loops) == len(set(loops))  # no loop twice
    assert set(loops) == _brute_force_loops(columns, rows, GOAL, inventory, max_pieces, fixed)
