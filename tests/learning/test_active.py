"""Active learning (§2.2.5–2.2.7): query strategies over the CTG, anti-edges, schedules, teaching sessions."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pytest

from supportive.errors import LearningError
from supportive.learning import HTNLearner
from supportive.learning.active import (
    AntiEdges,
    ConnectivityQuery,
    DistanceQuery,
    QueryContext,
    QueryRecord,
    QuerySchedule,
    RandomQuery,
    TeachingSession,
    connectivity_base,
    connectivity_scores,
    ctg_distances,
    run_session,
    state_key,
    strategy,
    strategy_names,
)
from supportive.tasks.conjugate import ORIGIN, TERMINAL

KCC = ("knife", "carrots", "celery")


def context(
    demos: Sequence[Sequence[str]],
    done: Sequence[str],
    actions: Sequence[str],
    anti: AntiEdges | None = None,
    seed: int = 0,
) -> QueryContext:
    learner = HTNLearner().fit([list(d) for d in demos]) if demos else None
    return QueryContext(
        learner.task_graph_ if learner else None,
        learner.ctg_ if learner else None,
        tuple(done),
        tuple(actions),
        anti if anti is not None else AntiEdges(),
        np.random.default_rng(seed),
    )


def vertex(learner: HTNLearner, action: str, occurrence: int = 1) -> int:
    index = learner.task_graph_.subgoal_index((action, occurrence))
    assert index is not None
    return index


# ---------------------------------------------------------------- scripted instructors


class Scripted:
    """Performs the given sequences in turn (cycling) and ignores every query."""

    def __init__(self, *sequences: Sequence[str]) -> None:
        self.sequences = [tuple(s) for s in sequences]
        self.count = -1
        self.seen: list[str | None] = []

    def begin_demonstration(self) -> None:
        self.count += 1

    def next_action(self, done: tuple[str, ...], query: str | None) -> str | None:
        self.seen.append(query)
        sequence = self.sequences[self.count % len(self.sequences)]
        return sequence[len(done)] if len(done) < len(sequence) else None


class Obliging:
    """Follows a partial order (action -> actions it needs first); honours a query when it is valid now,
    otherwise takes a seeded random valid step."""

    def __init__(self, needs: dict[str, set[str]], seed: int) -> None:
        self.needs = needs
        self.rng = np.random.default_rng(seed)

    def begin_demonstration(self) -> None:
        pass

    def next_action(self, done: tuple[str, ...], query: str | None) -> str | None:
        ready = [a for a in self.needs if a not in done and self.needs[a] <= set(done)]
        if not ready:
            return None
        if query in ready:
            return query
        return ready[int(self.rng.integers(len(ready)))]


# Task 2 of the pilot study (§2.2.7.1): the V, a chain of cliques, rows {red}, {yellow, blue, purple},
# {green, black}, {white, orange}.
V_NEEDS = {
    "red": set(),
    "yellow": {"red"},
    "blue": {"red"},
    "purple": {"red"},
    "green": {"yellow", "blue", "purple"},
    "black": {"yellow", "blue", "purple"},
    "white": {"green", "black"},
    "orange": {"green", "black"},
}


# ---------------------------------------------------------------- CTG features, by hand


def test_knife_carrots_celery_features() -> None:
    # One demonstration knife, carrots, celery. CTG (Fig. 2.8 with a single ordering):
    #   origin -∅-> knife -{knife}-> carrots -{knife,carrots}-> celery -{knife,carrots,celery}-> terminal
    # base = 3 (prerequisites into terminal). Scores: knife 3 (in) + 1.5 (out) = 4.5;
    # carrots (3-1) + 1.5 = 3.5; celery (3-2) + 1.5 = 2.5.
    learner = HTNLearner().fit([list(KCC)])
    ctg = learner.ctg_
    knife, carrots, celery = (vertex(learner, a) for a in KCC)
    assert connectivity_base(ctg) == 3
    scores = connectivity_scores(ctg)
    assert (scores[knife], scores[carrots], scores[celery]) == (4.5, 3.5, 2.5)
    assert ctg_distances(ctg, ORIGIN) == {ORIGIN: 0, knife: 1, carrots: 2, celery: 3, TERMINAL: 4}
    assert ctg_distances(ctg, celery) == {celery: 0, TERMINAL: 1}


def test_knife_carrots_celery_choices() -> None:
    # Start of demonstration 2: knife is a known transition from the origin state, so the candidates are
    # carrots (distance 2, score 3.5) and celery (distance 3, score 2.5): both informed strategies ask carrots.
    ctx = context([KCC], (), KCC)
    assert ctx.candidates() == ("carrots", "celery")
    assert DistanceQuery().choose(ctx) == "carrots"
    assert ConnectivityQuery().choose(ctx) == "carrots"
    # After knife: carrots is known from {knife}, knife was executed; only celery is left.
    ctx = context([KCC], ("knife",), KCC)
    assert ctx.candidates() == ("celery",)
    for name in strategy_names():
        assert strategy(name).choose(ctx) == "celery"


def test_distance_and_connectivity_disagree() -> None:
    # Demonstrations a b c d and b a c d. CTG edges (prerequisites):
    #   origin->a ∅, origin->b ∅, a->b {a}, b->a {b}, a->c {a,b}, b->c {a,b}, c->d {a,b,c}, d->terminal {a,b,c,d}
    # base 4. Scores: a = 4 + (4-1) + 2 + 2 = 11, b = 11, c = 2 + 2 + 2 = 6, d = (4-3) + 2 = 3.
    demos = [("a", "b", "c", "d"), ("b", "a", "c", "d")]
    learner = HTNLearner().fit([list(d) for d in demos])
    scores = connectivity_scores(learner.ctg_)
    assert [scores[vertex(learner, x)] for x in "abcd"] == [11, 11, 6, 3]
    # A new demonstration starting with c (a state the graph does not know): candidates a, b, d.
    # Distance from c: d is 1 away, a and b are unreachable -> d. Connectivity: a and b tie at 11.
    ctx = context(demos, ("c",), "abcd")
    assert ctx.candidates() == ("a", "b", "d")
    assert DistanceQuery().choose(ctx) == "d"
    picks = {ConnectivityQuery().choose(context(demos, ("c",), "abcd", seed=s)) for s in range(20)}
    assert picks == {"a", "b"}
    # At the start: a and b are known from the origin; c is 2 away (origin->a->c), d 3 -> c by both.
    ctx = context(demos, (), "abcd")
    assert ctx.candidates() == ("c", "d")
    assert DistanceQuery().choose(ctx) == ConnectivityQuery().choose(ctx) == "c"


def test_unknown_actions_rank_last() -> None:
    # "e" was never demonstrated: no vertex, so unreachable (distance) and score 0 (connectivity).
    ctx = context([("a", "b", "c")], (), "abce")
    assert ctx.candidates() == ("b", "c", "e")
    assert DistanceQuery().choose(ctx) == "b"
    assert ConnectivityQuery().choose(ctx) == "b"
    ctx = context([("a", "b", "c")], ("a", "b", "c"), "abce")
    assert ctx.candidates() == ("e",)
    assert DistanceQuery().choose(ctx) == ConnectivityQuery().choose(ctx) == "e"


def test_no_learner_yet_is_random_among_all() -> None:
    ctx = context([], ("a",), "abc")
    assert ctx.candidates() == ("b", "c")
    for name in strategy_names():
        assert strategy(name).choose(ctx) in {"b", "c"}


# ---------------------------------------------------------------- what is skipped


def test_skips_executed_known_and_anti_edges() -> None:
    anti = AntiEdges([(("b", "a"), "d")])  # recorded after b, a: the same state as a, b
    ctx = context([("a", "b", "c", "d")], ("a",), "abcd", anti)
    # a executed, b known from {a}; d refused at {a, b} but we are at {a}: c and d remain.
    assert ctx.candidates() == ("c", "d")
    ctx = context([("a", "b", "c", "d")], ("a", "b"), "abcd", anti)
    # c known from {a, b}; d is an anti-edge there.
    assert ctx.candidates() == ()
    for name in strategy_names():
        assert strategy(name).choose(ctx) is None


def test_repeated_actions_map_to_next_occurrence() -> None:
    # stir, add, stir: after one stir, stir stands for the second stir (stir -> add -> stir#2: distance 2).
    demos = [("stir", "add", "stir")]
    ctx = context(demos, ("stir",), ("stir", "add", "bake"))
    assert ctx.next_subgoal("stir") == ctx.task_graph.subgoal_index(("stir", 2))  # type: ignore[union-attr]
    assert ctx.candidates() == ("stir", "bake")
    assert DistanceQuery().choose(ctx) == "stir"
    # After both stirs, a third stir is unknown: stir counts as executed.
    ctx = context(demos, ("stir", "add", "stir"), ("stir", "add", "bake"))
    assert ctx.candidates() == ("bake",)


def test_anti_edges_object() -> None:
    anti = AntiEdges()
    assert anti.add(["a", "b"], "c") and not anti.add(("b", "a"), "c")
    assert (("b", "a"), "c") in anti and (("a",), "c") not in anti and "x" not in anti
    assert anti.contains(state_key(["a", "b"]), "c")
    assert anti.blocked(["a", "b"]) == {"c"} and len(anti) == 1
    assert list(anti) == [(state_key(["a", "b"]), "c")]
    with pytest.raises(LearningError, match="not the string"):
        anti.add("ab", "c")


# ---------------------------------------------------------------- registry and determinism


def test_registry() -> None:
    assert strategy_names() == ("connectivity", "distance", "random")
    assert isinstance(strategy("random"), RandomQuery)
    with pytest.raises(LearningError, match=r"unknown query strategy 'nearest'.*connectivity, distance"):
        strategy("nearest")


def _queries(name: str, seed: int) -> tuple[QueryRecord, ...]:
    session = TeachingSession(list(V_NEEDS), strategy=name, schedule=QuerySchedule((0, 1, 3, 5)), seed=seed)
    run_session(session, Obliging(V_NEEDS, seed=7), 4)
    return session.queries


@pytest.mark.parametrize("name", ["random", "distance", "connectivity"])
def test_same_seed_same_queries(name: str) -> None:
    assert _queries(name, 3) == _queries(name, 3)
    assert len({_queries(name, seed) for seed in range(6)}) > 1  # ties (and random) differ across seeds


# ---------------------------------------------------------------- schedule


def test_schedule_steps_and_limits() -> None:
    order = ("a", "b", "c", "d", "e", "f", "g")
    vocabulary = (*order, "x", "y", "z")  # never performed, so always askable somewhere
    session = TeachingSession(vocabulary, strategy="random", seed=1)  # default: after steps 1, 3, 5
    run_session(session, Scripted(order), 2)
    assert [q.step for q in session.queries] == [1, 3, 5, 1, 3, 5]

    limited = QuerySchedule(after_steps=(0, 2, 4), max_per_demonstration=2, skip_first_demonstrations=1)
    session = TeachingSession(vocabulary, strategy="random", schedule=limited, seed=1)
    instructor = Scripted(order)
    run_session(session, instructor, 3)
    assert [(q.demonstration, q.step) for q in session.queries] == [(1, 0), (1, 2), (2, 0), (2, 2)]
    assert instructor.seen[: len(order) + 1] == [None] * (len(order) + 1)  # nothing asked in the first


def test_thesis_schedules_and_validation() -> None:
    assert QuerySchedule.thesis(1) == QuerySchedule((1, 3, 5), 3, 1)
    assert QuerySchedule.thesis(3).after_steps == (0, 2, 4)
    assert QuerySchedule((5, 1, 1)).after_steps == (1, 5)
    with pytest.raises(LearningError, match="tasks 1, 2 or 3"):
        QuerySchedule.thesis(4)
    with pytest.raises(LearningError, match="after_steps"):
        QuerySchedule((-1,))
    with pytest.raises(LearningError, match="max_per_demonstration"):
        QuerySchedule(max_per_demonstration=-1)
    with pytest.raises(LearningError, match="skip_first_demonstrations"):
        QuerySchedule(skip_first_demonstrations=-2)


# ---------------------------------------------------------------- sessions


def test_refused_query_records_anti_edge_and_is_never_repeated() -> None:
    order = ("a", "b", "c", "d")
    session = TeachingSession(order, strategy="random", schedule=QuerySchedule((0, 1, 2)), seed=4)
    run_session(session, Scripted(order), 1)
    session.begin()
    asked = session.query()
    assert asked is not None and asked != "a"
    session.observe("a")
    assert session.queries[-1] == QueryRecord(1, 0, asked, honoured=False)
    assert session.anti_edges.contains((), asked)
    for step in order[1:]:
        session.observe(step)
    session.end()
    session.begin()
    assert asked not in session.context().candidates()  # back at the origin state: ruled out
    for step in order:
        session.observe(step)
    session.end()
    run_session(session, Scripted(order), 12)
    refused = [q for q in session.queries if q.honoured is False]
    states = {(q.step, q.action) for q in refused}  # the scripted order makes the step identify the state
    assert len(states) == len(refused)  # never asked twice at the same state
    assert len(session.anti_edges) == len(refused)
    # Askable at all: b, c, d at the origin; c, d after a; d after a, b. All refused, then no more queries.
    assert states == {(0, "b"), (0, "c"), (0, "d"), (1, "c"), (1, "d"), (2, "d")}
    assert all(q.demonstration < 10 for q in session.queries)


def test_honoured_query() -> None:
    session = TeachingSession(KCC, schedule=QuerySchedule((0,), skip_first_demonstrations=1), seed=0)
    run_session(session, Scripted(KCC), 1)
    session.begin()
    assert session.query() == "carrots" and session.query() == "carrots"  # idempotent, counted once
    assert session.pending == "carrots"
    session.observe("knife")  # refused: carrots cannot come first
    assert session.pending is None and session.query() is None  # only step 0 is scheduled
    session.observe("carrots")
    session.observe("celery")
    session.end()
    session.begin()
    assert session.query() == "celery"  # carrots refused at the origin; knife is known
    session.observe("knife")
    session.observe("celery")
    session.observe("carrots")
    session.end()
    session.begin()
    assert session.query() is None  # carrots and celery refused at the origin, knife known
    for step in KCC:
        session.observe(step)
    session.end()
    assert [q.honoured for q in session.queries] == [False, False]

    session = TeachingSession(KCC, schedule=QuerySchedule((1,), skip_first_demonstrations=1), seed=0)
    run_session(session, Scripted(KCC), 1)
    session.begin()
    session.observe("knife")
    assert session.query() == "celery"
    session.observe("celery")
    assert session.queries[-1].honoured is True and len(session.anti_edges) == 0


@pytest.mark.parametrize("name", ["random", "distance", "connectivity"])
def test_full_session_learns_incrementally(name: str) -> None:
    session = TeachingSession(list(V_NEEDS), strategy=name, schedule=QuerySchedule.thesis(2), seed=11)
    counts = []
    instructor = Obliging(V_NEEDS, seed=5)
    for _ in range(4):
        run_session(session, instructor, 1)
        counts.append(session.learner.stats_.demonstrations)
    assert counts == [1, 2, 3, 4]
    demos = [d.actions for d in session.demonstrations]
    batch = HTNLearner(mode="strict").fit([list(d) for d in demos])
    assert session.learner.htn_.canonical() == batch.htn_.canonical()
    assert session.learner.task_graph_.path_count() == batch.task_graph_.path_count()
    assert session.learner.ctg_.n_edges == batch.ctg_.n_edges
    assert all(q.demonstration > 0 for q in session.queries)
    assert all(sum(q.demonstration == d for q in session.queries) <= 3 for d in range(4))
    assert any(q.honoured for q in session.queries)


def test_session_with_fitted_learner() -> None:
    learner = HTNLearner().fit([list(KCC)])
    session = TeachingSession(KCC, schedule=QuerySchedule((0,)), learner=learner)
    session.begin()
    assert session.query() == "carrots"
    assert session.learner is learner


def test_errors() -> None:
    with pytest.raises(LearningError, match="at least one action"):
        TeachingSession([])
    with pytest.raises(LearningError, match="repeat 'a'"):
        TeachingSession(["a", "a"])
    with pytest.raises(LearningError, match="not a string"):
        TeachingSession("abc")
    session = TeachingSession(KCC)
    with pytest.raises(LearningError, match="begin"):
        session.query()
    with pytest.raises(LearningError, match="begin"):
        session.observe("knife")
    session.begin()
    with pytest.raises(LearningError, match="already in progress"):
        session.begin()
    with pytest.raises(
        LearningError, match=r"step 1 of demonstration 1: unknown action 'fork'; expected one of knife"
    ):
        session.observe("fork")
    with pytest.raises(LearningError, match="no steps"):
        session.end()
    with pytest.raises(LearningError, match=">= 0"):
        run_session(session, Scripted(KCC), -1)

    class Endless:
        def begin_demonstration(self) -> None:
            pass

        def next_action(self, done: tuple[str, ...], query: str | None) -> str | None:
            return "knife"

    with pytest.raises(LearningError, match="did not finish within 5 steps"):
        run_session(TeachingSession(KCC), Endless(), 1, max_steps=5)


def test_questions_buy_known_orders_in_the_demo_session() -> None:
    from supportive.cli.demo_tour import teach_tower

    quiet, asking = teach_tower(None), teach_tower("distance")
    assert quiet.questions == ()
    assert len(asking.questions) >= 6  # up to 3 per demonstration after the first
    assert asking.known_orders > quiet.known_orders
