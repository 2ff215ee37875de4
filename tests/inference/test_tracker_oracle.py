"""The progress-aware tracker against brute force (issue 27), over both forms of its belief — the exact
vector and the beam's map of states (a beam wide enough to hold every state) — as hmmlearn runs each test over
each implementation, and over both kinds of hierarchy the learners make: single-root trees of chains, cliques,
optional and repeated leaves, and partial hierarchies — two or three such roots in the order a top level
gives, either the general learner's partial order of the roots (some optional, some that may be performed as
nothing) or the orders of roots seen (the strict learner's), with or without learned counts.

On small generated tasks the oracle enumerates every hidden path of states through the evidence (contact
events, known actions, or both mixed), each step's moves written out here from the model's own next-step
probabilities (:meth:`ProgressModel.outcomes`) and the documented rules (docs/inference.md: a subgoal under
way stays with probability ``1 - 1/mean_duration``; a step is off-script with probability ``slip``; off-script
contact events skip one step; an off-script action lands on the nearest state ahead in which it was just
done, or keeps the progress), weighs each path by its moves and by the observation probabilities worked out
event by event from the observation table, and compares the posterior over states, what is done, finished,
the probability that the last step was off-script and the log-likelihood with the tracker's, to 1e-9.

For a partial hierarchy the oracle first checks that those moves follow the top level's edges
(:func:`assert_follows_top_level`): from every prefix, the actions the model allows next, and whether it may
end, are exactly those of the walks through the top level that begin with that prefix — every walk from an
initial state to a terminal one, each edge's root performed in any order it admits, as nothing where it may
be (:func:`top_level_walks`) — and its probabilities add up to one over those walks."""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections import defaultdict
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.inference import (
    END_LABEL,
    ActionFilter,
    Filter,
    FlatHMM,
    HierarchicalHMM,
    ObservationModel,
    ProgressFilter,
    ProgressHMM,
)
from supportive.learning.distribution import END, ProgressModel
from supportive.learning.general.top_order import seen_top_level
from supportive.tasks.executions import Progress
from supportive.tasks.htn import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Counts,
    Leaf,
    Node,
    TopLevel,
    iter_orderings,
)

Shape = str | tuple[str, list["Shape"]]
State = Progress | None  # None: finished
Evidence = tuple[str, Any]  # ("events", frozenset of events) or ("action", action id)

FORMS: dict[str, dict[str, Any]] = {
    "exact": {},  # the states enumerated, the belief a vector moved by sparse matrices
    "beam": {"max_states": 1, "beam": 1_000_000},  # not enumerated: a map of states, cut to the beam
}

def _shapes(leaves: list[str], max_leaves: int = 4) -> st.SearchStrategy[Shape]:
    return st.recursive(
        st.sampled_from(leaves),
        lambda inner: st.tuples(st.sampled_from(["chain", "clique"]), st.lists(inner, min_size=2, max_size=3)),
        max_leaves=max_leaves,
    )


shapes = _shapes(["leaf", "optional"])
"""Small hierarchies of chains, cliques and optional steps, every action once."""
repeating = _shapes(["leaf", "optional", "again"])
"""The same, where a leaf may be the previous leaf's action again (its next occurrence)."""


def build(shape: Shape, names: itertools.count[int] | None = None, done: list[ActionNode] | None = None) -> Node:
    """The hierarchy a drawn shape describes (actions ``x0``, ``x1``, ... in order; ``again``: the previous
    leaf's action once more)."""
    names = itertools.count() if names is None else names
    done = [] if done is None else done
    if isinstance(shape, str):
        if shape == "again" and done:
            leaf = ActionNode(done[-1].action, done[-1].occurrence + 1)
        else:
            leaf = ActionNode(f"x{next(names)}", optional=shape == "optional")
        done.append(leaf)
        return leaf
    kind, parts = shape
    children = tuple(build(p, names, done) for p in parts)
    return (ChainNode if kind == "chain" else CliqueNode)(children)


def partial_order(n: int, before: set[tuple[int, int]], required: frozenset[int]) -> TopLevel:
    """The top level the general learner makes of ``n`` roots and the precedences ``before`` (``(u, v)``: ``u``
    comes before ``v``), written out from its rule (docs/learning.md, ``top_order.py``): its states are the sets
    of roots done; a root may be done when it is not done, no root that must follow it is done, and every
    *required* root that must precede it is done (a precedence binds an optional root only when it is
    performed); the task may end once every required root is done. The optional roots are ``free``."""
    number: dict[frozenset[int], int] = {frozenset(): 0}
    edges: list[tuple[int, int, int]] = []
    frontier = [frozenset[int]()]
    while frontier:
        done = frontier.pop()
        for root in range(n):
            if root in done or any((root, v) in before for v in done):
                continue
            if any((u, root) in before and u in required and u not in done for u in range(n)):
                continue
            after = done | {root}
            if after not in number:
                number[after] = len(number)
                frontier.append(after)
            edges.append((number[done], root, number[after]))
    terminal = tuple(sorted(state for done, state in number.items() if required <= done))
    return TopLevel((0,), terminal, tuple(sorted(edges)), free=frozenset(range(n)) - required)


@st.composite
def partial_hierarchies(draw: st.DrawFn, shape: st.SearchStrategy[Shape], top: str, *, roots: int = 3) -> HTN:
    """A partial hierarchy: two to ``roots`` roots, each a drawn shape (numbered on from the previous root's
    actions, so an ``again`` leaf may repeat another root's action), under a top level of the given form,
    with or without learned counts (which root comes first, which follows which, how often each was
    performed).

    ``top="partial order"``: the general learner's (:func:`partial_order`) over a random partial order of the
    roots, some roots optional. ``top="seen orders"``: the top level of one to three random orders of the
    roots (:func:`~supportive.learning.general.top_order.seen_top_level`); a root ``shape`` draws optional
    may be skipped wherever the orders pass it, which may lead elsewhere than performing it (see
    :func:`test_a_top_level_of_seen_orders_with_an_optional_root_keeps_every_walk`)."""
    names: itertools.count[int] = itertools.count()
    done: list[ActionNode] = []
    nodes = [build(s, names, done) for s in draw(st.lists(shape, min_size=2, max_size=roots))]
    n = len(nodes)
    if top == "partial order":
        nodes = [dataclasses.replace(node, optional=True) if draw(st.booleans()) else node for node in nodes]
        order = draw(st.permutations(range(n)))
        before = {(order[i], order[j]) for i in range(n) for j in range(i + 1, n) if draw(st.booleans())}
        top_level = partial_order(n, before, frozenset(r for r, node in enumerate(nodes) if not node.optional))
    else:
        top_level = seen_top_level(range(n), draw(st.lists(st.permutations(range(n)), min_size=1, max_size=3)))
    if draw(st.booleans()):
        counts = st.integers(0, 3)
        first = tuple(draw(st.lists(counts, min_size=n, max_size=n)))
        after = tuple(tuple(draw(st.lists(counts, min_size=n, max_size=n))) for _ in range(n))
        top_level = dataclasses.replace(top_level, counts=Counts(performed=sum(first), first=first, after=after))
        nodes = [dataclasses.replace(node, counts=Counts(performed=draw(counts))) for node in nodes]
    return HTN("t", tuple(nodes), top_level)


def tree(shape: Shape) -> HTN:
    """The complete hierarchy of one drawn shape."""
    return HTN("t", (build(shape),))


HIERARCHIES: dict[str, st.SearchStrategy[HTN]] = {
    "tree": repeating.map(tree),
    "partial order": partial_hierarchies(_shapes(["leaf", "optional", "again"], max_leaves=3), "partial order"),
    "seen orders": partial_hierarchies(_shapes(["leaf", "optional", "again"], max_leaves=3), "seen orders"),
}
"""The hierarchies the tracker is checked over: single-root trees, and partial hierarchies of a few small roots
under either form of top level the learners make (kept small: the oracle's paths grow as a power of the
states)."""


def top_level_walks(htn: HTN) -> list[tuple[Leaf, ...]]:
    """Every leaf sequence a partial hierarchy admits, by brute force over its top level: every walk from an
    initial state to a terminal one along the top level's edges, each edge's root performed in any order it
    admits (as nothing, when it may be: ``iter_orderings``), the same sequence counted once."""
    top = htn.top_level
    assert top is not None
    out = top.successors()
    terminal = set(top.terminal)
    orders = [list(iter_orderings(root)) for root in htn.roots]
    found: set[tuple[Leaf, ...]] = set()

    def walk(state: int, sequence: tuple[Leaf, ...]) -> None:
        if state in terminal:
            found.add(sequence)
        for root, after in out.get(state, {}).items():
            for part in orders[root]:
                walk(after, sequence + part)

    for state in top.initial:
        walk(state, ())
    return sorted(found)


def assert_follows_top_level(model: ProgressModel) -> None:
    """The model's next steps from every prefix, action by action, are exactly the next actions (or the end) of
    the walks through the top level that begin with that prefix (:func:`top_level_walks`), and its
    probabilities add up to one over those walks: the model's on-script moves, which the oracle takes from
    it, follow the top level's edges. (Action by action, because the model starts only the lowest-numbered of
    a repeated subtask's instances; which actions come next is the same.)"""
    walks = {tuple(action for action, _ in w) for w in top_level_walks(model.htn)}
    following: dict[tuple[str, ...], set[str | None]] = defaultdict(set)  # None: the end
    for w in walks:
        for k in range(len(w) + 1):
            following[w[:k]].add(w[k] if k < len(w) else None)
    stack: list[tuple[tuple[str, ...], set[Progress]]] = [((), set(model.executions.initial()))]
    while stack:
        prefix, states = stack.pop()
        offered: dict[str | None, set[Progress]] = defaultdict(set)
        for state in states:
            for leaf, (p, nxt) in model.outcomes(state).items():
                assert p > 0
                if nxt is None:
                    offered.setdefault(None, set())
                else:
                    offered[model.leaves[leaf][0]].add(nxt)
        assert set(offered) == following[prefix], prefix
        stack.extend(((*prefix, action), nexts) for action, nexts in offered.items() if action is not None)
    assert sum(math.exp(model.log_probability(w)) for w in walks) == pytest.approx(1.0, abs=1e-12)


def tracker(htn: HTN, form: str, **settings: Any) -> ProgressFilter:
    """A fresh tracker over ``htn`` in the given form of the belief."""
    hmm = ProgressHMM(htn, **FORMS[form], **settings).fit()
    assert hmm.exact == (form == "exact")
    return hmm.filter()


# ---------------------------------------------------------------------- the oracle
class Oracle:
    """Every step's moves, written out from the model and the documented rules (for a partial hierarchy, once
    the model's moves are checked to follow its top level)."""

    def __init__(self, htn: HTN, *, stay: float, slip: float, restart: bool, events: ObservationModel | None) -> None:
        self.model = ProgressModel(htn)
        if htn.top_level is not None:
            assert_follows_top_level(self.model)
        self.stay, self.slip, self.restart, self.events = stay, slip, restart, events
        states = self.model.states(10**6)
        assert states is not None
        self.states: list[Progress] = states
        self.leaves = self.model.leaves
        self.actions = list(dict.fromkeys(a for a, _ in self.leaves))
        self._emissions: dict[tuple[State, frozenset[str]], float] = {}

    def next_states(self, state: State) -> list[tuple[int, float, State]]:
        """(leaf or END, probability, state after) of every next step; finished: stays, or starts again."""
        if state is None and not self.restart:
            return [(END, 1.0, None)]
        if state is None:
            start = self.model.executions.initial()
            return [(leaf, p / len(start), nxt) for s in start for leaf, (p, nxt) in self.model.outcomes(s).items()]
        return [(leaf, p, nxt) for leaf, (p, nxt) in self.model.outcomes(state).items()]

    def skipped(self, state: State) -> dict[Progress, float]:
        """A step skipped: the subgoal states two steps ahead, normalised."""
        ahead: dict[Progress, float] = defaultdict(float)
        for _, p, middle in self.next_states(state):
            for _, q, after in self.next_states(middle):
                if after is not None:
                    ahead[after] += p * q
        total = sum(ahead.values())
        return {s: w / total for s, w in ahead.items()}

    def reachable(self, state: Progress) -> set[Progress]:
        """The states one or more on-script steps ahead of ``state``."""
        found: set[Progress] = set()
        frontier = [state]
        while frontier:
            for _, _, nxt in self.next_states(frontier.pop()):
                if nxt is not None and nxt not in found:
                    found.add(nxt)
                    frontier.append(nxt)
        return found

    def resync(self, state: State, action: str) -> State:
        """The state ahead with ``action`` just done and the fewest leaves done (ties: done set, last, top);
        ``state`` when there is none."""
        if state is None:
            return None
        hits = [t for t in self.reachable(state) if self.leaves[t.last][0] == action]
        if not hits:
            return state
        return min(hits, key=lambda t: (t.done.bit_count(), t.done, t.last, t.top))

    def emission(self, state: State, events: frozenset[str]) -> float:
        """P(events | state): the action of its subgoal's table, event by event; finished or not started:
        the mean over the leaves."""
        key = (state, events)
        if key not in self._emissions:
            self._emissions[key] = self._emission(state, events)
        return self._emissions[key]

    def _emission(self, state: State, events: frozenset[str]) -> float:
        assert self.events is not None
        table = self.events

        def given(action: str) -> float:
            row = table.table[table.action_index[action]]
            return math.prod(
                float(p) if event in events else 1.0 - float(p) for event, p in zip(table.events, row, strict=True)
            )

        if state is None or state.last < 0:
            return sum(given(a) for a, _ in self.leaves) / len(self.leaves)
        return given(self.leaves[state.last][0])

    def moves(self, state: State, evidence: Evidence) -> Iterator[tuple[State, float, bool]]:
        """(state after, weight with the evidence's probability, off-script) of every way one piece of
        evidence can be explained from ``state``."""
        kind, value = evidence
        if kind == "action":
            for leaf, p, nxt in self.next_states(state):
                if leaf != END and self.leaves[leaf][0] == value:
                    yield nxt, (1.0 - self.slip) * p, False
            yield self.resync(state, value), self.slip / (len(self.actions) + 1), True
            return
        performing = state is not None and state.last >= 0
        stays = self.stay if performing else (1.0 if state is None and not self.restart else 0.0)
        if stays:
            yield state, stays * self.emission(state, value), False
        skips = self.skipped(state)
        slip = self.slip if skips else 0.0
        for _, p, nxt in self.next_states(state):
            yield nxt, (1.0 - stays) * (1.0 - slip) * p * self.emission(nxt, value), False
        for after, p in skips.items():
            yield after, (1.0 - stays) * slip * p * self.emission(after, value), True

    def paths(self, evidence: list[Evidence]) -> Iterator[tuple[State, float, bool]]:
        """Every hidden path through ``evidence``: (last state, weight, last step off-script)."""
        start = self.model.executions.initial()

        def walk(state: State, weight: float, off: bool, t: int) -> Iterator[tuple[State, float, bool]]:
            if t == len(evidence):
                yield state, weight, off
                return
            for nxt, w, slipped in self.moves(state, evidence[t]):
                if w > 0:
                    yield from walk(nxt, weight * w, slipped, t + 1)

        for s in start:
            yield from walk(s, 1.0 / len(start), False, 0)

    def posterior(self, evidence: list[Evidence]) -> tuple[dict[State, float], float, float]:
        """Posterior over the last state, P(last step off-script | evidence), log P(evidence)."""
        mass: dict[State, float] = defaultdict(float)
        off = 0.0
        for state, weight, slipped in self.paths(evidence):
            mass[state] += weight
            off += weight * slipped
        total = sum(mass.values())
        return {s: m / total for s, m in mass.items()}, off / total, math.log(total)


def random_events(actions: list[str], seed: int) -> ObservationModel:
    rng = np.random.default_rng(seed)
    return ObservationModel(
        {a: {e: float(rng.uniform(0.05, 0.95)) for e in ("e0", "e1", "e2") if rng.random() < 0.8} for a in actions},
        noise=0.1,
    )


def assert_agrees(running: ProgressFilter, oracle: Oracle, evidence: list[Evidence]) -> None:
    """Feed ``evidence`` one piece at a time; after each, the tracker's belief is the oracle's."""
    for t, (kind, value) in enumerate(evidence):
        belief = running.update(value) if kind == "events" else running.observe(value)
        states, off_script, log_likelihood = oracle.posterior(evidence[: t + 1])
        done = np.zeros(len(oracle.leaves))
        current = np.zeros(len(oracle.leaves))
        for state, p in states.items():
            if state is not None:
                done[[i for i in range(len(oracle.leaves)) if state.done >> i & 1]] += p
                if state.last >= 0:
                    current[state.last] += p
        assert belief.off_script == pytest.approx(off_script, abs=1e-9)
        assert running.log_likelihood == pytest.approx(log_likelihood, rel=1e-9, abs=1e-9)
        assert belief.finished == pytest.approx(states.get(None, 0.0), abs=1e-9)
        assert belief.done == pytest.approx(done, abs=1e-9)
        assert belief.subgoals == pytest.approx(current, abs=1e-9)
    believed = {s: p for s, p in running.belief.items() if p > 1e-12}
    expected = {s: p for s, p in states.items() if p > 1e-12}
    assert set(believed) == set(expected)
    assert believed == pytest.approx(expected, abs=1e-9)


# ---------------------------------------------------------------------- the tests
@pytest.mark.parametrize("kind", HIERARCHIES)
@pytest.mark.parametrize("form", FORMS)
@settings(max_examples=30, deadline=None)
@given(
    seed=st.integers(0, 10_000),
    duration=st.floats(1.0, 6.0),
    slip=st.floats(0.01, 0.5),
    restart=st.booleans(),
    data=st.data(),
)
def test_contact_events_agree_with_brute_force(
    form: str, kind: str, seed: int, duration: float, slip: float, restart: bool, data: st.DataObject
) -> None:
    htn = data.draw(HIERARCHIES[kind], label="htn")
    actions = list(dict.fromkeys(a for a, _ in htn.leaves))
    events = random_events(actions, seed)
    moments = data.draw(st.lists(st.frozensets(st.sampled_from(["e0", "e1", "e2", "other"])), min_size=1, max_size=4))
    running = tracker(htn, form, observations=events, mean_duration=duration, slip=slip, restart=restart)
    oracle = Oracle(htn, stay=1.0 - 1.0 / duration, slip=slip, restart=restart, events=events)
    assert_agrees(running, oracle, [("events", m) for m in moments])


@pytest.mark.parametrize("kind", HIERARCHIES)
@pytest.mark.parametrize("form", FORMS)
@settings(max_examples=30, deadline=None)
@given(slip=st.floats(0.001, 0.5), restart=st.booleans(), data=st.data())
def test_known_actions_agree_with_brute_force_slips_included(
    form: str, kind: str, slip: float, restart: bool, data: st.DataObject
) -> None:
    htn = data.draw(HIERARCHIES[kind], label="htn")
    actions = list(dict.fromkeys(a for a, _ in htn.leaves))
    steps = data.draw(st.lists(st.sampled_from([*actions, "juggle"]), min_size=1, max_size=5))  # any order
    running = tracker(htn, form, slip=slip, restart=restart)
    oracle = Oracle(htn, stay=0.0, slip=slip, restart=restart, events=None)
    assert_agrees(running, oracle, [("action", a) for a in steps])


@pytest.mark.parametrize("kind", HIERARCHIES)
@pytest.mark.parametrize("form", FORMS)
@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 10_000), slip=st.floats(0.01, 0.5), data=st.data())
def test_mixed_evidence_agrees_with_brute_force(
    form: str, kind: str, seed: int, slip: float, data: st.DataObject
) -> None:
    htn = data.draw(HIERARCHIES[kind], label="htn")
    actions = list(dict.fromkeys(a for a, _ in htn.leaves))
    events = random_events(actions, seed)
    piece = st.one_of(
        st.tuples(st.just("events"), st.frozensets(st.sampled_from(["e0", "e1", "e2"]))),
        st.tuples(st.just("action"), st.sampled_from(actions)),
    )
    evidence = data.draw(st.lists(piece, min_size=1, max_size=4))
    running = tracker(htn, form, observations=events, mean_duration=3.0, slip=slip)
    oracle = Oracle(htn, stay=1.0 - 1.0 / 3.0, slip=slip, restart=False, events=events)
    assert_agrees(running, oracle, evidence)


BIGGER: dict[str, st.SearchStrategy[HTN]] = {
    "partial order": partial_hierarchies(_shapes(["leaf", "optional", "again"]), "partial order", roots=4),
    "seen orders": partial_hierarchies(_shapes(["leaf", "optional", "again"]), "seen orders", roots=4),
}
"""Partial hierarchies bigger than the oracle's: up to four roots of up to four leaves."""


@pytest.mark.parametrize("kind", BIGGER)
@settings(max_examples=40, deadline=None)
@given(data=st.data())
def test_a_partial_hierarchys_model_follows_its_top_level(kind: str, data: st.DataObject) -> None:
    """The model's next steps are those of the walks through the top level, and it is a distribution over
    them (what the oracle checks of each hierarchy it is given, on bigger ones)."""
    assert_follows_top_level(ProgressModel(data.draw(BIGGER[kind], label="htn"), smoothing=0.5))


def test_a_root_begins_after_the_fewest_skips() -> None:
    """Three required roots that may be performed as nothing, ``A``, ``B`` and ``C``, and ``q``, which needs
    ``A`` and ``B`` first: ``q c1`` is a walk (``A`` and ``B`` as nothing, ``q``, then ``C``). The top-level
    states that let ``q`` begin were searched depth first, so ``q`` began where ``C`` had been skipped too,
    and ``c1`` could not follow; breadth first, ``q`` begins after the fewest skips."""

    def nothing_needed(action: str) -> ChainNode:
        return ChainNode((ActionNode(f"{action}1", optional=True), ActionNode(f"{action}2", optional=True)))

    roots = (nothing_needed("a"), nothing_needed("b"), nothing_needed("c"), ActionNode("q"))
    htn = HTN("t", roots, partial_order(4, {(0, 3), (1, 3)}, frozenset(range(4))))
    assert htn.admits(["q", "c1"])
    assert_follows_top_level(ProgressModel(htn))


@pytest.mark.parametrize("kind", ["partial order", "seen orders"])
@settings(max_examples=40, deadline=None)
@given(data=st.data())
def test_a_partial_hierarchy_admits_each_walk_and_counts_them(kind: str, data: st.DataObject) -> None:
    """What :meth:`~supportive.tasks.htn.HTN.admits_leaves` accepts and what ``count_orderings`` counts are the
    walks through the top level, however optional roots are passed."""
    htn = data.draw(BIGGER[kind], label="htn")
    walks = top_level_walks(htn)
    assert all(htn.admits_leaves(walk) for walk in walks)
    assert htn.count_orderings() == len(walks)


def test_a_top_level_of_seen_orders_with_an_optional_root_keeps_every_walk() -> None:
    """Where skipping an optional root along its edge leads elsewhere than not skipping it, a root begun may
    stand in several top-level states at once: seen ``x0 [x1 x2]``, ``x0 [x1 x2] [x3 x4]`` and
    ``[x3 x4] [x1 x2] x0`` with ``x0`` and ``[x3 x4]`` optional, ``[x1 x2]`` begins after skipping ``x0`` or
    after skipping ``[x3 x4]``, and only the second lets ``x0`` follow. Committing to the first state reached
    with the fewest skips (``x0`` skipped) lost ``x1 x2 x0``. The general learner's partial orders never
    meet this (from fewer roots passed, at least as much is allowed: ``TopLevel.free``); its fallback to the
    orders seen, beyond 50,000 top-level states or 1,500 roots, can."""
    roots = (
        ActionNode("x0", optional=True),
        ChainNode((ActionNode("x1"), ActionNode("x2"))),
        ChainNode((ActionNode("x3"), ActionNode("x4")), optional=True),
    )
    htn = HTN("t", roots, seen_top_level(range(3), [[0, 1], [0, 1, 2], [2, 1, 0]]))
    assert ("x1", "x2", "x0") in {tuple(a for a, _ in w) for w in top_level_walks(htn)}
    assert htn.admits(["x1", "x2", "x0"]) and htn.admits(["x1", "x2", "x3", "x4"]) and not htn.admits(["x1", "x2", "x3"])
    assert_follows_top_level(ProgressModel(htn))


ONCE: dict[str, st.SearchStrategy[HTN]] = {
    "tree": shapes.map(tree),
    "partial order": partial_hierarchies(_shapes(["leaf", "optional"], max_leaves=3), "partial order"),
    "seen orders": partial_hierarchies(_shapes(["leaf", "optional"], max_leaves=3), "seen orders"),
}
"""Hierarchies in which every action is done once (so a leaf sequence is an action sequence)."""


@pytest.mark.parametrize("kind", ONCE)
@pytest.mark.parametrize("form", FORMS)
@settings(deadline=None)
@given(data=st.data(), seed=st.integers(0, 2**16))
def test_next_steps_agree_with_brute_force_over_executions(
    form: str, kind: str, data: st.DataObject, seed: int
) -> None:
    htn = data.draw(ONCE[kind], label="htn")
    model = ProgressModel(htn, smoothing=1.0)

    def probability(sequence: tuple[tuple[str, int], ...]) -> float:  # step by step from the model's choices
        (state,) = model.executions.initial()
        p = 1.0
        for leaf in sequence:
            outcome = model.outcomes(state).get(model.executions.index[leaf])
            if outcome is None:
                return 0.0
            p *= outcome[0]
            state = outcome[1]  # type: ignore[assignment]
        return p * model.outcomes(state).get(END, (0.0, None))[0]

    executions = list(iter_orderings(htn.roots[0])) if htn.top_level is None else top_level_walks(htn)
    masses = {s: probability(s) for s in executions}
    assert sum(masses.values()) == pytest.approx(1.0)  # the model is a distribution over executions
    truth = executions[int(np.random.default_rng(seed).integers(len(executions)))]
    running = tracker(htn, form, slip=1e-9)
    for k in range(len(truth) + 1):
        consistent = {s: m for s, m in masses.items() if s[:k] == truth[:k]}
        mass = sum(consistent.values())
        expected: dict[str, float] = defaultdict(float)
        for s, m in consistent.items():
            expected[s[k][0] if len(s) > k else END_LABEL] += m / mass
        predicted = running.last.next_actions
        for action, p in expected.items():
            assert predicted[action] == pytest.approx(p, abs=1e-6)
        if k < len(truth):
            running.observe(truth[k][0])


def test_the_discrepancy_of_issue_27_is_gone() -> None:
    """A beam wide enough to hold every state gives the exact tracker's ``off_script`` on contact events
    (before, the beam charged the slip on every moment and spread it over its own states: 0.0085 against
    0.0251 on the lab's stream)."""
    structure = ChainNode((ActionNode("a"), CliqueNode((ActionNode("b"), ActionNode("c"))), ActionNode("d")))
    events = ObservationModel({x: {f"hand-{x}": 0.9} for x in "abcd"})
    exact, beam = (tracker(HTN("t", (structure,)), form, observations=events, mean_duration=3.0) for form in FORMS)
    for moment in ["hand-a", "hand-a", "hand-c", "hand-d", "hand-d", "hand-b", ""]:
        a, b = exact.update({moment}), beam.update({moment})
        assert a.off_script == pytest.approx(b.off_script, abs=1e-12)
        assert a.subgoals == pytest.approx(b.subgoals, abs=1e-12)
        assert exact.log_likelihood == pytest.approx(beam.log_likelihood, abs=1e-12)
    assert a.off_script > 0.0  # d before b: a step was skipped


def test_every_filter_is_a_filter() -> None:
    htn = HTN("t", (ChainNode((ActionNode("a"), ActionNode("b"))),))
    events = ObservationModel({"a": {"x": 0.9}, "b": {"y": 0.9}})
    for kind in (FlatHMM, HierarchicalHMM):
        running = kind(htn, events).fit().filter()
        assert isinstance(running, Filter) and not isinstance(running, ActionFilter)
        assert running.last.step == 0 and running.update({"x"}) is running.last
    progress = ProgressHMM(htn, events).fit().filter()
    assert isinstance(progress, ActionFilter)
    assert progress.update({"x"}) is progress.last and progress.observe("b") is progress.last
