"""The board's authority rules (docs/service.md, "The board's rules"), one test per rule, and an invariant over
random boards and random operations: an assistant never owns, progresses or completes anything of a lead-only
subtask, whichever node it starts from."""

from __future__ import annotations

from dataclasses import replace

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import BoardError
from supportive.service.statuses import board_status
from supportive.social.board import TaskBoard
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, Node

# n0 chain "Chair"
#   n1 action get
#   n2 clique "Seat" (lead-only)
#     n3 action screw_a
#     n4 action screw_b
#   n5 action finish
CHAIR = ChainNode(
    (
        ActionNode("get"),
        CliqueNode((ActionNode("screw_a"), ActionNode("screw_b")), name="Seat"),
        ActionNode("finish"),
    ),
    name="Chair",
)


def chair() -> TaskBoard:
    return TaskBoard.from_node("chair", CHAIR, lead_only=["Seat"])


def refused(status: int, text: str, operation: object, *args: object) -> None:
    with pytest.raises(BoardError) as caught:
        operation(*args)  # type: ignore[operator]
    assert board_status(caught.value) == status and text in caught.value.message


def test_an_assistant_may_not_claim_a_lead_only_node() -> None:
    refused(403, "reserved for leads", chair().claim, "n2", "robot", "assistant")


def test_an_assistant_may_not_claim_a_node_containing_a_lead_only_node() -> None:
    refused(403, "reserved for leads", chair().claim, "n0", "robot", "assistant")


def test_an_assistant_may_not_claim_a_node_inside_a_lead_only_node() -> None:
    for leaf in ("n3", "n4"):
        refused(403, "part of 'Seat', reserved for leads", chair().claim, leaf, "robot", "assistant")


def test_an_assistant_may_not_complete_or_progress_inside_a_lead_only_node() -> None:
    """Even a leaf the assistant somehow owns (a board written by an older version) is refused."""
    board = chair().claim("n1", "robot", "assistant").complete("n1", "robot", "assistant")
    owned = TaskBoard(board.task, tuple(replace(n, owner="robot") if n.id == "n3" else n for n in board.nodes))
    refused(403, "reserved for leads", owned.complete, "n3", "robot", "assistant")
    refused(403, "reserved for leads", owned.report, "n3", "robot", "assistant", 0.5)


def test_an_assistant_may_do_what_is_outside_lead_only_nodes() -> None:
    board = chair().claim("n1", "robot", "assistant").report("n1", "robot", "assistant", 0.5)
    board = board.complete("n1", "robot", "assistant")
    assert board.node("n1").done and board.node("n1").owner == "robot"
    refused(409, "already done: there is nothing to give back", board.release, "n1", "robot", "assistant")
    assert board.claim("n5", "robot", "assistant").node("n5").owner == "robot"


def test_a_lead_may_claim_and_complete_lead_only_nodes_and_their_parents() -> None:
    board = chair().claim("n0", "alice", "lead")
    for leaf in ("n1", "n3", "n4", "n5"):
        board = board.complete(leaf, "alice", "lead")
    assert board.node("n2").done and board.node("n0").done


def test_observers_only_read() -> None:
    board = chair().claim("n1", "alice", "lead")
    refused(403, "observers may not claim", board.claim, "n5", "screen", "observer")
    refused(403, "observers may not release", board.release, "n1", "screen", "observer")
    refused(403, "observers may not complete", board.complete, "n1", "screen", "observer")
    refused(403, "observers may not report progress", board.report, "n1", "screen", "observer", 0.5)


def test_only_the_owner_releases_completes_or_progresses() -> None:
    board = chair().claim("n1", "alice", "lead")
    refused(409, "not claimed by bob", board.release, "n1", "bob", "lead")
    refused(409, "not claimed by bob", board.complete, "n1", "bob", "lead")
    refused(409, "not claimed by bob", board.report, "n1", "bob", "lead", 0.5)


def test_a_refusal_leaves_the_board_unchanged() -> None:
    board = chair()
    with pytest.raises(BoardError):
        board.claim("n3", "robot", "assistant")
    assert board == chair()


@st.composite
def hierarchies(draw: st.DrawFn, depth: int = 3) -> Node:
    counter = iter(range(10_000))

    def node(level: int) -> Node:
        if level == 0 or draw(st.booleans()):
            return ActionNode(f"a{next(counter)}")
        children = tuple(node(level - 1) for _ in range(draw(st.integers(2, 3))))
        name = f"s{next(counter)}"
        return ChainNode(children, name=name) if draw(st.booleans()) else CliqueNode(children, name=name)

    return node(depth)


@given(hierarchies(), st.data())
def test_no_sequence_of_operations_lets_an_assistant_into_a_lead_only_subtask(root: Node, data: st.DataObject) -> None:
    board = TaskBoard.from_node("t", root)
    names = [n.name for n in board.nodes]
    reserved = data.draw(st.lists(st.sampled_from(names), min_size=1, max_size=2, unique=True))
    board = TaskBoard.from_node("t", root, lead_only=reserved)
    locked = {n.id for n in board.nodes if n.lead_only}
    related = set()
    for ident in locked:
        related |= {n.id for n in board.subtree(ident)} | {n.id for n in board.ancestors(ident)}
    agents = [("alice", "lead"), ("robot", "assistant")]
    done_by_robot: set[str] = set()
    for _ in range(data.draw(st.integers(1, 30))):
        agent, role = data.draw(st.sampled_from(agents))
        op = data.draw(st.sampled_from(["claim", "release", "complete", "progress"]))
        ident = data.draw(st.sampled_from([n.id for n in board.nodes]))
        try:
            after = board.apply(op, ident, agent, role, 0.5)  # type: ignore[arg-type]
        except BoardError:
            continue
        if agent == "robot" and op == "complete":
            done_by_robot.add(ident)
        board = after
        assert not any(n.owner == "robot" and not n.done for n in board.nodes if n.id in related)
    under_locked = set().union(*({n.id for n in board.subtree(i)} for i in locked))
    assert not done_by_robot & under_locked
