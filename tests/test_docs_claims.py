"""Two behaviours the docs state, which they once stated wrongly (issue #26).

docs/inference.md: an action done as often as the task has it gets no on-script probability, only its share of
the off-script one. docs/learning.md: the hierarchy may refuse a demonstration with a step set aside as a slip.
"""

from __future__ import annotations

import pytest

from supportive.inference import ProgressHMM
from supportive.learning import HTNLearner


def test_a_finished_action_keeps_only_its_share_of_the_slip_probability() -> None:
    htn = HTNLearner(mode="strict").fit([["a", "b", "c"], ["b", "a", "c"]]).htn_
    slip = 0.02
    running = ProgressHMM(htn, slip=slip).fit().filter()
    running.observe("a")
    belief = running.observe("b")
    nxt = belief.next_actions
    assert nxt["c"] > 0.9
    for done in ("a", "b"):  # each done once, as often as the task has it: slip / (actions + 1), nothing more
        assert nxt[done] == pytest.approx(slip / (3 + 1))


def test_the_hierarchy_may_refuse_a_demonstration_with_a_step_set_aside_as_a_slip() -> None:
    # d before c once in 21 (with 6 of each, once in 13 could be chance: no slip)
    demos = [["a", "b", "c", "d", "e"]] * 10 + [["a", "b", "d", "c", "e"]] + [["a", "c", "b", "d", "e"]] * 10
    learner = HTNLearner().fit(demos)
    slipped = {d.demonstration for d in learner.deviations_}
    assert slipped == {10}
    assert not learner.htn_.admits(demos[10])
    assert all(learner.htn_.admits(d) for i, d in enumerate(demos) if i not in slipped)
