"""Circuit scenarios: a table, a board, pieces and a goal, as a file or at random (§3.2.9).

A scenario file (YAML or JSON)::

    name: two-cells-and-an-led
    table: {width: 104, depth: 70}          # cm; the lead works from y < 0, the support agent from y > depth
    board: {columns: 6, rows: 5, pitch: 4, at: [44, 8]}   # where grid point (0, 0) lies on the table
    goal: {light: led, batteries_in_series: 2, switch_controls: true}
    scatter: {seed: 3, pieces: {battery: 2, switch: 1, led: 1, wire2: 3, wire3: 2}}
    # or, instead of scatter, every piece where it lies:
    # pieces: [{id: b1, kind: battery, at: [12, 40], rotation: 0}, ...]
    lead: {speed: 0.33}                     # a fraction of full speed (30 cm/s)
    support: {speed: 1.0}
    planner: {scheme: conservative, environments: 200, quickest: 15, spread: 15, max_pieces: 6,
              search_limit: 250000, estimate_limit: 200000}

Every field but ``name`` and one of ``pieces`` / ``scatter`` has a default (the thesis-size task of
Figure 3.3). Problems are reported as :class:`~supportive.errors.ScenarioFileError` with the file, line and
field.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, StringConstraints, ValidationError, model_validator

from supportive.envs.circuits.goals import CircuitGoal
from supportive.envs.circuits.pieces import PIECE_TYPES
from supportive.envs.circuits.plans import CircuitPlan, known_plans
from supportive.envs.circuits.world import BoardGeometry, CircuitWorld, circuit_item_types
from supportive.envs.tabletop.arms import ArmModel
from supportive.envs.tabletop.geometry import Rect
from supportive.envs.tabletop.items import TablePose
from supportive.envs.tabletop.layout import TableLayout
from supportive.errors import InvalidValueError, PlanningError, ScenarioFileError, SearchLimitError
from supportive.io.safe_load import check_kind, read_text
from supportive.io.structured import kind_of, line_of, load_structured, place_of, schema_error
from supportive.io.values import Coordinate
from supportive.planning.selection import SupportPlanner
from supportive.planning.weighting import WeightingScheme

__all__ = [
    "THESIS_PIECES",
    "CircuitScenario",
    "parse_scenario_file",
    "parse_scenario_string",
    "scatter_pieces",
    "thesis_scenario",
]

THESIS_PIECES: Mapping[str, int] = {
    "battery": 2,
    "switch": 1,
    "led": 1,
    "wire2": 3,
    "wire3": 2,
    "wire4": 2,
    "wire5": 1,
    "lamp": 1,
    "resistor": 1,
}
"""The pieces of the thesis-size task (Figure 3.3: two cells in series drive an LED on a switched circuit),
with excess wires, a lamp and a resistor that allow worse but more obvious circuits."""

_EDGE = 4.0  # cm kept free along the table's edges when scattering
_SCATTER_TRIES = 10_000
Name = Annotated[str, StringConstraints(strip_whitespace=True, min_length=1)]
Positive = Annotated[float, Field(gt=0, le=10_000, allow_inf_nan=False)]  # cm: a table of at most 100 m


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class TableIn(_Strict):
    width: Positive = 104.0
    depth: Positive = 70.0
    tray: tuple[Coordinate, Coordinate, Coordinate, Coordinate] | None = None


class BoardIn(_Strict):
    columns: Annotated[int, Field(ge=2, le=20)] = 6
    rows: Annotated[int, Field(ge=2, le=20)] = 5
    pitch: Positive = 4.0
    at: tuple[Coordinate, Coordinate] | None = None


class GoalIn(_Strict):
    light: Literal["led", "lamp"] = "led"
    batteries_in_series: Annotated[int, Field(ge=0, le=100)] = 2
    switch_controls: bool = True
    no_short: bool = True


class PieceIn(_Strict):
    id: Name
    kind: Name
    at: tuple[Coordinate, Coordinate]
    rotation: Annotated[int, Field(ge=0, le=3)] = 0


class ScatterIn(_Strict):
    seed: Annotated[int, Field(ge=0, le=2**63 - 1)] = 0
    pieces: dict[Name, Annotated[int, Field(ge=1, le=100)]]


class ArmIn(_Strict):
    speed: Annotated[float, Field(gt=0, le=1, allow_inf_nan=False)] = 1.0


class PlannerIn(_Strict):
    scheme: Literal["conservative", "greedy", "aggressive"] = "conservative"
    environments: Annotated[int, Field(ge=1, le=100_000)] = 200
    quickest: Annotated[int, Field(ge=1, le=100_000)] = 15
    spread: Annotated[int, Field(ge=0, le=100_000)] = 15
    max_pieces: Annotated[int, Field(ge=4, le=8)] = 6
    search_limit: Annotated[int, Field(ge=1_000, le=1_000_000_000)] | None = None
    estimate_limit: Annotated[int, Field(ge=1_000, le=1_000_000_000)] | None = None


class ScenarioIn(_Strict):
    name: Name
    description: str | None = None
    table: TableIn = TableIn()
    board: BoardIn = BoardIn()
    goal: GoalIn = GoalIn()
    pieces: list[PieceIn] | None = None
    scatter: ScatterIn | None = None
    lead: ArmIn = ArmIn()
    support: ArmIn = ArmIn()
    planner: PlannerIn = PlannerIn()

    @model_validator(mode="after")
    def _one_source(self) -> ScenarioIn:
        if (self.pieces is None) == (self.scatter is None):
            raise InvalidValueError("give the pieces either as 'pieces' (where each lies) or as 'scatter', not both")
        return self


@dataclass(frozen=True)
class CircuitScenario:
    """A circuit task at a table, and how the support agent plans for it.

    Attributes:
        name: The scenario's name.
        world: The world (its initial state is the scenario's table).
        scheme: The plan weighting.
        environments: Hypothetical environments per decision.
        quickest: Π_T: how many of the quickest circuits.
        spread: Π_T: how many more, spread over the rest.
        max_pieces: Π_T: the largest circuit enumerated.
        description: Words for people.
        search_limit: Π_T: the most pieces the enumeration of circuits may try (1,000 to 10^9; default
            250,000, three times what the thesis-size table needs with ``max_pieces`` 6, a few seconds):
            :meth:`plans` stops there with a one-line error rather than run on for minutes.
        estimate_limit: The most duration estimates (Algorithm 5) one decision may make: hypothetical
            environments × known plans (1,000 to 10^9; default 200,000, some 12 s on two cores; the thesis's
            settings make 6,200). :meth:`check_decision` refuses more before any is made.
    """

    name: str
    world: CircuitWorld
    scheme: WeightingScheme = WeightingScheme.CONSERVATIVE
    environments: int = 200
    quickest: int = 15
    spread: int = 15
    max_pieces: int = 6
    description: str = ""
    search_limit: int = 250_000
    estimate_limit: int = 200_000

    def check_decision(self, plans: Sequence[CircuitPlan]) -> None:
        """Check that a decision over ``plans`` stays within :attr:`estimate_limit` duration estimates.

        Raises:
            SearchLimitError: when the hypothetical environments times the known plans exceed it; the message
                says what to change.
        """
        estimates = self.environments * len(plans)
        if estimates > self.estimate_limit:
            raise SearchLimitError(
                f"planner: {self.environments:,} hypothetical environments × {len(plans):,} known plans = "
                f"{estimates:,} duration estimates per decision, more than planner.estimate_limit "
                f"({self.estimate_limit:,}): lower the environments (--environments or planner.environments), "
                "planner.quickest or planner.spread, or raise planner.estimate_limit"
            )

    def plans(self) -> tuple[CircuitPlan, ...]:
        """Π_T for this scenario (see :func:`~supportive.envs.circuits.plans.known_plans`).

        Raises:
            PlanningError: when the pieces allow no circuit that meets the goal.
            SearchLimitError: when enumerating the circuits tried :attr:`search_limit` pieces before it was
                complete; the message says what to change.
        """
        try:
            return known_plans(
                self.world, self.quickest, self.spread, max_pieces=self.max_pieces, search_limit=self.search_limit
            )
        except SearchLimitError:
            raise SearchLimitError(
                f"planner: the search for circuits of up to {self.max_pieces} pieces stopped at "
                f"planner.search_limit ({self.search_limit:,} pieces tried) before it had them all: lower "
                "planner.max_pieces, use fewer pieces, or raise planner.search_limit (some 30,000 pieces a second)"
            ) from None

    def planner(self, **options: Any) -> SupportPlanner[Any, Any, Any]:
        """A support planner with the scenario's scheme and number of environments (``options`` override)."""
        settings: dict[str, Any] = {"environments": self.environments, **options}
        return SupportPlanner(settings.pop("scheme", self.scheme), **settings)


def _layout(table: TableIn, board: BoardGeometry) -> TableLayout:
    tray = None if table.tray is None else Rect(*table.tray)
    return TableLayout(Rect(0.0, 0.0, table.width, table.depth), board.area.grown(2.0), tray=tray)


def _arms(table: TableIn, lead: float, support: float) -> tuple[ArmModel, ArmModel]:
    middle = table.width / 2
    return (
        ArmModel("lead", (middle, -12.0), speed_factor=lead),
        ArmModel("support", (middle, table.depth + 14.0), speed_factor=support),
    )


def _board(model: BoardIn, table: TableIn) -> BoardGeometry:
    width = (model.columns - 1) * model.pitch
    at = model.at or (round(table.width / 2 - width / 2, 1), 8.0)
    return BoardGeometry(model.columns, model.rows, model.pitch, at)


def scatter_pieces(
    counts: Mapping[str, int], layout: TableLayout, pitch: float, seed: int | np.random.Generator | None
) -> list[tuple[str, str, TablePose]]:
    """Pieces scattered on the table at random: whole-centimetre positions and any rotation, each clear of
    the board, the table's edges and the pieces before it; ids are ``kind-n`` in catalogue order.

    Raises:
        PlanningError: for an unknown kind, or a table too crowded to scatter on.
    """
    unknown = sorted(set(counts) - set(PIECE_TYPES))
    if unknown:
        raise PlanningError(f"unknown piece kinds {', '.join(unknown)}: expected {', '.join(PIECE_TYPES)}")
    rng = np.random.default_rng(seed)
    types = circuit_item_types(pitch)
    table = layout.table
    inner = Rect(table.x0 + _EDGE, table.y0 + _EDGE, table.x1 - _EDGE, table.y1 - _EDGE)
    placed: list[tuple[str, str, TablePose]] = []
    index = 0
    for kind in PIECE_TYPES:
        for _ in range(counts.get(kind, 0)):
            for _ in range(_SCATTER_TRIES):
                x = float(rng.integers(int(inner.x0), int(inner.x1) + 1))
                y = float(rng.integers(int(inner.y0), int(inner.y1) + 1))
                pose = TablePose(x, y, int(rng.integers(4)))
                footprint = pose.footprint(types[kind])
                if (
                    inner.encloses(footprint)
                    and layout.lies_on_surface(footprint)
                    and not any(
                        footprint.overlaps(other.footprint(types[k]), layout.clearance)
                        for _, k, other in placed
                    )
                ):
                    placed.append((f"{kind}-{index}", kind, pose))
                    index += 1
                    break
            else:
                raise PlanningError(f"the table is too crowded to scatter {sum(counts.values())} pieces on")
    return placed


def thesis_scenario(
    seed: int = 0,
    *,
    lead: float = 1.0,
    support: float = 1.0,
    scheme: str = "conservative",
    environments: int = 200,
) -> CircuitScenario:
    """The thesis-size task (Figure 3.3) with :data:`THESIS_PIECES` scattered from ``seed``."""
    table, board_in = TableIn(), BoardIn()
    board = _board(board_in, table)
    layout = _layout(table, board)
    lead_arm, support_arm = _arms(table, lead, support)
    pieces = scatter_pieces(THESIS_PIECES, layout, board.pitch, seed)
    goal = CircuitGoal(batteries_in_series=2, switch_controls=True)
    world = CircuitWorld(board, goal, layout, pieces, lead_arm, support_arm)
    return CircuitScenario(
        f"thesis-{seed}", world, WeightingScheme(scheme), environments, description=goal.text
    )


def parse_scenario_file(path: str | Path) -> CircuitScenario:
    """Read a scenario file (.yaml, .yml or .json).

    Raises:
        ScenarioFileError: when the file is missing, unreadable or invalid.
    """
    path = Path(path)
    suffix = check_kind(path, (".yaml", ".yml", ".json"), "a circuit scenario file", ScenarioFileError)
    return parse_scenario_string(
        read_text(path, ScenarioFileError), "json" if suffix == ".json" else "yaml", path=path
    )


def parse_scenario_string(
    text: str, format: Literal["yaml", "json"] = "yaml", *, path: str | Path | None = None
) -> CircuitScenario:
    """Read a scenario from text.

    Raises:
        ScenarioFileError: for text that is not a valid scenario (the message names the line and field).
    """
    if not text.strip():
        raise ScenarioFileError("file is empty", path=path)
    data = load_structured(text, format, path, ScenarioFileError)
    if not isinstance(data, dict):
        raise ScenarioFileError(
            f"expected a mapping with at least 'name', got {kind_of(data)}", path=path, line=1
        )
    try:
        model = ScenarioIn.model_validate(data)
    except ValidationError as exc:
        raise schema_error(exc, text, path, ScenarioFileError, ScenarioIn) from None

    def fail(problem: str, loc: Sequence[str | int]) -> ScenarioFileError:
        return ScenarioFileError(problem, path=path, place=place_of(loc), line=line_of(text, loc))

    try:
        board = _board(model.board, model.table)
        layout = _layout(model.table, board)
    except PlanningError as exc:
        raise fail(str(exc), ["board"]) from None
    pieces = _pieces(model, layout, board, fail)
    goal = CircuitGoal(
        model.goal.light, model.goal.batteries_in_series, model.goal.switch_controls, model.goal.no_short
    )
    lead, support = _arms(model.table, model.lead.speed, model.support.speed)
    try:
        world = CircuitWorld(board, goal, layout, pieces, lead, support)
    except PlanningError as exc:
        raise fail(str(exc), ["pieces"]) from None
    planner = model.planner
    return CircuitScenario(
        model.name,
        world,
        WeightingScheme(planner.scheme),
        planner.environments,
        planner.quickest,
        planner.spread,
        planner.max_pieces,
        model.description or goal.text,
        **{name: value for name in ("search_limit", "estimate_limit") if (value := getattr(planner, name)) is not None},
    )


def _pieces(
    model: ScenarioIn,
    layout: TableLayout,
    board: BoardGeometry,
    fail: Callable[[str, Sequence[str | int]], ScenarioFileError],
) -> list[tuple[str, str, TablePose]]:
    """The scenario's pieces: scattered, or each where the file says (checked one by one)."""
    if model.scatter is not None:
        for kind in model.scatter.pieces:
            if kind not in PIECE_TYPES:
                raise fail(
                    f"unknown piece kind {kind!r}: expected one of {', '.join(PIECE_TYPES)}",
                    ["scatter", "pieces", kind],
                )
        try:
            return scatter_pieces(model.scatter.pieces, layout, board.pitch, model.scatter.seed)
        except PlanningError as exc:
            raise fail(str(exc), ["scatter"]) from None
    types = circuit_item_types(board.pitch)
    seen: set[str] = set()
    placed: list[tuple[str, str, TablePose]] = []
    for index, piece in enumerate(model.pieces or ()):
        loc: list[str | int] = ["pieces", index]
        if piece.kind not in PIECE_TYPES:
            raise fail(
                f"unknown piece kind {piece.kind!r}: expected one of {', '.join(PIECE_TYPES)}", [*loc, "kind"]
            )
        if piece.id in seen:
            raise fail(f"piece id {piece.id!r} is used twice", [*loc, "id"])
        seen.add(piece.id)
        pose = TablePose(piece.at[0], piece.at[1], piece.rotation)
        footprint = pose.footprint(types[piece.kind])
        if not layout.lies_on_surface(footprint):
            raise fail(f"piece {piece.id} at {piece.at} is off the table or on the board", [*loc, "at"])
        for other_id, kind, other in placed:
            if footprint.overlaps(other.footprint(types[kind]), layout.clearance):
                raise fail(f"piece {piece.id} at {piece.at} overlaps {other_id}", [*loc, "at"])
        placed.append((piece.id, piece.kind, pose))
    return placed
