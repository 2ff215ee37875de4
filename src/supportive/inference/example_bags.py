"""The thesis's chair and workbench examples as ROS 2 bags (MCAP), made from the bundled task files.

``python -m supportive.inference.example_bags DIR`` (``make example-bags``) writes ``DIR/ikea-chair`` and
``DIR/workbench-blocks``: every demonstration after a marker on ``/task/demonstration``
(``supportive_msgs/msg/Demonstration``: id and agent), each action on ``/task/action`` (``std_msgs/msg/String``)
one second after the one before; the chair's bag also holds what an observer would have seen during its first
demonstration, on ``/contacts`` (``supportive_msgs/msg/ContactFrame``, five frames a second, each drawn from
the chair's declared observation model with a fixed seed). The same command writes the same messages; the repository ships its
output in ``examples/bags/``.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

from supportive.examples import load
from supportive.inference.observations import ObservationModel
from supportive.io.rosbag import BagWriter, ContactFrame, write_contact_frames, write_demonstrations
from supportive.seeding import Seed, rng_from
from supportive.tasks.spec import TaskSpec

__all__ = ["EXAMPLES", "START", "write_example_bag", "write_example_bags"]

EXAMPLES = ("ikea-chair", "workbench-blocks")
START = 1_704_067_200 * 1_000_000_000
"""When the examples' recordings begin: 2024-01-01 00:00:00 UTC, in ns."""
_FRAMES_PER_STEP = 5
_SECOND = 1_000_000_000


def _frames(spec: TaskSpec, origin: int, seed: Seed) -> Iterator[ContactFrame]:
    """What an observer sees during the first demonstration, which begins at ``origin``."""
    model = ObservationModel.from_spec(spec)
    rng = rng_from(seed)
    for index, step in enumerate(spec.demonstrations[0].steps):
        for frame in range(_FRAMES_PER_STEP):
            time = origin + index * _SECOND + frame * _SECOND // _FRAMES_PER_STEP
            yield model.sample(step.action, rng), time


def write_example_bag(name: str, directory: Path, seed: Seed = 0) -> Path:
    """Write one example's bag into ``directory`` (as ``directory/name``); its path.

    Raises:
        TaskFileError: for an unknown example.
        BagError: when the bag exists already or cannot be written.
    """
    spec = load(name)
    path = directory / name
    with BagWriter(path, "mcap") as writer:
        origins = write_demonstrations(writer, spec.demonstrations, start=START)
        if all(action.observations for action in spec.actions):
            write_contact_frames(writer, _frames(spec, origins[0], seed))
    return path


def write_example_bags(directory: Path, seed: Seed = 0) -> list[Path]:
    """Write every example's bag into ``directory``; their paths."""
    return [write_example_bag(name, directory, seed) for name in EXAMPLES]


if __name__ == "__main__":  # pragma: no cover - run by make example-bags
    for written in write_example_bags(Path(sys.argv[1] if len(sys.argv) > 1 else "examples/bags")):
        print(f"wrote {written}")
