"""Slips as noise (learning/general/noise.py): nothing set aside on clean data, whatever its structure and size; the
mistakes put into generated demonstrations are found, each as the kind it was.

The clean-data properties draw their examples deterministically (``derandomize``): no detector can promise
that no sample of valid executions ever looks like one with a slip (a partial order's rare order may happen to
come up once in 25 where it is due six times), so the rate at which it happens on generated tasks is measured
by ``supportive reproduce learner-settings`` and, over fresh draws of these tests' own distributions, by
``benchmarks/bench_clean_slips.py`` (``make bench``), both quoted in docs/learning.md, and these tests pin that the
defaults keep clean data clean on a varied sample of tasks and sizes (the same sample in every run: see
``_without_local_constants`` in tests/conftest.py; before it, a run collecting fewer tests drew the clean sample
pinned below, where a step was set aside before slips had to be more than chance would show).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from supportive.generate import inject, random_known_task, random_partial_order, random_structure
from supportive.generate.mistakes import KnownTask
from supportive.generate.partial_orders import PartialOrderTask
from supportive.io.htn_json import htn_to_dict
from supportive.learning import HTNLearner
from supportive.tasks.htn import sample_ordering
from supportive.tasks.nodes import ActionNode, ChainNode, CliqueNode

CLEAN = settings(max_examples=20, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
KIND_OF_SLIP = {"moved": "out of order", "repeated": "repeated", "dropped": "missing"}


def _assert_clean(demos: list[list[str]]) -> None:
    learner = HTNLearner().fit(demos)
    assert learner.deviations_ == ()
    assert learner.noise_ is not None and all(rate == 0.0 for rate in learner.noise_.rates.values())
    assert all(learner.htn_.admits(demo) for demo in demos)


@CLEAN
@given(
    seed=st.integers(0, 10_000),
    size=st.integers(3, 10),
    profile=st.sampled_from(["ikea", "uniform"]),
    n=st.integers(1, 200),
)
def test_nested_structures_sampled_uniformly_have_no_slips(seed: int, size: int, profile: str, n: int) -> None:
    rng = np.random.default_rng(seed)
    structure = random_structure(size, rng, profile=profile)  # type: ignore[arg-type]
    _assert_clean([[a for a, _ in sample_ordering(structure, rng)] for _ in range(n)])


@CLEAN
@given(
    seed=st.integers(0, 10_000),
    size=st.integers(4, 9),
    chains=st.integers(2, 3),
    cross=st.integers(0, 3),
    n=st.integers(1, 200),
)
def test_partial_orders_sampled_uniformly_have_no_slips(seed: int, size: int, chains: int, cross: int, n: int) -> None:
    rng = np.random.default_rng(seed)
    task = random_partial_order(size, rng, chains=chains, cross=cross)
    _assert_clean([list(task.sample(rng)) for _ in range(n)])


def test_a_clean_sample_that_avoids_an_arrangement_by_chance_has_no_slips() -> None:
    # Two free chains (s1 alone, s2 → … → s9), 52 valid executions. Hypothesis drew this example (seed 5585, size
    # 9, 2 chains, no cross constraint, n 52) when only tests/learning and tests/inference were collected. s1
    # falls between s2 and s3 once in 52 executions where 5.8 are due (a chance of 1.7 %), and the hierarchy
    # learned from the other 51 keeps s2 -> s3 together: the likelihood comparison alone took s1 for a step out
    # of order. Among the 36 pairs of steps such a shortfall is no evidence (noise.py, `_by_chance`).
    rng = np.random.default_rng(5585)
    task = random_partial_order(9, rng, chains=2, cross=0)
    _assert_clean([list(task.sample(rng)) for _ in range(52)])


def test_slips_of_different_steps_are_each_more_than_chance() -> None:
    # Three demonstrations of twenty swap a different pair of neighbours each: whether one step's slips are more
    # than chance is judged on the demonstrations the other slips leave alone (with their step taken out,
    # the others fall outside any hierarchy, and counting them in found one of the three).
    clean = [list("abcdefgh")] * 8 + [list("acbdefgh")] * 8
    slipped = [list("abcdfegh"), list("abcdefhg"), list("bacdefgh"), list("abcedfgh")]
    found = {d.demonstration for d in HTNLearner().fit(clean + slipped).deviations_}
    assert {16, 17, 19} <= found <= {16, 17, 18, 19}


@pytest.mark.parametrize("n", [10, 20, 40, 80])
def test_two_interleaved_chains_the_issue_case(n: int) -> None:
    # a1 < a2 < a3 and b1 < b2 < b3 interleaved freely (20 orders): b3 before a1 comes once in twenty, which is
    # what the partial order predicts, not a slip; the old test against a fair coin called it one.
    task = random_partial_order(6, 0, chains=2)
    rng = np.random.default_rng(n)
    _assert_clean([list(task.sample(rng)) for _ in range(n)])


@pytest.mark.parametrize("kind", ["moved", "repeated", "dropped"])
def test_mistakes_put_in_are_found_as_their_kind(kind: str) -> None:
    # Six generated tasks (three profiles, two seeds), 60 demonstrations, one in twenty with a mistake: every
    # slip reported is one put in, of its kind, and most of those put in are found (the rates over many tasks
    # are measured by `supportive reproduce learner-settings`).
    put_in = found = 0
    for profile, seed in itertools.product(["ikea", "uniform", "partial order"], [3, 4]):
        task = random_known_task(profile, 8, seed=seed)  # type: ignore[arg-type]
        rng = np.random.default_rng(seed)
        demos, injected = inject([task.sample(rng) for _ in range(60)], kind, 0.05, task.admits, rng)  # type: ignore[arg-type]
        learner = HTNLearner().fit(demos)
        reported = {(d.demonstration, d.kind) for d in learner.deviations_}
        truth = {(i.demonstration, KIND_OF_SLIP[kind]) for i in injected}
        assert reported <= truth, f"{profile} {seed}: a slip reported where none was put in"
        put_in += len(truth)
        found += len(reported)
        cleaned = [d for i, d in enumerate(demos) if i not in {s.demonstration for s in learner.deviations_}]
        assert all(learner.htn_.admits(d) for d in cleaned)
    assert found >= 0.7 * put_in, (found, put_in)



def _put_right(task: KnownTask, slipped: list[str], seed: int, n: int = 50) -> tuple[set[int], set[int]]:
    """Learn ``n - len(slipped)`` valid executions of ``task`` followed by the ``slipped`` ones (each one step
    moved); return the demonstrations with a slip reported and those put right (a step out of order whose
    move back makes the demonstration valid)."""
    rng = np.random.default_rng(seed)
    demos = [task.sample(rng) for _ in range(n - len(slipped))] + [s.split() for s in slipped]
    assert not any(task.admits(d) for d in demos[n - len(slipped) :])
    learner = HTNLearner().fit(demos)
    right = set()
    for slip in learner.deviations_:
        demo = demos[slip.demonstration]
        rest = demo[: slip.position] + demo[slip.position + 1 :]
        if slip.kind == "out of order" and any(
            task.admits([*rest[:j], slip.leaf[0], *rest[j:]]) for j in range(len(rest) + 1)
        ):
            right.add(slip.demonstration)
    return {slip.demonstration for slip in learner.deviations_}, right


def test_subtasks_broken_by_steps_moved_in_several_demonstrations() -> None:
    # (1, {2, 3}, {4, 5}) in any order, then 6: five demonstrations each break a subtask with one step moved,
    # the same steps inside the same span in more than one of them; no single slip set aside tightens the
    # hierarchy, all of them together do.
    def pair(a: str, b: str) -> CliqueNode:
        return CliqueNode((ActionNode(a), ActionNode(b)))

    structure = ChainNode((CliqueNode((ActionNode("s1"), pair("s2", "s3"), pair("s4", "s5"))), ActionNode("s6")))
    slipped = ["s1 s5 s2 s3 s4 s6", "s1 s2 s5 s3 s4 s6", "s2 s3 s5 s1 s4 s6", "s5 s1 s4 s2 s3 s6", "s1 s2 s5 s4 s3 s6"]
    reported, right = _put_right(KnownTask("uniform", structure=structure), slipped, seed=93)
    assert reported == right == set(range(45, 50))


def test_an_order_several_demonstrations_reverse_by_slips() -> None:
    # s4 < s5 is reversed by three slipped demonstrations (s5 moved in one, s4 in two): only together do they
    # show the order, and the search must not stop at the slips that pay alone.
    chains = (("s1", "s2", "s3"), ("s4", "s5"), ("s6",))
    task = KnownTask("partial order", partial=PartialOrderTask(chains, (("s1", "s4"),)))
    slipped = ["s6 s1 s2 s5 s4 s3", "s1 s5 s2 s4 s3 s6", "s6 s4 s2 s1 s3 s5", "s1 s2 s6 s5 s3 s4", "s5 s1 s2 s4 s6 s3"]
    reported, right = _put_right(task, slipped, seed=75)
    assert reported == right == set(range(45, 50))


@pytest.mark.parametrize("seed", [5, 7])
def test_a_steps_real_slips_among_its_valid_variants_are_found_alone(seed: int) -> None:
    # Two chains of five and a free step, drawn uniformly: s7 comes after s2 in about a fifth of the valid
    # executions. Four demonstrations move s7 past s8. Started from the most telling step out of place in every
    # demonstration, the greedy search took s7 as a slip in those valid executions too and could not take them
    # back without the real four (on 19 of 56 seeds, 8 to 25 steps set aside); the search from no slip finds
    # the four alone, 70 nats more probable on the case learner-settings found (seed 1, trial 24).
    chains = (("s1", "s2", "s3", "s4", "s5"), ("s6",), ("s7", "s8", "s9", "s10", "s11"))
    task = KnownTask("partial order", partial=PartialOrderTask(chains))
    slipped = [
        "s6 s1 s8 s2 s3 s9 s4 s7 s10 s11 s5",
        "s8 s1 s6 s9 s2 s10 s3 s4 s5 s7 s11",
        "s1 s6 s8 s2 s9 s3 s10 s4 s5 s11 s7",
        "s1 s8 s9 s6 s10 s2 s3 s7 s11 s4 s5",
    ]
    reported, right = _put_right(task, slipped, seed=seed, n=100)
    assert reported == right == set(range(96, 100))


@pytest.mark.parametrize(
    ("odd", "expected"),
    [
        ("hbcdaefg", {("h", "out of order"), ("a", "out of order")}),  # two steps moved in one demonstration
        ("bcdeafg", {("h", "missing"), ("a", "out of order")}),  # one forgotten, one moved
    ],
)
def test_two_slips_in_one_demonstration_are_put_back_together(odd: str, expected: set[tuple[str, str]]) -> None:
    # put back one at a time, the first has no place while the second is still out: the pair scored -inf,
    # and the hierarchy was loosened to admit the odd demonstration instead
    learner = HTNLearner().fit([list("abcdefgh")] * 11 + [list(odd)])
    assert {(d.leaf[0], d.kind) for d in learner.deviations_} == expected
    assert all(d.demonstration == 11 for d in learner.deviations_)
    assert learner.htn_.count_orderings() == 1


def test_slips_that_no_demonstration_can_judge_are_taken_back() -> None:
    # every demonstration has two slips: judging one step's, the other slips leave no demonstration to tell
    # them from chance, so they do not stand (this raised an error before)
    from supportive.learning.general.labelling import label_performances
    from supportive.learning.general.noise import Deviation, NoiseSettings, _Search
    from supportive.learning.general.structure import StructureSettings

    demos = [list("badc")] * 3 + [list("acdb")] * 3
    labelled = label_performances(demos)
    search = _Search(labelled, StructureSettings(0.05, None, 2), NoiseSettings(0.0, 0.1, 300.0, 12, 1.0), True)
    slips = frozenset(
        Deviation(d, position, (step, 1), "out of order")
        for demonstrations, moved in ((range(3), ((1, "a"), (3, "c"))), (range(3, 6), ((3, "b"), (2, "d"))))
        for d in demonstrations
        for position, step in moved
    )
    assert search._by_chance(slips) < slips


def _learned(learner: HTNLearner) -> tuple[object, ...]:
    """What a general fit learned: the hierarchy, the slips, the noise model and how many explanations its
    search scored."""
    assert learner.noise_ is not None
    return (htn_to_dict(learner.htn_), learner.deviations_, learner.noise_.as_dict(), learner.noise_.evaluations)


@pytest.mark.parametrize(("profile", "kind"), [("ikea", "moved"), ("uniform", "repeated"), ("partial order", "dropped")])
def test_a_slip_cache_shared_by_a_sweep_changes_no_fit(profile: str, kind: str) -> None:
    # a sweep over the slip settings with one cache learns exactly what each setting learns alone, on two sets of
    # demonstrations (kept apart in the cache)
    from supportive.learning.general import SlipSearchCache

    cache = SlipSearchCache()
    grid = [
        {"slip_margin": margin, "slip_rate_weight": weight, "order_concentration": concentration}
        for margin, weight, concentration in itertools.product((0.0, 1.0), (100.0, 1000.0), (0.25, math.inf))
    ]
    for seed in (1, 2):
        task = random_known_task(profile, 7, seed=seed)  # type: ignore[arg-type]
        rng = np.random.default_rng(seed)
        demos, injected = inject([task.sample(rng) for _ in range(30)], kind, 0.1, task.admits, rng)  # type: ignore[arg-type]
        assert injected
        for setting in grid:
            alone = HTNLearner(mode="general", **setting).fit(demos)  # type: ignore[arg-type]
            shared = HTNLearner(mode="general", slip_cache=cache, **setting).fit(demos)  # type: ignore[arg-type]
            assert _learned(shared) == _learned(alone), (seed, setting)
    assert len(cache) == 2


def test_a_slip_cache_learns_each_hierarchy_once(monkeypatch: pytest.MonkeyPatch) -> None:
    # the second fit of the same demonstrations with a shared cache learns no hierarchy in its slip search
    from supportive.learning.general import SlipSearchCache, noise
    from supportive.learning.general.structure import fit_structure as learn

    task = random_known_task("uniform", 7, seed=3)
    rng = np.random.default_rng(3)
    demos, _ = inject([task.sample(rng) for _ in range(30)], "moved", 0.1, task.admits, rng)
    fits = 0

    def counted(*args: object, **kwargs: object) -> object:
        nonlocal fits
        fits += 1
        return learn(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(noise, "fit_structure", counted)
    cache = SlipSearchCache()
    first = HTNLearner(mode="general", slip_cache=cache).fit(demos)
    assert fits > 0
    learned, fits = fits, 0
    again = HTNLearner(mode="general", slip_margin=1.0, slip_cache=cache).fit(demos)
    assert fits == 0 and learned > 0
    assert again.noise_ is not None and first.noise_ is not None and again.noise_.evaluations > 0


def test_a_slip_cache_must_be_one() -> None:
    from supportive.errors import LearningError

    with pytest.raises(LearningError, match="slip_cache must be a SlipSearchCache or None, got dict"):
        HTNLearner(slip_cache={})  # type: ignore[arg-type]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(st.permutations("abcde"), st.integers(3, 5)).map(lambda t: t[0][: t[1]]), min_size=2, max_size=8))
def test_transition_surprisal_matches_counting_by_hand(orders: list[list[str]]) -> None:
    """The candidate search's transition surprisal (vectorised) against counting each demonstration's
    transitions among the others', add-one smoothed over what may follow a step (a step or the end)."""
    from supportive.learning.general.noise import _Steps, _transition_surprisal

    demos = [[(a, 1) for a in order] for order in orders]
    outcomes = len({leaf for demo in demos for leaf in demo}) + 1
    padded = [["<start>", *demo, "<end>"] for demo in demos]
    expected = []
    for d, demo in enumerate(padded):
        others = [o for e, o in enumerate(padded) if e != d]
        pairs = [(x, y) for o in others for x, y in itertools.pairwise(o)]
        surprisal = [
            -math.log((sum(p == (x, y) for p in pairs) + 1) / (sum(p[0] == x for p in pairs) + outcomes))
            for x, y in itertools.pairwise(demo)
        ]
        expected.append(sum(surprisal) / len(surprisal))
    assert _transition_surprisal(_Steps.of(demos)) == pytest.approx(expected)


def test_a_clean_sample_whose_free_steps_look_like_a_subtask_by_chance_has_no_slips() -> None:
    # Drawn by a clean-data check outside the suite (seed 85 of 600): 22 steps, 9 uniform demonstrations of a
    # known task; steps 8, 9, 10 are free, 9 came before 10 in all nine and right before it in eight.
    rng = np.random.default_rng(85)
    rng.integers(3, 31), rng.integers(1, 201)  # the check drew the size and the number of demonstrations first
    task = random_known_task("uniform", 22, rng)
    _assert_clean([task.sample(rng) for _ in range(9)])


@pytest.mark.parametrize("order_penalty", [None, 1.0])
def test_a_repeat_done_after_its_successor_is_one_repeated_step(order_penalty: float | None) -> None:
    """The generalisation experiment's slip check, task 641 (a 21-step partial order, 50 demonstrations by
    people drawing uniformly, five with a step done twice): in demonstrations 10 and 23 ``s20`` is done in its
    place and again after ``s21``. Without the exchange pass the search took the earlier performance for the
    repeat and then the later for a step out of order (with the top level's orders weighed), or called the
    later one out of order (with the coin test) — 12.5 and 7.7 nats less probable than the later one repeated,
    which needs one slip out and another in at once."""
    from supportive.experiments.generalisation.measure import DEFAULT_TRIALS, make_trials
    from supportive.experiments.learner_settings.measure import trial_demonstrations

    demos, truth, _ = trial_demonstrations(make_trials(DEFAULT_TRIALS, 0)[641])
    found = HTNLearner(order_penalty=order_penalty).fit(demos).deviations_
    for d in (10, 23):
        assert d in truth
        (slip,) = [s for s in found if s.demonstration == d]
        later = max(i for i, step in enumerate(demos[d]) if step == "s20")
        assert (slip.kind, slip.leaf[0], slip.position) == ("repeated", "s20", later)
