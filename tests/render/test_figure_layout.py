"""Figures whose labels and legends do not overlap (issue 26: they did in `support --render` and the
reproduce plots)."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from supportive.render.layout import legends_outside, spread_labels


def test_a_legend_is_moved_off_the_data_and_stays_on_the_page(tmp_path: Path) -> None:
    figure = Figure(figsize=(4, 3))
    FigureCanvasAgg(figure)
    for i in range(2):
        axes = figure.add_subplot(1, 2, i + 1)
        axes.fill_between([0, 1], [0, 0], [1, 1], label="everywhere")  # data under every spot a legend could take
        axes.plot([0, 1], [1, 0], label="a line with a long name")
        axes.legend(loc="center", fontsize=7, title="kinds")
    legends_outside(figure)
    figure.savefig(tmp_path / "f.png")
    renderer = figure.canvas.get_renderer()  # type: ignore[attr-defined]
    page = figure.bbox
    for axes in figure.axes:
        legend = axes.get_legend()
        assert legend is not None
        box = legend.get_window_extent(renderer)
        assert not box.overlaps(axes.get_window_extent(renderer))
        assert page.x0 <= box.x0 and box.x1 <= page.x1 + 1 and page.y0 <= box.y0 and box.y1 <= page.y1 + 1
        assert [t.get_text() for t in legend.get_texts()] == ["everywhere", "a line with a long name"]
        assert legend.get_title().get_text() == "kinds"
    first, second = (axes.get_legend().get_window_extent(renderer) for axes in figure.axes)  # type: ignore[union-attr]
    assert not first.overlaps(second)


def test_labels_of_items_close_together_are_spread_apart() -> None:
    figure = Figure(figsize=(4, 4))
    FigureCanvasAgg(figure)
    axes = figure.add_subplot()
    axes.set_xlim(0, 100)
    axes.set_ylim(0, 100)
    boxes = [(40 + 3 * i, 45, 42 + 3 * i, 55) for i in range(3)] + [(10, 10, 14, 14)]
    labels = [(axes.text((b[0] + b[2]) / 2, (b[1] + b[3]) / 2, f"item-{i}", fontsize=6), b) for i, b in enumerate(boxes)]
    figure.draw_without_rendering()
    moved = spread_labels(axes, labels)
    renderer = figure.canvas.get_renderer()  # type: ignore[attr-defined]
    extents = [text.get_window_extent(renderer) for text, _ in labels]
    assert moved >= 2
    assert not any(a.overlaps(b) for a, b in itertools.combinations(extents, 2))
    assert labels[3][0].get_position() == (12.0, 12.0)  # a label with room stays on its item


def test_the_circuit_picture_has_no_overlapping_labels(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from supportive.envs.circuits.scenario import parse_scenario_file
    from supportive.examples import circuit_path
    from supportive.render import circuits

    seen: list[list[object]] = []
    spread = circuits.spread_labels  # type: ignore[attr-defined]

    def watched(axes: object, labels: list[tuple[object, tuple[float, float, float, float]]]) -> int:
        moved = spread(axes, labels)
        seen.append([text.get_window_extent(text.figure.canvas.get_renderer()) for text, _ in labels])  # type: ignore[attr-defined]
        return moved

    monkeypatch.setattr(circuits, "spread_labels", watched)
    world = parse_scenario_file(circuit_path("two-cells-led")).world
    circuits.write_before_after(world, world.initial_state, world.initial_state, tmp_path / "t.png")
    assert len(seen) == 2 and all(seen)
    for extents in seen:
        assert not any(a.overlaps(b) for a, b in itertools.combinations(extents, 2))  # type: ignore[attr-defined]
