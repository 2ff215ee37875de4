"""examples/workbench-blocks.yaml: the thesis's construction task (§3.4.5, Figure 3.9)."""

from __future__ import annotations

import itertools
import json
from collections.abc import Callable

from supportive import examples
from supportive.io.htn_json import htn_from_dict
from supportive.learning import learn
from supportive.tasks.htn import ChainNode, CliqueNode, canonical, iter_orderings

CliRunner = Callable[[list[str]], tuple[int, str, str]]

TABLE = (1.83, 0.762)


def _valid(order: tuple[str, ...]) -> bool:
    """The task's real precedence: each branch in order, and the blue block pushed before red is placed."""
    at = {a: i for i, a in enumerate(order)}
    return (
        at["locate_blue"] < at["push_blue"] < at["rest_blue"]
        and at["pick_red"] < at["place_red"] < at["rest_red"]
        and at["push_blue"] < at["place_red"]
    )


def test_the_demonstrations_learn_the_intended_hierarchy() -> None:
    spec = examples.load("workbench-blocks")
    htn = learn(spec, mode="strict").htn_  # three demonstrations: the reading that commits to what it saw
    assert htn.complete and htn.alternatives == ()
    assert spec.structure is not None and canonical(htn.roots[0]) == canonical(spec.structure)
    assert isinstance(htn.roots[0], ChainNode | CliqueNode) and htn.roots[0].name == "Join the bases under the red top"


def test_the_structure_admits_only_valid_orders_and_both_first_actions() -> None:
    structure = examples.load("workbench-blocks").structure
    assert structure is not None
    orders = [tuple(a for a, _ in o) for o in iter_orderings(structure)]
    assert all(_valid(o) for o in orders)
    assert {o[0] for o in orders} == {"locate_blue", "pick_red"}  # either branch may start
    assert len(orders) == 2
    # the real precedence allows more (interleaved) orders: no chain/clique structure holds exactly them
    actions = ("locate_blue", "push_blue", "rest_blue", "pick_red", "place_red", "rest_red")
    assert sum(_valid(o) for o in itertools.permutations(actions)) == 10


def test_every_action_has_keyframes_on_the_table_and_one_goal() -> None:
    spec = examples.load("workbench-blocks")
    for action in spec.actions:
        assert action.keyframes, action.id
        assert all(0 <= k.x <= TABLE[0] and 0 <= k.y <= TABLE[1] for k in action.keyframes)
        assert [k.goal for k in action.keyframes] == [False] * (len(action.keyframes) - 1) + [True]


def test_the_cli_learns_it(cli: CliRunner) -> None:
    code, out, _ = cli(["learn", str(examples.path("workbench-blocks")), "--format", "json", "--mode", "strict"])
    assert code == 0
    htn = htn_from_dict(json.loads(out))
    assert htn.complete
    assert htn.roots[0].kind == "chain" and [c.kind for c in htn.roots[0].children] == ["clique", "action", "action"]


def test_the_general_learner_keeps_the_valid_orders_of_three_demonstrations() -> None:
    spec = examples.load("workbench-blocks")
    htn = learn(spec).htn_
    assert all(htn.admits(d) for d in spec.action_sequences())
    assert not htn.admits(["rest_blue", "push_blue", "locate_blue", "pick_red", "place_red", "rest_red"])
