"""Cross-check with the learner: from every ordering of a small generated structure, the CC-HTN learner must
recover that structure exactly (up to the equivalences of ``canonical``)."""

from __future__ import annotations

from hypothesis import assume, given
from hypothesis import strategies as st

from supportive.generate import Profile, random_structure
from supportive.learning import HTNLearner
from supportive.learning.learner import Mode
from supportive.tasks.htn import canonical, count_orderings, iter_orderings

PROFILES: tuple[Profile, ...] = ("ikea", "uniform")


@given(
    n=st.integers(1, 8),
    seed=st.integers(0, 2**32 - 1),
    profile=st.sampled_from(PROFILES),
)
def test_learning_from_all_orderings_recovers_the_structure(n: int, seed: int, profile: Profile) -> None:
    structure = random_structure(n, seed, profile=profile)
    assume(count_orderings(structure) <= 400)
    demonstrations = [[action for action, _ in ordering] for ordering in iter_orderings(structure)]
    # the general learner makes subtasks from four demonstrations on, or of a single one
    mode: Mode = "general" if len(demonstrations) >= 4 or len(demonstrations) == 1 else "strict"
    htn = HTNLearner(mode=mode).fit(demonstrations).htn_
    assert len(htn.roots) == 1, f"partial hierarchy for {structure!r}"
    assert canonical(htn.roots[0]) == canonical(structure), f"wrong hierarchy for {structure!r}"
