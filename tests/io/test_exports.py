from __future__ import annotations

import json

import pytest

from supportive import examples
from supportive.io.dot import htn_to_dot
from supportive.io.htn_json import htn_from_dict, htn_to_dict
from supportive.io.tree import render_tree
from supportive.learning import learn
from supportive.tasks.htn import HTN, ActionNode, ChainNode


@pytest.mark.parametrize("name", examples.names())
def test_json_round_trip(name: str) -> None:
    learner = learn(examples.load(name))
    data = json.loads(json.dumps(htn_to_dict(learner.htn_, learner.stats_.as_dict())))
    assert set(data) >= {"task", "complete", "roots", "alternatives", "stats"}
    assert set(data["stats"]) == {"demonstrations", "actions", "task_graph", "ctg", "htn", "seconds"}
    back = htn_from_dict(data)
    assert back.canonical() == learner.htn_.canonical()
    assert back.top_level == learner.htn_.top_level
    assert [a.canonical() for a in back.alternatives] == [a.canonical() for a in learner.htn_.alternatives]
    assert [getattr(r, "name", None) for r in back.roots] == [
        getattr(r, "name", None) for r in learner.htn_.roots
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
