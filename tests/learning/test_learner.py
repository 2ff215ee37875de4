from __future__ import annotations

import pytest

from supportive import examples
from supportive.errors import LearningError
from supportive.learning import HTNLearner, learn
from supportive.learning.learner import Mode
from supportive.learning.selection import CANDIDATES
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, canonical, count_orderings, iter_orderings

BLOCKS = {
    "blocks-tower": (720, "chain containing a clique"),
    "blocks-v": (24, "chain of cliques"),
    "blocks-towers": (6, "clique of chains"),
}


def _all_orderings(name: str) -> list[list[str]]:
    structure = examples.load(name).structure
    assert structure is not None
    return [[a for a, _ in o] for o in iter_orderings(structure)]


@pytest.mark.parametrize("name", sorted(BLOCKS))
def test_block_tasks_from_all_orderings(name: str) -> None:
    paths, _ = BLOCKS[name]
    spec = examples.load(name)
    assert spec.structure is not None and count_orderings(spec.structure) == paths
    learner = HTNLearner().fit(_all_orderings(name))
    assert learner.task_graph_.path_count() == paths
    assert learner.htn_.complete
    assert canonical(learner.htn_.roots[0]) == canonical(spec.structure)


def test_block_task_shapes() -> None:
    tower = HTNLearner().fit(_all_orderings("blocks-tower")).htn_.roots[0]
    assert isinstance(tower, ChainNode) and [c.kind for c in tower.children] == ["action", "clique", "action"]
    v = HTNLearner().fit(_all_orderings("blocks-v")).htn_.roots[0]
    assert isinstance(v, ChainNode) and [c.kind for c in v.children] == [
        "action",
        "clique",
        "clique",
        "clique",
    ]
    towers = HTNLearner().fit(_all_orderings("blocks-towers")).htn_.roots[0]
    assert isinstance(towers, CliqueNode) and {c.kind for c in towers.children} == {"chain"}


@pytest.mark.parametrize("name", examples.names())
def test_examples_learn_and_admit_their_demonstrations(name: str) -> None:
    spec = examples.load(name)
    learner = learn(spec)
    correct = [d.actions for d in spec.demonstrations if not d.labelled]  # a labelled mistake is not a way to do it
    assert correct and all(learner.htn_.admits(d) for d in correct)
    stats = learner.stats_.as_dict()
    assert stats["demonstrations"] == len(spec.demonstrations)
    assert stats["task_graph"]["paths"] >= len({tuple(d) for d in spec.action_sequences()})


def test_two_glasses_yields_both_readings() -> None:
    htn = learn(examples.load("two-glasses"), mode="strict").htn_  # the thesis's readings: the strict learner's
    assert not htn.complete and len(htn.roots) == 4
    p1, p2, f1, f2 = (
        ActionNode(a) for a in ("place_glass_1", "place_glass_2", "fill_glass_1", "fill_glass_2")
    )
    by_glass = canonical(CliqueNode((ChainNode((p1, f1)), ChainNode((p2, f2)))))
    place_then_fill = canonical(ChainNode((CliqueNode((p1, p2)), CliqueNode((f1, f2)))))
    found = [canonical(alt.roots[0]) for alt in htn.alternatives]
    assert found == [place_then_fill, by_glass]  # best first: the reading admitting more known orders


def test_alternatives_need_the_orders_they_admit() -> None:
    # only the "glass by glass" orders were seen: that reading is learned outright, no alternatives
    learner = HTNLearner(mode="strict").fit([["p1", "f1", "p2", "f2"], ["p2", "f2", "p1", "f1"]])
    assert learner.htn_.complete and learner.htn_.alternatives == ()
    assert learner.htn_.roots[0].kind == "clique"


def test_order_agnostic_but_interleaved_set_is_not_a_clique() -> None:
    # b and c commute (both orders seen from the same state) but d sometimes runs between them
    learner = HTNLearner(mode="strict").fit([list("abcde"), list("acbde"), list("abdce")])
    for root in learner.htn_.roots:
        if not isinstance(root, ActionNode):
            assert set(root.leaves) != {("b", 1), ("c", 1)}
    assert all(learner.htn_.admits(list(d)) for d in ("abcde", "acbde", "abdce"))


def test_nested_clique_is_not_flattened() -> None:
    # clique{clique{a, b}, c}: every pair is seen both ways, yet a, c, b is never valid
    orders = [list("abc"), list("bac"), list("cab"), list("cba")]
    root = HTNLearner().fit(orders).htn_.roots[0]
    assert canonical(root) == canonical(
        CliqueNode((CliqueNode((ActionNode("a"), ActionNode("b"))), ActionNode("c")))
    )


def test_partial_hierarchy_reports_top_level() -> None:
    learner = HTNLearner(mode="strict").fit([list("abcd"), list("bacd"), list("abdc")])
    htn = learner.htn_
    assert htn.complete  # chain{clique{a,b}, clique{c,d}} needs both orders of c, d after both of a, b
    partial = HTNLearner(mode="strict").fit([list("abcd"), list("bdac")]).htn_
    assert not partial.complete and partial.top_level is not None
    assert partial.admits(list("abcd")) and partial.admits(list("bdac"))
    assert not partial.admits(list("dcba"))


def _names(node: object) -> set[str]:
    found = {node.name} if getattr(node, "name", None) else set()  # type: ignore[attr-defined]
    for child in getattr(node, "children", ()):
        found |= _names(child)
    return found


@pytest.mark.parametrize("mode", ["strict", "general"])
def test_structure_names_label_learned_nodes(mode: Mode) -> None:
    htn = learn(examples.load("ikea-chair"), mode=mode).htn_
    names = set().union(*(_names(r) for r in htn.roots))
    assert {"Build frame", "Attach seat", "Fasten front left bolt"} <= names


@pytest.mark.parametrize("reading", CANDIDATES)
def test_every_reading_auto_may_keep_can_be_pinned(reading: str) -> None:
    # a learner fitted with ``auto`` names the reading it kept in ``reading_``; that name fits another learner
    # in the same reading (the next-step predictor's calibration folds do)
    demos = [list(o) for o in ("abcdef", "bacdfe", "abdcef", "badcfe", "abcdfe", "bacdef", "abdcfe")]
    learner = HTNLearner(mode=reading).fit(demos)  # type: ignore[arg-type]
    assert learner.reading_ == reading
    assert all(learner.htn_.admits(d) for d in demos)
    chosen = HTNLearner().fit(demos)
    assert repr(HTNLearner(mode=chosen.reading_).fit(demos).htn_) == repr(chosen.htn_)  # type: ignore[arg-type]


def test_an_unknown_mode_is_an_error_naming_the_readings() -> None:
    with pytest.raises(LearningError, match=r"'partial order \(consistent orders\)'.*got 'partial'"):
        HTNLearner(mode="partial")  # type: ignore[arg-type]


def test_no_demonstrations_is_an_error() -> None:
    with pytest.raises(LearningError, match="no demonstrations"):
        HTNLearner().fit([])
    with pytest.raises(LearningError, match="string"):
        HTNLearner().fit(["abc"])


@pytest.mark.parametrize("mode", ["strict", "auto"])
def test_a_step_that_is_not_an_action_id_is_an_error_naming_it(mode: Mode) -> None:
    # (action, instance) leaves are what iter_orderings yields: a slip of hand, not a TypeError from deep inside
    with pytest.raises(LearningError, match=r"^demonstration 2, step 1: expected an action id \(a string\), got tuple$"):
        HTNLearner(mode=mode).fit([["a", "b"], [("b", 1), ("a", 1)]])  # type: ignore[list-item]
    learner = HTNLearner(mode=mode).fit([["a", "b"]])
    with pytest.raises(LearningError, match=r"^demonstration 2, step 2: expected an action id \(a string\), got NoneType$"):
        learner.partial_fit(["b", None])  # type: ignore[list-item]
    assert not learner.fitted  # as after any fit that raises (supportive.estimator)


@pytest.mark.parametrize("mode", ["strict", "general"])
def test_repeated_actions_learn_as_occurrences(mode: Mode) -> None:
    orders = [["stir", "heat", "stir", "a", "b"], ["stir", "heat", "stir", "b", "a"]] * 2
    root = HTNLearner(mode=mode).fit(orders).htn_.roots[0]
    assert canonical(root) == canonical(
        ChainNode(
            (
                ActionNode("stir"),
                ActionNode("heat"),
                ActionNode("stir", 2),
                CliqueNode((ActionNode("a"), ActionNode("b"))),
            )
        )
    )
