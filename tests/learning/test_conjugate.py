from __future__ import annotations

import itertools

from supportive.learning.strict.conjugate import conjugate_task_graph, update_conjugate
from supportive.tasks.conjugate import ORIGIN, TERMINAL, ConjugateTaskGraph
from supportive.tasks.task_graph import TaskGraph


def _edges(ctg: ConjugateTaskGraph) -> set[tuple[str, str, tuple[str, ...]]]:
    return {(ctg.label(e.source), ctg.label(e.target), tuple(sorted(e.prerequisites))) for e in ctg.edges()}


def test_figure_2_8_knife_carrots_celery() -> None:
    graph = TaskGraph()
    graph.add(["knife", "carrots", "celery"])
    graph.add(["knife", "celery", "carrots"])
    assert _edges(conjugate_task_graph(graph)) == {
        ("origin", "knife", ()),
        ("knife", "carrots", ("knife",)),
        ("knife", "celery", ("knife",)),
        ("carrots", "celery", ("carrots", "knife")),
        ("celery", "carrots", ("celery", "knife")),
        ("carrots", "terminal", ("carrots", "celery", "knife")),
        ("celery", "terminal", ("carrots", "celery", "knife")),
    }


def test_redundant_edges_keep_minimal_prerequisites() -> None:
    graph = TaskGraph()
    graph.add(["a", "x", "b", "c"])  # x -> b with {a, x}
    graph.add(["x", "b", "a", "c"])  # x -> b with {x}: makes {a, x} redundant
    ctg = conjugate_task_graph(graph)
    x, b = graph.subgoal_index(("x", 1)), graph.subgoal_index(("b", 1))
    assert x is not None and b is not None
    assert [ctg.prerequisites(s) for s in ctg.prerequisite_states(x, b)] == [frozenset({"x"})]
    assert ctg.successors(ORIGIN) == {graph.subgoal_index(("a", 1)), x}
    c = graph.subgoal_index(("c", 1))
    assert c is not None and TERMINAL in ctg.successors(c)


def test_incremental_equals_batch() -> None:
    orders = list(itertools.permutations("abcd"))[::5]
    incremental = TaskGraph()
    ctg = conjugate_task_graph(incremental)
    for order in orders:
        update_conjugate(ctg, incremental.add(list(order)))
    batch = TaskGraph()
    for order in orders:
        batch.add(list(order))
    assert _edges(ctg) == _edges(conjugate_task_graph(batch))
    assert ctg.n_edges == conjugate_task_graph(batch).n_edges


def test_networkx_view_has_prerequisites() -> None:
    graph = TaskGraph()
    graph.add(["a", "b"])
    nxg = conjugate_task_graph(graph).to_networkx()
    assert nxg.number_of_nodes() == 4
    assert {tuple(d["prerequisites"]) for _, _, d in nxg.edges(data=True)} == {(), ("a",), ("a", "b")}
