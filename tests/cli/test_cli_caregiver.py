"""``supportive caregiver``: watching a novice and the caregiver robot in the terminal and as a GIF (§3.5)."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from supportive.errors import ExportError, MissingExtraError
from supportive.render.household import GIF_SIGNATURE, write_gif
from supportive.safety.episode import run_episode
from supportive.worlds.household import load_map

CliRunner = Callable[[list[str]], tuple[int, str, str]]

RUN = ["caregiver", "--map", "playroom", "--novice", "0.5", "--seed", "1", "--steps", "5"]


def _one_line_error(code: int, out: str, err: str) -> str:
    assert code == 2
    assert out == ""
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("supportive: error: ")
    return lines[0]


def test_runs_on_a_shipped_map_and_prints_the_summary(cli: CliRunner) -> None:
    code, out, _ = cli(RUN)
    assert code == 0
    assert "playroom: a novice making 50% random moves (ε = 0.5), with the caregiver" in out
    assert "N novice · R caregiver" in out
    assert out.count("╭─ playroom") == 5
    assert "step      1 of 5" in out and "step      5 of 5" in out
    assert "#S........B#" in out and "P(safe|τ) 0." in out
    assert "block the stairwell at (6, 10)" in out
    summary = out.strip().splitlines()[-1]
    assert summary.startswith("with the caregiver: damage ")
    assert "damage 15 not reached in 5 steps" in summary and "cells explored:" in summary
    assert "toy bins reached:" in summary and "(never reached)" not in summary


def test_without_the_caregiver_the_output_differs(cli: CliRunner) -> None:
    _, helped, _ = cli(RUN)
    code, alone, _ = cli([*RUN, "--no-caregiver"])
    assert code == 0 and alone != helped
    assert "without a caregiver" in alone and "caregiver none" in alone
    assert "no caregiver to estimate it" in alone
    assert alone.strip().splitlines()[-1].startswith("without a caregiver: damage ")


def test_the_same_seed_gives_the_same_output(cli: CliRunner) -> None:
    _, first, _ = cli(RUN)
    _, second, _ = cli(RUN)
    _, other, _ = cli([*RUN[:-4], "--seed", "2", "--steps", "5"])
    assert first == second != other


def test_every_prints_every_kth_step_and_the_last(cli: CliRunner) -> None:
    code, out, _ = cli(["caregiver", "--map", "playroom", "--steps", "7", "--every", "3"])
    assert code == 0
    steps = [line.split("step")[1].split()[0] for line in out.splitlines() if " of 7 " in line]
    assert steps == ["3", "6", "7"]


def test_delay_waits_between_printed_steps(cli: CliRunner, monkeypatch: pytest.MonkeyPatch) -> None:
    import time

    waits: list[float] = []
    monkeypatch.setattr(time, "sleep", waits.append)
    code, _, _ = cli(["caregiver", "--map", "playroom", "--steps", "3", "--delay", "0.25"])
    assert code == 0 and waits == [0.25, 0.25]


def test_gif_is_written(tmp_path: Path, cli: CliRunner) -> None:
    pytest.importorskip("matplotlib")
    target = tmp_path / "runs" / "episode.gif"
    code, out, err = cli([*RUN, "--gif", str(target)])
    assert code == 0 and "with the caregiver: damage" in out
    assert target.read_bytes().startswith(GIF_SIGNATURE)
    assert f"wrote {target} (5 frames)" in err
    from PIL import Image

    with Image.open(target) as image:
        assert getattr(image, "n_frames", 1) == 5  # an animated GIF (PIL types no frames on Image)


def test_a_bad_map_file_names_file_line_and_column(tmp_path: Path, cli: CliRunner) -> None:
    path = tmp_path / "bad.map"
    path.write_text("; a comment line\n#####\n#B.X#\n#####\n")
    line = _one_line_error(*cli(["caregiver", "--map", str(path), "--steps", "3"]))
    assert line.startswith(f"supportive: error: {path}:3:4: unknown map character 'X'")


def test_a_map_without_a_toy_bin_exits_2(tmp_path: Path, cli: CliRunner) -> None:
    path = tmp_path / "nobin.map"
    path.write_text("#####\n#..S#\n#...#\n#####\n")
    line = _one_line_error(*cli(["caregiver", "--map", str(path)]))
    assert str(path) in line and "no toy bin" in line


def test_unknown_map_names_and_missing_files_exit_2(tmp_path: Path, cli: CliRunner) -> None:
    line = _one_line_error(*cli(["caregiver", "--map", "castle"]))
    assert "castle: no shipped map of this name" in line and "playroom" in line
    missing = tmp_path / "missing.map"
    assert str(missing) in _one_line_error(*cli(["caregiver", "--map", str(missing)]))


@pytest.mark.parametrize("epsilon", ["1.5", "-0.1", "nan"])
def test_novice_epsilon_out_of_range_exits_2(epsilon: str, cli: CliRunner) -> None:
    line = _one_line_error(*cli(["caregiver", "--map", "playroom", "--novice", epsilon]))
    assert "--novice" in line and "[0, 1]" in line


def test_write_gif_needs_frames_and_matplotlib(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    grid = load_map("playroom")
    with pytest.raises(ExportError, match="no frames"):
        write_gif((), grid, tmp_path / "empty.gif")
    frames = run_episode(grid, 1.0, steps=2, seed=0, record=True).frames
    for name in ("matplotlib", "matplotlib.backends.backend_agg", "matplotlib.figure"):
        monkeypatch.setitem(sys.modules, name, None)
    with pytest.raises(MissingExtraError, match=r"supportive\[plot\]"):
        write_gif(frames, grid, tmp_path / "run.gif")
    assert not (tmp_path / "run.gif").exists()


def test_reaching_a_toy_bin_is_no_collision() -> None:
    """Issue 26: a novice reaching its goal, a toy bin, was counted as a collision. Oracle: the frames."""
    result = run_episode(load_map("playroom"), 0.3, caregiver=False, seed=2, steps=60, record=True)
    reached = sum(f.collision is not None and f.collision.kind == "bin" for f in result.frames)
    assert reached > 0 and result.bins_reached == reached and "bin" not in result.collisions
    assert sum(result.collisions.values()) == sum(
        f.collision is not None and f.collision.kind != "bin" for f in result.frames
    )


def test_a_terminal_gets_a_delay_by_default(monkeypatch: pytest.MonkeyPatch) -> None:
    """Issue 26: on a terminal 200 steps scrolled past in 2 s: the default delay was 0."""
    import time

    from supportive.cli import caregiver as command
    from supportive.cli.output import out

    waits: list[float] = []
    monkeypatch.setattr(time, "sleep", waits.append)
    monkeypatch.setattr(type(out), "is_terminal", property(lambda self: True))
    command.caregiver(map_name="playroom", novice=0.5, seed=1, steps=4, no_caregiver=False, gif=None, every=1, delay=None)
    assert waits == [command.TERMINAL_DELAY] * 3
    waits.clear()
    monkeypatch.setattr(type(out), "is_terminal", property(lambda self: False))
    command.caregiver(map_name="playroom", novice=0.5, seed=1, steps=4, no_caregiver=False, gif=None, every=1, delay=None)
    assert waits == []
