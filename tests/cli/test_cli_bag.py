"""``supportive bag`` and ``supportive infer --bag`` end to end: task files through bags of every format and
back, the failures a user meets (one line on stderr, exit 2, nothing written), and beliefs written back that
equal ``infer --observations`` on the same contact events."""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest
from rosbags.highlevel import AnyReader

from supportive import examples
from supportive.inference.example_bags import EXAMPLES, write_example_bags
from supportive.io.rosbag import BagWriter, Storage, write_contact_frames
from supportive.io.rosbag.writing import LATCHED
from supportive.io.taskfile import dump_task, parse_task_file, task_to_dict, write_task_file
from supportive.tasks.spec import Demonstration, Step, TaskSpec

CliRunner = Callable[[list[str]], tuple[int, str, str]]
SHIPPED = Path(__file__).resolve().parents[2] / "examples" / "bags"
T0 = 1_700_000_000 * 1_000_000_000


def timed_chair(tmp_path: Path) -> Path:
    """The chair with every step timed (starts 1.25 s apart, most with an end), in canonical form."""
    spec = examples.load("ikea-chair")
    demos = tuple(
        replace(
            demo,
            steps=tuple(
                Step(s.action, 1.25 * k, None if k % 5 == 4 else 1.25 * k + 0.75)
                for k, s in enumerate(demo.steps)
            ),
        )
        for demo in spec.demonstrations
    )
    path = tmp_path / "chair.yaml"
    write_task_file(replace(spec, demonstrations=demos), path)
    return path


def bag_name(storage: str) -> str:
    return "rec.bag" if storage == "rosbag1" else "rec"


@pytest.mark.parametrize("storage", ["mcap", "sqlite3", "rosbag1"])
def test_a_task_file_survives_a_bag_of_every_format(tmp_path: Path, cli: CliRunner, storage: str) -> None:
    task = timed_chair(tmp_path)
    bag = tmp_path / bag_name(storage)
    code, _, err = cli(["bag", "export", str(task), "-o", str(bag), "--format", storage])
    assert code == 0 and "6 demonstrations" in err
    out = tmp_path / "out.yaml"
    args = [
        "bag",
        "import",
        str(bag),
        "--segment-topic",
        "/task/demonstration",
        "--task",
        str(task),
        "-o",
        str(out),
    ]
    code, _, _ = cli(args)
    assert code == 0
    assert out.read_text() == task.read_text()
    code, bare, _ = cli(
        ["bag", "import", str(bag), "--segment-topic", "/task/demonstration", "--name", "ikea-chair"]
    )
    spec = parse_task_file(task)
    assert code == 0 and bare == dump_task(TaskSpec(spec.name, (), None, spec.demonstrations), "yaml")
    learned: list[Any] = []
    for source in (task, out):
        code, text, _ = cli(["learn", str(source), "-f", "json"])
        learned.append({k: v for k, v in json.loads(text).items() if k != "stats"})
    assert learned[0] == learned[1]


def test_several_bags_one_demonstration_each_with_an_agent_as_csv(tmp_path: Path, cli: CliRunner) -> None:
    bags = []
    for name, actions in (("trial-1", ["a", "b"]), ("trial-2", ["b", "a"])):
        path = tmp_path / name
        with BagWriter(path, "mcap") as writer:
            topic = writer.topic("/task/action", "std_msgs/msg/String")
            for k, action in enumerate(actions):
                writer.write(topic, T0 + k * 2 * 10**9, writer.message("std_msgs/msg/String", data=action))
        bags.append(str(path))
    out = tmp_path / "trials.csv"
    code, _, _ = cli(["bag", "import", *bags, "--agent", "erin", "-o", str(out)])
    assert code == 0
    assert parse_task_file(out).demonstrations == (
        Demonstration((Step("a", 0.0), Step("b", 2.0)), "trial-1", "erin"),
        Demonstration((Step("b", 0.0), Step("a", 2.0)), "trial-2", "erin"),
    )


def _failures(tmp_path: Path) -> list[tuple[list[str], str]]:
    good = tmp_path / "good"
    with BagWriter(good, "mcap") as writer:
        topic = writer.topic("/task/action", "std_msgs/msg/String")
        writer.write(topic, T0, writer.message("std_msgs/msg/String", data="get_seat"))
        writer.write(topic, T0 + 10**9, writer.message("std_msgs/msg/String", data="fly_away"))
        writer.topic("/silent", "std_msgs/msg/String")
        contacts = writer.topic("/imu", "std_msgs/msg/Float64")
        writer.write(contacts, T0, writer.message("std_msgs/msg/Float64", data=0.5))
    broken = tmp_path / "broken.bag"
    broken.write_bytes(b"#ROSBAG V2.0\n" + b"\x00" * 40)
    chair = str(examples.path("ikea-chair"))
    odd = {}
    for name, action in (("bell", "get\x07seat"), ("huge", "a" * 5_000_000)):  # ids learn would refuse
        odd[name] = tmp_path / name
        with BagWriter(odd[name], "mcap") as writer:
            topic = writer.topic("/task/action", "std_msgs/msg/String")
            writer.write(topic, T0, writer.message("std_msgs/msg/String", data=action))
    piped = tmp_path / "piped"  # a FIFO where the bag's data would be: reading it would wait for ever
    shutil.copytree(good, piped)
    data = next(piped.glob("*.mcap"))
    data.unlink()
    os.mkfifo(data)
    loop = tmp_path / "loop"
    loop.symlink_to(loop)
    return [
        (
            ["bag", "import", str(odd["bell"])],
            f"{odd['bell']}: topic /task/action: the action id of the message at 0.000 s may not contain",
        ),
        (
            ["bag", "import", str(odd["huge"])],
            f"{odd['huge']}: topic /task/action: the action id of the message at 0.000 s is at most",
        ),
        (["bag", "import", str(piped)], f"{piped}: {data.name} is a FIFO, not a file: a bag holds files only"),
        (["infer", chair, "--bag", str(piped)], f"{piped}: {data.name} is a FIFO, not a file"),
        (["bag", "import", str(loop)], f"{loop}: cannot read loop: Too many levels of symbolic links"),
        (["infer", chair, "--bag", str(loop)], f"{loop}: cannot read loop: Too many levels of symbolic links"),
        (
            ["bag", "import", str(good), "--task", chair],
            f"{good}: topic /task/action: action 'fly_away' at 1.000 s is not one of the task's actions",
        ),
        (
            ["bag", "import", str(good), "--actions-topic", "/none"],
            f"{good}: no topic /none in the bag (it has: /imu, /silent, /task/action)",
        ),
        (
            ["bag", "import", str(good), "--actions-topic", "/silent"],
            f"{good}: topic /silent: the topic has no messages",
        ),
        (
            ["bag", "import", str(good), "--actions-topic", "/imu"],
            f"{good}: topic /imu: messages of type std_msgs/msg/Float64; expected",
        ),
        (
            ["bag", "import", str(good), "--segment-topic", "/imu"],
            f"{good}: topic /imu: messages of type std_msgs/msg/Float64; expected",
        ),
        (["bag", "import", str(broken)], f"{broken}: cannot open the bag: "),
        (["bag", "import", str(tmp_path / "gone")], f"{tmp_path / 'gone'}: no such bag"),
        (
            ["bag", "import", str(good), "--types", str(tmp_path / "nodefs")],
            f"{tmp_path / 'nodefs'}: no such message definition",
        ),
        (
            ["infer", chair, "--bag", str(good), "--contacts-topic", "/imu"],
            f"{good}: topic /imu: messages of type std_msgs/msg/Float64; expected",
        ),
        (
            ["infer", chair, "--bag", str(good), "--contacts-topic", "/none"],
            f"{good}: no topic /none in the bag",
        ),
        (["infer", chair, "--bag", str(broken)], f"{broken}: cannot open the bag: "),
        (["infer", chair], "give one source: --observations FILE, --actions FILE or --bag BAG"),
        (["bag", "export", chair, "-o", str(good)], f"{good}: exists already; a bag is never overwritten"),
    ]


def test_every_failure_is_one_line_and_writes_nothing(tmp_path: Path, cli: CliRunner) -> None:
    cases = _failures(tmp_path)
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    for args, expected in cases:
        out = tmp_path / "out.yaml"
        extra = ["-o", str(out)] if args[:2] == ["bag", "import"] else []
        extra += ["--write-bag", str(tmp_path / "beliefs")] if args[0] == "infer" and "--bag" in args else []
        code, stdout, err = cli([*args, *extra])
        assert code == 2, args
        assert err.startswith(f"supportive: error: {expected}"), (args, err)
        assert err.count("\n") == 1 and "Traceback" not in err and stdout == ""
        assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before, args


def frames_of_chair(seed: int, skip: str | None = None) -> list[tuple[frozenset[str], int]]:
    """Ten frames a second through the chair's d2 (without the step ``skip``), events drawn from its
    observation model."""
    from supportive.inference import ObservationModel

    spec = examples.load("ikea-chair")
    model = ObservationModel.from_spec(spec)
    import numpy as np

    rng = np.random.default_rng(seed)
    frames = []
    for k, step in enumerate(s for s in spec.demonstrations[1].steps if s.action != skip):
        for j in range(int(rng.integers(3, 9))):
            frames.append(
                (model.sample(step.action, rng), T0 + k * 10**9 + j * 10**8 + int(rng.integers(0, 999)))
            )
    return frames


def read_topics(path: Path) -> dict[str, list[tuple[int, Any]]]:
    """Every topic of a bag, read independently of supportive: time and message per message."""
    topics: dict[str, list[tuple[int, Any]]] = {}
    with AnyReader([path]) as reader:
        for connection, time, raw in reader.messages():
            topics.setdefault(connection.topic, []).append(
                (time, reader.deserialize(raw, connection.msgtype))
            )
    return topics


@pytest.mark.parametrize(("storage", "typed"), [("mcap", True), ("sqlite3", False), ("rosbag1", True)])
def test_beliefs_written_back_equal_infer_on_the_same_events(
    tmp_path: Path, cli: CliRunner, storage: Storage, typed: bool
) -> None:
    frames = frames_of_chair(seed=len(storage))
    bag = tmp_path / bag_name(storage)
    with BagWriter(bag, storage) as writer:
        write_contact_frames(writer, frames, topic="/perception/contacts", typed=typed)
    stream = tmp_path / "stream.jsonl"
    stream.write_text("".join(json.dumps({"events": sorted(e), "time": t / 1e9}) + "\n" for e, t in frames))
    chair = str(examples.path("ikea-chair"))
    code, expected, _ = cli(["infer", chair, "--observations", str(stream), "--top", "4"])
    assert code == 0
    out = tmp_path / "beliefs"
    args = ["infer", chair, "--bag", str(bag), "--contacts-topic", "/perception/contacts", "--top", "4"]
    code, printed, _ = cli([*args, "--write-bag", str(out)])
    assert code == 0 and printed == expected
    records = [json.loads(line) for line in expected.splitlines()]
    topics = read_topics(out)
    assert [(t, json.loads(m.data)) for t, m in topics["/supportive/belief"]] == [
        (t, r) for (_, t), r in zip(frames, records, strict=True)
    ]
    for name, key in (("subgoal", "subgoals"), ("subtask", "subtasks"), ("next", "next")):
        assert [(t, m.data) for t, m in topics[f"/supportive/{name}"]] == [
            (t, r[key][0][0]) for (_, t), r in zip(frames, records, strict=True)
        ]
        assert [m.data for _, m in topics[f"/supportive/{name}/probability"]] == [
            r[key][0][1] for r in records
        ]
    ((when, hierarchy),) = topics["/supportive/hierarchy"]
    code, learned, _ = cli(["learn", chair, "-f", "json"])
    assert when == frames[0][1] and json.loads(hierarchy.data)["roots"] == json.loads(learned)["roots"]
    with AnyReader([out]) as reader:
        latched = {c.topic: c.ext.offered_qos_profiles for c in reader.connections}  # type: ignore[union-attr]
    assert latched["/supportive/hierarchy"] == [LATCHED] and latched["/supportive/belief"] == []
    assert "/supportive/surprise" in topics  # the progress-aware tracker says how surprising each frame was
    assert next(out.glob("*.mcap"))


def test_a_skipped_step_is_a_mistake_in_the_printed_lines_and_the_belief_bag(tmp_path: Path, cli: CliRunner) -> None:
    frames = frames_of_chair(seed=7, skip="place_left_frame")
    bag = tmp_path / "rec"
    with BagWriter(bag, "mcap") as writer:
        write_contact_frames(writer, frames)
    out = tmp_path / "beliefs"
    code, printed, _ = cli(["infer", str(examples.path("ikea-chair")), "--bag", str(bag), "--write-bag", str(out)])
    assert code == 0
    records = [json.loads(line) for line in printed.splitlines()]
    judged = [r["mistake"] for r in records if "mistake" in r]
    flagged = [m for m in judged if m["mistake"]]
    assert flagged and flagged[0]["kind"] == "missing" and "place_left_frame" in flagged[0]["skipped"]
    assert flagged[0]["help"]["category"] == "enhancing awareness"
    assert "standing the left side frame on the table" in flagged[0]["help"]["say"]
    topics = read_topics(out)
    assert [m.data for _, m in topics["/supportive/mistake/probability"]] == [m["probability"] for m in judged]
    assert [json.loads(m.data) for _, m in topics["/supportive/mistake"]] == flagged


def test_the_shipped_example_bags_are_what_the_script_makes(tmp_path: Path) -> None:
    written = write_example_bags(tmp_path)
    assert [p.name for p in written] == list(EXAMPLES)
    for path in written:
        fresh, shipped = read_topics(path), read_topics(SHIPPED / path.name)
        assert fresh.keys() == shipped.keys()
        for topic in fresh:
            assert [(t, repr(m)) for t, m in fresh[topic]] == [(t, repr(m)) for t, m in shipped[topic]], topic


@pytest.mark.parametrize("name", EXAMPLES)
def test_the_readme_bag_import_gives_the_examples_demonstrations(
    tmp_path: Path, cli: CliRunner, name: str
) -> None:
    out = tmp_path / f"{name}.yaml"
    args = ["bag", "import", str(SHIPPED / name), "--segment-topic", "/task/demonstration", "--task"]
    code, _, _ = cli([*args, str(examples.path(name)), "-o", str(out)])
    spec, imported = examples.load(name), parse_task_file(out)
    assert code == 0
    assert [(d.id, d.agent, [s.action for s in d.steps]) for d in imported.demonstrations] == [
        (d.id, d.agent, [s.action for s in d.steps]) for d in spec.demonstrations
    ]
    assert [s.start for s in imported.demonstrations[0].steps] == [
        float(k) for k in range(len(spec.demonstrations[0].steps))
    ]
    assert task_to_dict(replace(imported, demonstrations=())) == task_to_dict(
        replace(spec, demonstrations=())
    )


def test_infer_on_the_shipped_chair_bag_follows_its_first_demonstration(cli: CliRunner) -> None:
    code, out, _ = cli(
        ["infer", str(examples.path("ikea-chair")), "--bag", str(SHIPPED / "ikea-chair"), "--top", "1"]
    )
    records = [json.loads(line) for line in out.splitlines()]
    truth = [s.action for s in examples.load("ikea-chair").demonstrations[0].steps]
    assert code == 0 and len(records) == 5 * len(truth)
    right = sum(r["subgoals"][0][0].split("#")[0] == truth[k // 5] for k, r in enumerate(records))
    assert right / len(records) > 0.7


def test_without_the_ros_extra_a_bag_command_says_what_to_install(
    cli: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    import sys

    for name in [
        m for m in sys.modules if m == "rosbags" or m.startswith(("rosbags.", "supportive.io.rosbag"))
    ]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "rosbags", None)  # what an environment without rosbags imports
    code, _, err = cli(["bag", "import", str(SHIPPED / "ikea-chair")])
    assert code == 2
    assert (
        err
        == "supportive: error: reading and writing ROS bags needs rosbags, which is not installed: pip install 'supportive[ros]'\n"
    )


def test_damage_found_mid_stream_stops_infer_and_leaves_no_belief_bag(tmp_path: Path, cli: CliRunner) -> None:
    frames = frames_of_chair(seed=3)
    bag = tmp_path / "contacts.bag"
    with BagWriter(bag, "rosbag1") as writer:
        write_contact_frames(writer, frames)
    data = bytearray(bag.read_bytes())
    at = data.index(b"hand-seat")  # a frame late in the recording: the length of its first event is broken
    data[at - 4 : at] = b"\xff\xff\xff\xff"
    bag.write_bytes(bytes(data))
    out = tmp_path / "beliefs"
    code, printed, err = cli(
        ["infer", str(examples.path("ikea-chair")), "--bag", str(bag), "--write-bag", str(out)]
    )
    assert code == 2 and err.startswith(f"supportive: error: {bag}: topic /contacts: cannot read the bag: ")
    assert printed == ""  # the bag is read through before anything is printed (issue 28)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["contacts.bag"]


def test_bag_import_never_writes_over_its_inputs_and_replaces_a_file_only_with_force(
    tmp_path: Path, cli: CliRunner
) -> None:
    """Issue 28: ``-o rec/metadata.yaml`` overwrote the bag's own metadata. An output inside a bag, equal to
    an input (also through a symlink), or inside a --types folder is refused; an existing file only with
    --force."""
    rec = tmp_path / "rec"
    assert cli(["bag", "export", str(examples.path("ikea-chair")), "-o", str(rec)])[0] == 0
    types = tmp_path / "types"
    types.mkdir()
    (types / "Note.msg").write_text("string data\n", encoding="utf-8")
    task = tmp_path / "task.yaml"
    task.write_text(examples.path("ikea-chair").read_text(encoding="utf-8"), encoding="utf-8")
    link = tmp_path / "link.yaml"
    link.symlink_to(rec / "metadata.yaml")
    files = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    segments = ["--segment-topic", "/task/demonstration"]
    for output, problem in [
        (rec / "metadata.yaml", "-o is inside the input"),
        (rec / "new.yaml", "-o is inside the input"),
        (link, "-o is inside the input"),
        (task, "-o is the input"),
        (types / "out.yaml", "-o is inside the input"),
        (rec, "-o is the input"),
    ]:
        code, out, err = cli(["bag", "import", str(rec), *segments, "--task", str(task), "--types", str(types),
                              "-o", str(output), "--force"])
        assert code == 2 and out == "" and err.count("\n") == 1 and problem in err, err
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == files
    target = tmp_path / "out.yaml"
    target.write_text("mine\n", encoding="utf-8")
    code, _, err = cli(["bag", "import", str(rec), *segments, "-o", str(target)])
    assert code == 2 and "exists already; give --force to replace it" in err and target.read_text() == "mine\n"
    assert cli(["bag", "import", str(rec), *segments, "-o", str(target), "--force"])[0] == 0
    assert len(parse_task_file(target).demonstrations) == len(examples.load("ikea-chair").demonstrations)
    assert cli(["bag", "import", str(rec), *segments])[0] == 0  # the bag still opens
