"""ROS bags through rosbags (no ROS installation): demonstrations and contact frames written in every format
and read back, user message definitions, and every failure as one BagError naming the bag and the topic."""

from __future__ import annotations

import sqlite3
from collections.abc import Callable
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.errors import BagError
from supportive.io.rosbag import (
    SEGMENT_TOPIC,
    STORAGES,
    BagWriter,
    Storage,
    import_demonstrations,
    load_definitions,
    open_bag,
    read_contact_frames,
    read_demonstrations,
    typestore,
    write_contact_frames,
    write_demonstrations,
)
from supportive.io.rosbag.writing import LATCHED
from supportive.tasks.spec import Demonstration, Step

T0 = 1_700_000_000 * 1_000_000_000


def bag_path(directory: Path, storage: Storage, name: str = "rec") -> Path:
    return directory / (f"{name}.bag" if storage == "rosbag1" else name)


def write(directory: Path, storage: Storage, fill: Callable[[BagWriter], object], name: str = "rec") -> Path:
    path = bag_path(directory, storage, name)
    with BagWriter(path, storage) as writer:
        fill(writer)
    return path


@st.composite
def demonstrations(draw: st.DrawFn) -> list[Demonstration]:
    """Demonstrations with distinct ids, optional agents, strictly increasing starts (ms) and optional ends."""
    count = draw(st.integers(1, 3))
    ids = draw(
        st.lists(
            st.from_regex(r"[a-z][a-z0-9_-]{0,8}", fullmatch=True),
            min_size=count,
            max_size=count,
            unique=True,
        )
    )
    demos = []
    for demo_id in ids:
        agent = draw(st.one_of(st.none(), st.sampled_from(["alice", "bob", "robot"])))
        actions = draw(st.lists(st.sampled_from(["get", "place", "screw", "peg"]), min_size=1, max_size=6))
        steps, start = [], draw(st.integers(0, 5000))
        for action in actions:
            start += draw(st.integers(1, 3000))
            length = draw(st.one_of(st.none(), st.integers(0, 2000)))
            steps.append(Step(action, start / 1000, None if length is None else (start + length) / 1000))
        demos.append(Demonstration(tuple(steps), demo_id, agent))
    return demos


@pytest.mark.parametrize("storage", STORAGES)
@settings(max_examples=15)
@given(demos=demonstrations())
def test_demonstrations_survive_a_bag_in_every_format(
    tmp_path_factory: pytest.TempPathFactory, storage: Storage, demos: list[Demonstration]
) -> None:
    path = write(tmp_path_factory.mktemp("bags"), storage, lambda w: write_demonstrations(w, demos, start=T0))
    assert list(import_demonstrations([path], segment_topic=SEGMENT_TOPIC)) == demos


def test_untimed_steps_come_a_second_apart_as_strings(tmp_path: Path) -> None:
    demo = Demonstration((Step("a"), Step("b"), Step("c")), "d1", None)
    path = write(tmp_path, "mcap", lambda w: write_demonstrations(w, [demo], start=T0))
    with open_bag(path) as bag:
        assert {c.topic: c.msgtype for c in bag.reader.connections}["/task/action"] == "std_msgs/msg/String"
    (read,) = read_demonstrations(path, segment_topic=SEGMENT_TOPIC)
    assert [(s.action, s.start, s.end) for s in read.steps] == [
        ("a", 0.0, None),
        ("b", 1.0, None),
        ("c", 2.0, None),
    ]


def test_a_bag_without_segments_is_one_demonstration_timed_from_its_first_message(tmp_path: Path) -> None:
    def fill(w: BagWriter) -> None:
        clock = w.topic("/clock_marker", "std_msgs/msg/Empty")
        w.write(clock, T0, w.message("std_msgs/msg/Empty"))
        actions = w.topic("/task/action", "std_msgs/msg/String")
        for k, action in enumerate(["x", "y"]):
            w.write(
                actions, T0 + (k + 1) * 1_500_000_000, w.message("std_msgs/msg/String", data=f" {action}\n")
            )

    path = write(tmp_path, "sqlite3", fill, name="session-7")
    (demo,) = read_demonstrations(path, agent="carol")
    assert demo == Demonstration((Step("x", 1.5), Step("y", 3.0)), "session-7", "carol")


def test_segment_markers_of_every_documented_kind(tmp_path: Path) -> None:
    def fill(w: BagWriter) -> None:
        named = w.topic("/seg", "std_msgs/msg/String")
        actions = w.topic("/task/action", "std_msgs/msg/String")
        w.write(named, T0, w.message("std_msgs/msg/String", data="first"))
        w.write(actions, T0 + 10**9, w.message("std_msgs/msg/String", data="a"))
        w.write(named, T0 + 5 * 10**9, w.message("std_msgs/msg/String", data=""))
        w.write(actions, T0 + 7 * 10**9, w.message("std_msgs/msg/String", data="b"))

    path = write(tmp_path, "mcap", fill)
    demos = read_demonstrations(path, segment_topic="/seg", agent="dana")
    assert demos == [
        Demonstration((Step("a", 1.0),), "first", "dana"),
        Demonstration((Step("b", 2.0),), "rec-2", "dana"),
    ]


def test_span_messages_of_a_users_own_type_from_a_msg_file_or_folder(tmp_path: Path) -> None:
    package = tmp_path / "defs" / "lab_msgs" / "msg"
    package.mkdir(parents=True)
    (package / "Step.msg").write_text(
        "# a lab's own step message\nfloat64 start\nfloat64 end\nstring action\nstring note\n"
    )
    path = bag_path(tmp_path, "sqlite3")
    with BagWriter(path, "sqlite3", definitions=[package / "Step.msg"]) as w:
        topic = w.topic("/lab/steps", "lab_msgs/msg/Step")
        for k, action in enumerate(["a", "b"]):
            start = (T0 + k * 10**9) / 1e9
            w.write(
                topic,
                T0 + k * 10**9 + 10**8,
                w.message("lab_msgs/msg/Step", start=start, end=start + 0.5, action=action, note=""),
            )
    # Like a Humble SQLite3 bag: no message definitions inside.
    database = next(path.glob("*.db3"))
    with sqlite3.connect(database) as connection:
        connection.execute("DELETE FROM message_definitions")
    with pytest.raises(
        BagError, match=r"rec: topic /lab/steps: message type lab_msgs/msg/Step is defined neither"
    ):
        read_demonstrations(path, actions_topic="/lab/steps")
    for definitions in ([package / "Step.msg"], [tmp_path / "defs"]):
        (demo,) = read_demonstrations(path, actions_topic="/lab/steps", definitions=definitions)
        assert [(s.action, s.start, s.end) for s in demo.steps] == [("a", 0.0, 0.5), ("b", 1.0, 1.5)]


def test_message_definitions_that_cannot_be_used(tmp_path: Path) -> None:
    loose = tmp_path / "Step.msg"
    loose.write_text("string action\n")
    with pytest.raises(BagError, match=r"Step.msg: a .msg file must sit in a <package>/msg/ folder"):
        load_definitions(loose)
    broken = tmp_path / "p" / "msg" / "Bad.msg"
    broken.parent.mkdir(parents=True)
    broken.write_text("int32[ x\n")
    with pytest.raises(BagError, match=r"Bad.msg: invalid message definition: Could not parse$"):
        load_definitions(broken)
    broken.write_text("string action\nother_msgs/Missing part\n")
    with pytest.raises(BagError, match=r"message definitions do not fit together"):
        typestore(2, [broken])
    with pytest.raises(BagError, match=r"no .msg or .idl"):
        load_definitions(_empty(tmp_path))
    with pytest.raises(BagError, match=r"nowhere: no such message definition"):
        load_definitions(tmp_path / "nowhere")


def _empty(tmp_path: Path) -> Path:
    folder = tmp_path / "empty"
    folder.mkdir()
    return folder


@pytest.mark.parametrize("storage", STORAGES)
@pytest.mark.parametrize("typed", [True, False])
def test_contact_frames_in_every_format(tmp_path: Path, storage: Storage, typed: bool) -> None:
    frames = [
        (frozenset({"hand-peg", "peg-frame"}), T0),
        (frozenset(), T0 + 10**8),
        (frozenset({"hand-seat"}), T0 + 2 * 10**8),
    ]
    path = write(tmp_path, storage, lambda w: write_contact_frames(w, frames, typed=typed))
    assert list(read_contact_frames(path)) == frames


def test_a_string_frame_may_separate_events_by_commas_or_spaces(tmp_path: Path) -> None:
    def fill(w: BagWriter) -> None:
        topic = w.topic("/contacts", "std_msgs/msg/String")
        w.write(topic, T0, w.message("std_msgs/msg/String", data=" hand-peg,peg-frame  hand-seat ,"))

    assert list(read_contact_frames(write(tmp_path, "mcap", fill))) == [
        (frozenset({"hand-peg", "peg-frame", "hand-seat"}), T0)
    ]


def test_latched_topics_are_transient_local(tmp_path: Path) -> None:
    def fill(w: BagWriter) -> None:
        w.write(
            w.topic("/latched", "std_msgs/msg/String", latched=True),
            T0,
            w.message("std_msgs/msg/String", data="x"),
        )

    with open_bag(write(tmp_path, "mcap", fill)) as bag:
        (connection,) = bag.reader.connections
        assert connection.ext.offered_qos_profiles == [LATCHED]  # type: ignore[union-attr]
    with open_bag(write(tmp_path, "rosbag1", fill)) as bag:
        (connection,) = bag.reader.connections
        assert connection.ext.latching == 1  # type: ignore[union-attr]


# ------------------------------------------------------------------------------------------- failures
def _actions(*items: tuple[int, str]) -> Callable[[BagWriter], None]:
    def fill(w: BagWriter) -> None:
        topic = w.topic("/task/action", "std_msgs/msg/String")
        for time, action in items:
            w.write(topic, time, w.message("std_msgs/msg/String", data=action))

    return fill


def test_each_problem_names_the_bag_and_the_topic(tmp_path: Path) -> None:
    good = write(tmp_path, "mcap", _actions((T0, "a"), (T0 + 10**9, "b")), name="good")
    with pytest.raises(BagError, match=r"good: no topic /other in the bag \(it has: /task/action\)"):
        read_demonstrations(good, actions_topic="/other")
    with pytest.raises(
        BagError, match=r"good: topic /task/action: action 'b' at 1.000 s is not one of the task's actions"
    ):
        read_demonstrations(good, vocabulary={"a"})
    empty = write(tmp_path, "mcap", lambda w: w.topic("/task/action", "std_msgs/msg/String"), name="empty")
    with pytest.raises(BagError, match=r"empty: topic /task/action: the topic has no messages"):
        read_demonstrations(empty)
    blank = write(tmp_path, "rosbag1", _actions((T0, "  ")), name="blank")
    with pytest.raises(BagError, match=r"blank.bag: topic /task/action: an empty action id at 0.000 s"):
        read_demonstrations(blank)

    def wrong(w: BagWriter) -> None:
        w.write(
            w.topic("/task/action", "std_msgs/msg/Float64"), T0, w.message("std_msgs/msg/Float64", data=1.0)
        )

    with pytest.raises(
        BagError, match=r"wrong: topic /task/action: messages of type std_msgs/msg/Float64; expected"
    ):
        read_demonstrations(write(tmp_path, "sqlite3", wrong, name="wrong"))
    with pytest.raises(
        BagError, match=r"wrong: topic /task/action: messages of type std_msgs/msg/Float64; expected"
    ):
        list(read_contact_frames(tmp_path / "wrong", "/task/action"))

    def backwards(w: BagWriter) -> None:
        topic = w.topic("/task/action", "supportive_msgs/msg/ActionSpan")
        w.write(
            topic,
            T0,
            w.message(
                "supportive_msgs/msg/ActionSpan", action="a", start=w.stamp(T0 + 10**9), end=w.stamp(T0)
            ),
        )

    with pytest.raises(
        BagError, match=r"backwards: topic /task/action: action 'a' at 0.000 s ends before it starts"
    ):
        read_demonstrations(write(tmp_path, "mcap", backwards, name="backwards"))


def test_segment_problems(tmp_path: Path) -> None:
    def early(w: BagWriter) -> None:
        _actions((T0, "a"), (T0 + 3 * 10**9, "b"))(w)
        w.write(w.topic("/seg", "std_msgs/msg/Empty"), T0 + 10**9, w.message("std_msgs/msg/Empty"))

    with pytest.raises(
        BagError,
        match=r"early: topic /task/action: action 'a' at 0.000 s comes before the first demonstration marker on /seg",
    ):
        read_demonstrations(write(tmp_path, "mcap", early, name="early"), segment_topic="/seg")

    def hollow(w: BagWriter) -> None:
        seg = w.topic("/seg", "std_msgs/msg/String")
        w.write(seg, T0, w.message("std_msgs/msg/String", data="one"))
        _actions((T0 + 10**9, "a"))(w)
        w.write(seg, T0 + 2 * 10**9, w.message("std_msgs/msg/String", data="two"))

    with pytest.raises(
        BagError, match=r"hollow: topic /seg: demonstration 'two' \(marker at 2.000 s\) has no actions"
    ):
        read_demonstrations(write(tmp_path, "mcap", hollow, name="hollow"), segment_topic="/seg")

    def odd(w: BagWriter) -> None:
        _actions((T0, "a"))(w)
        w.write(w.topic("/seg", "std_msgs/msg/Float64"), T0, w.message("std_msgs/msg/Float64", data=0.0))

    with pytest.raises(
        BagError,
        match=r"odd: topic /seg: messages of type std_msgs/msg/Float64; expected std_msgs/msg/String",
    ):
        read_demonstrations(write(tmp_path, "mcap", odd, name="odd"), segment_topic="/seg")


def test_two_bags_may_not_give_the_same_demonstration_id(tmp_path: Path) -> None:
    one = write(tmp_path / "a", "mcap", _actions((T0, "x")), name="rec")
    two = write(tmp_path / "b", "mcap", _actions((T0, "y")), name="rec")
    with pytest.raises(BagError, match=r"demonstration id 'rec' is also in .*a/rec"):
        import_demonstrations([one, two])


@pytest.mark.parametrize("storage", STORAGES)
def test_truncated_and_corrupt_bags(tmp_path: Path, storage: Storage) -> None:
    path = write(tmp_path, storage, _actions(*((T0 + k * 10**7, f"a{k}") for k in range(2000))))
    data = path if storage == "rosbag1" else next(p for p in path.iterdir() if p.suffix in (".mcap", ".db3"))
    content = data.read_bytes()
    data.write_bytes(content[: len(content) // 2])
    with pytest.raises(BagError, match=rf"{path.name}: cannot (open|read) the bag: "):
        read_demonstrations(path)
    data.write_bytes(b"\x00garbage" * 100)
    with pytest.raises(BagError, match=rf"{path.name}: cannot (open|read) the bag: "):
        read_demonstrations(path)


def test_paths_that_are_not_bags(tmp_path: Path) -> None:
    with pytest.raises(BagError, match=r"missing: no such bag"):
        read_demonstrations(tmp_path / "missing")
    (tmp_path / "notes.txt").write_text("hi")
    with pytest.raises(BagError, match=r"notes.txt: not a ROS bag"):
        read_demonstrations(tmp_path / "notes.txt")
    with pytest.raises(BagError, match=r"not a ROS bag"):
        read_demonstrations(tmp_path)


def test_naming_the_mcap_file_means_its_bag(tmp_path: Path) -> None:
    path = write(tmp_path, "mcap", _actions((T0, "a")))
    (demo,) = read_demonstrations(path / "rec.mcap")
    assert demo.id == "rec" and demo.steps == (Step("a", 0.0),)


def test_the_writer_never_overwrites_and_leaves_nothing_when_it_fails(tmp_path: Path) -> None:
    path = write(tmp_path, "mcap", _actions((T0, "a")))
    with pytest.raises(BagError, match=r"rec: exists already; a bag is never overwritten"):
        BagWriter(path, "mcap")
    with pytest.raises(BagError, match=r"rosbag1 bags are written as a .bag file"):
        BagWriter(tmp_path / "x", "rosbag1")
    with pytest.raises(BagError, match=r"mcap bags are written as a directory name"):
        BagWriter(tmp_path / "x.bag", "mcap")
    target = tmp_path / "half"
    with pytest.raises(RuntimeError), BagWriter(target, "sqlite3") as writer:
        _actions((T0, "a"))(writer)
        raise RuntimeError("the recording stopped")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rec"]
