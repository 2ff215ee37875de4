from __future__ import annotations

import json

import pytest

from supportive import examples
from supportive.errors import TaskFileError
from supportive.io.dot import htn_to_dot
from supportive.io.htn_json import htn_from_dict, htn_to_dict
from supportive.learning import HTNLearner, learn
from supportive.render.tree import render_tree
from supportive.tasks.htn import HTN, ActionNode, ChainNode
from supportive.tasks.naming import full_name


@pytest.mark.parametrize("name", examples.names())
def test_json_round_trip(name: str) -> None:
    learner = learn(examples.load(name))
    data = json.loads(json.dumps(htn_to_dict(learner.htn_, learner.stats_.as_dict())))
    assert set(data) >= {"task", "complete", "roots", "alternatives", "stats"}
    assert set(data["stats"]) == {"demonstrations", "actions", "task_graph", "ctg", "htn", "seconds"}
    back = htn_from_dict(data)
    assert back.canonical() == learner.htn_.canonical()
    assert back.top_level == learner.htn_.top_level
    if back.top_level is not None:  # the counting hint too (TopLevel's equality leaves it out)
        assert learner.htn_.top_level is not None and back.top_level.free == learner.htn_.top_level.free
    assert [a.canonical() for a in back.alternatives] == [a.canonical() for a in learner.htn_.alternatives]
    assert [getattr(r, "name", None) for r in back.roots] == [  # made-up names come back whole (issue 26)
        None if isinstance(r, ActionNode) else full_name(r) for r in learner.htn_.roots
    ]


def test_json_shape_of_a_complete_hierarchy() -> None:
    data = htn_to_dict(learn(examples.load("knife-carrots-celery"), mode="strict").htn_)
    assert data["complete"] is True and "top_level" not in data
    root = data["roots"][0]
    assert root["kind"] == "chain" and root["name"] == "Prepare salad vegetables"
    assert root["children"][0] == {"kind": "action", "action": "get_knife"}
    assert root["children"][1]["kind"] == "clique"


def test_repeated_action_keeps_its_occurrence() -> None:
    htn = HTN("t", (ChainNode((ActionNode("stir"), ActionNode("heat"), ActionNode("stir", 2))),))
    data = htn_to_dict(htn)
    assert data["roots"][0]["children"][2] == {"kind": "action", "action": "stir", "occurrence": 2}
    assert htn_from_dict(data).canonical() == htn.canonical()


def test_dot_has_every_node_and_marks_kinds() -> None:
    htn = learn(examples.load("blocks-v")).htn_
    dot = htn_to_dot(htn)
    assert dot.startswith("digraph htn {") and dot.rstrip().endswith("}")
    for action in examples.load("blocks-v").action_ids():
        assert f'label="{action}"' in dot
    partial = htn_to_dot(learn(examples.load("two-glasses")).htn_)
    assert "(partial)" in partial and partial.count("task ->") == 4


def test_tree_reads_in_order_and_any_order() -> None:
    spec = examples.load("knife-carrots-celery")
    text = render_tree(learn(spec, mode="strict").htn_, spec.texts())
    assert "in order Prepare salad vegetables" in text
    assert "any order Chop vegetables" in text
    assert "get_knife — get the knife" in text


def test_counts_beyond_what_json_holds_are_written_as_scientific_strings() -> None:
    """A task graph with more than 10^4300 paths (a valid task: 14,300 pairs each done both ways) used to
    crash ``learn --format json``: Python cannot even turn the count into digits."""
    import json

    from supportive.io.htn_json import htn_to_dict, json_count
    from supportive.learning.learner import learn as learn_htn
    from supportive.tasks.spec import Demonstration, TaskSpec

    spec = TaskSpec("pair", demonstrations=(Demonstration.of(["a", "b"]), Demonstration.of(["b", "a"])))
    learner = learn_htn(spec)
    stats = learner.stats_.as_dict()
    stats["task_graph"]["paths"] = 2**14_300
    data = json.loads(json.dumps(htn_to_dict(learner.htn_, stats)))
    assert data["stats"]["task_graph"]["paths"] == "5.35720e+4304"
    assert json_count(2**53) == 2**53 and json_count(2**53 + 1) == "9.00719e+15"
    assert [json_count(10**k) for k in (16, 300, 5000)] == ["1.00000e+16", "1.00000e+300", "1.00000e+5000"]


def test_the_tree_of_a_partial_hierarchy_shows_the_orders_of_its_parts() -> None:
    """Issue 26: "partial: 4 top-level parts" hid the orders seen among the parts."""
    from supportive.render.tree import top_level_orders

    spec = examples.load("two-glasses")
    htn = learn(spec).htn_
    assert not htn.complete and htn.top_level is not None
    text = render_tree(htn, spec.texts())
    orders, total = top_level_orders(htn)
    assert f"orders of these parts it admits ({total}):" in text
    for order in orders:
        assert " → ".join(htn.roots[i].label for i in order) in text  # type: ignore[union-attr]
        assert htn.admits([htn.roots[i].label for i in order])  # type: ignore[union-attr]
    assert total == htn.top_level.count_orderings() and len(orders) == min(total, 6)


@pytest.mark.parametrize("name", examples.names())
def test_json_names_are_never_cut(name: str) -> None:
    """Issue 26: names made up for people ("pour_water → … → stir") were written to JSON cut with "…"."""

    def names(node: dict[str, object]) -> list[str]:
        own = [str(node["name"])] if node.get("name") else []
        return own + [n for child in node.get("children", []) for n in names(child)]  # type: ignore[attr-defined]

    spec = examples.load(name)
    if name == "tea-mistakes":  # without the two steps done too early (each could be chance in 13), a subtask
        # made up of a step sequence and a named subtask, whose name is long
        spec = spec.with_demonstrations([d for d in spec.demonstrations if all(s.mistake != "order" for s in d.entries)])
    learner = learn(spec)
    data = htn_to_dict(learner.htn_, learner.stats_.as_dict())
    written = [n for root in data["roots"] for n in names(root)]
    assert not any("…" in n for n in written), written
    if name == "tea-mistakes":
        assert "pour_water → steep → remove_teabag → Milk and sugar → stir" in written


def test_the_counting_hint_of_a_partial_order_of_roots_survives_json() -> None:
    """A partial hierarchy whose optional root unlocks nothing keeps ``free`` through JSON (and so its fast
    count); a ``free`` that is not a list of root indices is one clear error."""
    demos = [["a", "b", "d"], ["a", "b", "c", "e"], ["b", "a", "d"]]  # c, d and e optional, of no fixed order
    htn = HTNLearner(mode="general", subtask_demonstrations=4).fit(demos).htn_  # orders only
    assert htn.top_level is not None and htn.top_level.free
    back = htn_from_dict(json.loads(json.dumps(htn_to_dict(htn))))
    assert back.top_level is not None and back.top_level.free == htn.top_level.free
    assert back.count_orderings() == htn.count_orderings()
    data = htn_to_dict(htn)
    data["top_level"]["free"] = ["b"]
    with pytest.raises(TaskFileError, match="'free', if given, a list of root indices"):
        htn_from_dict(data)
