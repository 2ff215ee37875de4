"""The task model's mistake labels: labelled steps, skipped steps kept apart from the performed ones."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import TaskModelError
from supportive.tasks.spec import MISTAKE_LABELS, Demonstration, Step, TaskSpec, mistake_label

LABELS = st.sampled_from(MISTAKE_LABELS)


@st.composite
def entries(draw: st.DrawFn) -> list[Step]:
    """Steps as a file lists them: performed steps (some labelled) and placeholders, at least one performed."""
    out: list[Step] = []
    for _ in range(draw(st.integers(1, 8))):
        action = draw(st.sampled_from("abcde"))
        label = draw(st.none() | LABELS)
        out.append(Step(action, mistake=label) if label == "missing" else Step(action, float(len(out)), None, None, label))
    if all(step.placeholder for step in out):
        out.append(Step("a"))
    return out


@given(entries())
def test_entries_and_from_entries_are_inverse(listed: list[Step]) -> None:
    demo = Demonstration.from_entries(listed, "d1")
    assert demo.entries == tuple(listed)
    assert Demonstration.from_entries(demo.entries, "d1") == demo
    assert demo.actions == tuple(s.action for s in listed if not s.placeholder)
    assert [a for _, a in demo.skipped] == [s.action for s in listed if s.placeholder]
    assert demo.labelled == any(s.mistake is not None for s in listed)
    before = [sum(not s.placeholder for s in listed[:i]) for i, s in enumerate(listed) if s.placeholder]
    assert [p for p, _ in demo.skipped] == before


def test_skipped_steps_are_not_performed() -> None:
    demo = Demonstration((Step("a"), Step("c", mistake="order")), "d1", skipped=((1, "b"), (2, "d")))
    assert demo.actions == ("a", "c") and demo.labelled
    assert [s.action for s in demo.entries] == ["a", "b", "c", "d"]
    spec = TaskSpec("t", demonstrations=(demo,))
    assert list(spec.action_sequences()) == [("a", "c")]
    assert spec.action_ids() == ("a", "c")  # what is learned from: the performed steps only
    assert not Demonstration.of(["a", "b"]).labelled


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: Step("a", mistake="oder"), "unknown mistake label 'oder'; expected one of order, missing"),
        (lambda: Step("a", 1.0, 2.0, mistake="missing"), "labelled missing, so it was not performed"),
        (lambda: Demonstration((Step("a", mistake="missing"),), "d1"), "give it in 'skipped'"),
        (lambda: Demonstration((Step("a"),), "d1", skipped=((2, "b"),)), "position 2; expected 0 to 1"),
        (lambda: Demonstration((Step("a"),), "d1", skipped=((1, "b"), (0, "c"))), "position 0; expected 1 to 1"),
    ],
)
def test_the_model_refuses_what_it_cannot_hold(make: Callable[[], object], message: str) -> None:
    with pytest.raises(TaskModelError, match=message):
        make()


def test_labels_as_files_give_them() -> None:
    assert [mistake_label(v) for v in (True, False, None, "order", "true")] == ["true", None, None, "order", "true"]
    for bad in ("Order", "", 1, 0.5, ["order"]):
        with pytest.raises(TaskModelError, match="or true when the kind is not known"):
            mistake_label(bad)
