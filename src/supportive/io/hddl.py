"""A learned HTN as HDDL (the hierarchical PDDL of IPC 2020): written, read and solved with unified-planning.

The encoding is totally ordered, so no planner can interleave the children of a clique:

* every leaf ``(action, occurrence)`` is a primitive action of its own (``stir``, ``stir_2``, …) that needs
  ``(not (done_<leaf>))``, and the leaf's previous occurrence done, and adds ``(done_<leaf>)``;
* a chain is a compound task with one method whose ordered subtasks are its children;
* a clique ``Q`` has, per child, a method "child not started yet → [child, Q]" and a method "every required
  child done → []" that ends the recursion (a child has started when one of the leaves it can begin with is
  done);
* an optional node ``X`` is a compound task of its own with two methods: ``[X]`` and ``[]`` (skip it);
* a partial hierarchy's top level is a state machine: one task per state, one method per edge
  ``(s, root, s')`` with ordered subtasks ``[root, s']`` and an empty method for each terminal state;
* the problem's ``:goal`` is what every plan achieves: every leaf that no execution skips is done (it cuts no
  plan of the task network; a hierarchy whose every part may be skipped has no ``:goal``).

unified-planning is an optional dependency (the ``planning`` extra); it is imported only when needed.
"""

from __future__ import annotations

import importlib.util
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.errors import ExportError, FileFormatError
from supportive.io.atomic import atomic_write, uninterrupted
from supportive.tasks.htn import HTN, ActionNode, ChainNode, Leaf, Node, first_leaves, nullable

__all__ = ["hddl_strings", "htn_to_problem", "read_hddl", "solve_hddl", "write_hddl"]

_MISSING = "HDDL export needs the 'planning' extra: pip install 'supportive[planning]'"
_LEAVES = "_supportive_leaves"  # set on an exported problem: HDDL action name -> leaf
_HDDL_WORDS = frozenset(
    {"task", "tasks", "method", "htn", "subtasks", "ordered-subtasks", "ordered-tasks", "ordering", "object"}
)


def _require_up(*, planner: bool = False) -> None:
    """Raise ``ExportError`` unless unified-planning (and, for ``planner``, up-aries) can be imported."""
    needed = ["unified_planning", "up_aries"] if planner else ["unified_planning"]
    if any(importlib.util.find_spec(module) is None for module in needed):
        raise ExportError(_MISSING)
    from unified_planning.shortcuts import get_environment

    get_environment().credits_stream = None


class _Namer:
    """Hands out unique HDDL identifiers: lowercase letters, digits, ``_`` and ``-``; a letter first."""

    def __init__(self) -> None:
        from unified_planning.io.pddl_writer import PDDL3_KEYWORDS, PDDL_PLUS_KEYWORDS

        self.taken: set[str] = set(PDDL3_KEYWORDS | PDDL_PLUS_KEYWORDS | _HDDL_WORDS)

    def __call__(self, text: str) -> str:
        base = re.sub(r"[^a-z0-9_-]+", "_", text.lower()).strip("_-") or "x"
        if not base[0].isalpha():
            base = f"x_{base}"
        name, k = base, 1
        while name in self.taken:
            k += 1
            name = f"{base}_{k}"
        self.taken.add(name)
        return name


def _leaf_names(htn: HTN, namer: _Namer) -> dict[Leaf, str]:
    """The HDDL action of every leaf; named first, so they get the plainest names."""
    if len(set(htn.leaves)) != len(htn.leaves):
        raise ExportError(f"task {htn.task or '?'}: a leaf occurs twice in the HTN; it cannot be exported")
    return {leaf: namer(leaf[0] if leaf[1] == 1 else f"{leaf[0]}_{leaf[1]}") for leaf in htn.leaves}


class _Builder:
    """Builds the ``HierarchicalProblem`` of one HTN (see the module docstring for the encoding)."""

    def __init__(self, htn: HTN) -> None:
        import unified_planning.shortcuts as up
        from unified_planning.model.htn import HierarchicalProblem

        self.up = up
        self.namer = _Namer()
        self.leaf_names = _leaf_names(htn, self.namer)
        self.problem: Any = HierarchicalProblem(self.namer(htn.task or "task"))
        self.done: dict[Leaf, Any] = {}
        self.actions: dict[Leaf, Any] = {}
        for leaf, name in self.leaf_names.items():
            fluent = up.Fluent(self.namer(f"done_{name}"), up.BoolType())
            self.problem.add_fluent(fluent, default_initial_value=False)
            self.done[leaf] = fluent()
        skippable = {leaf for root in htn.roots for leaf in _skippable(root, False)}
        for leaf, name in self.leaf_names.items():
            action = up.InstantaneousAction(name)
            action.add_precondition(up.Not(self.done[leaf]))
            previous = (leaf[0], leaf[1] - 1)
            if previous in self.done and previous not in skippable:  # occurrences are numbered in order
                action.add_precondition(self.done[previous])
            action.add_effect(self.done[leaf], True)
            self.problem.add_action(action)
            self.actions[leaf] = action
        self.problem.task_network.add_subtask(self._top(htn), ident="s1")
        required = [self.done[leaf] for leaf in htn.required_leaves]
        if required:  # true after every plan of the task network: it says what a plan achieves, cuts none
            self.problem.add_goal(up.And(*required))
        setattr(self.problem, _LEAVES, {name: leaf for leaf, name in self.leaf_names.items()})

    def _node(self, node: Node) -> Any:
        """The action or compound task that performs ``node`` (a task that may skip it, when optional)."""
        performed = self._performed(node)
        if not node.optional:
            return performed
        name = node.label if isinstance(node, ActionNode) else (node.name or node.kind)
        task = self.problem.add_task(self.namer(f"optional_{name}"))
        self._method(task, "do", [performed])
        self._method(task, "skip", [])
        return task

    def _performed(self, node: Node) -> Any:
        if isinstance(node, ActionNode):
            return self.actions[node.leaf]
        task = self.problem.add_task(self.namer(node.name or node.kind))
        if isinstance(node, ChainNode):
            self._method(task, "in_order", [self._node(child) for child in node.children])
            return task
        # a clique may end without its optional children, so each child's method performs it outright
        children = [self._performed(child) for child in node.children]
        up = self.up
        for child, target in zip(node.children, children, strict=True):
            # Children run as blocks, so the leaves it can begin with tell whether a child has started.
            self._method(task, f"{target.name}_next", [target, task], up.Not(self._started(child)))
        required = [self._started(child) for child in node.children if not nullable(child)]
        self._method(task, "all_done", [], up.And(*required) if required else None)
        return task

    def _started(self, node: Node) -> Any:
        return self.up.Or(*(self.done[leaf] for leaf in sorted(first_leaves(node))))

    def _top(self, htn: HTN) -> Any:
        """The task the initial task network performs."""
        top = htn.top_level
        if top is None:
            if len(htn.roots) != 1:
                raise ExportError(
                    f"task {htn.task or '?'}: {len(htn.roots)} roots but no top level to order them"
                )
            return self._node(htn.roots[0])
        if any(not 0 <= root < len(htn.roots) for _, root, _ in top.edges):
            raise ExportError(f"task {htn.task or '?'}: a top-level edge names a root that does not exist")
        roots = [self._node(root) for root in htn.roots]
        states = sorted({*top.initial, *top.terminal, *(state for edge in top.edges for state in edge[::2])})
        tasks = {state: self.problem.add_task(self.namer(f"state_{state}")) for state in states}
        for src, root, dst in top.edges:
            self._method(tasks[src], roots[root].name, [roots[root], tasks[dst]])
        for state in top.terminal:
            self._method(tasks[state], "end", [])
        if len(top.initial) == 1:
            return tasks[top.initial[0]]
        start = self.problem.add_task(self.namer("start"))
        for state in top.initial:
            self._method(start, f"from_state_{state}", [tasks[state]])
        return start

    def _method(self, task: Any, label: str, subtasks: list[Any], precondition: Any = None) -> None:
        from unified_planning.model.htn import Method

        method = Method(self.namer(f"{task.name}_{label}"))
        method.set_task(task)
        if precondition is not None:
            method.add_precondition(precondition)
        steps = [method.add_subtask(subtask, ident=f"s{i}") for i, subtask in enumerate(subtasks, 1)]
        method.set_ordered(*steps)
        self.problem.add_method(method)


def _skippable(node: Node, inside_optional: bool) -> list[Leaf]:
    """The leaves under ``node`` that an execution may skip (one of their ancestors, or they, optional)."""
    skipped = inside_optional or node.optional
    if isinstance(node, ActionNode):
        return [node.leaf] if skipped else []
    return [leaf for child in node.children for leaf in _skippable(child, skipped)]


def htn_to_problem(htn: HTN) -> Any:
    """The HTN as a unified-planning ``HierarchicalProblem``.

    Args:
        htn: A complete hierarchy (one root) or a partial one with its ``top_level``.

    Returns:
        The problem; its primitive plans are exactly the leaf orders ``htn`` admits.

    Raises:
        ExportError: when unified-planning is not installed, or the HTN has several roots and no top level
            or a leaf twice.
    """
    _require_up()
    return _Builder(htn).problem


def hddl_strings(htn: HTN) -> tuple[str, str]:
    """The HDDL domain and problem texts of ``htn`` (see :func:`htn_to_problem`)."""
    problem = htn_to_problem(htn)
    from unified_planning.io import PDDLWriter

    writer = PDDLWriter(problem)
    text = writer.get_problem()
    return writer.get_domain(), re.sub(r"\n \(:goal \(and\s*\)\s*\)", "", text)  # nothing every plan achieves: no goal


def write_hddl(htn: HTN, directory: str | Path) -> tuple[Path, Path]:
    """Write ``domain.hddl`` and ``problem.hddl`` into ``directory`` (created if missing).

    Both texts are produced before anything is written, and each file is written atomically (mode and symlinks
    kept), Ctrl-C held back until both are, so a failed or interrupted export leaves no half-written file and
    no domain without its problem.

    Returns:
        The paths of the domain and problem files.

    Raises:
        ExportError: as :func:`htn_to_problem`; when ``directory`` is a file or cannot be written.
    """
    folder = Path(directory)
    if folder.exists() and not folder.is_dir():
        raise ExportError(f"{folder}: is a file, not a directory: HDDL export writes domain.hddl and problem.hddl into a directory")
    domain, problem = hddl_strings(htn)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ExportError(f"{folder}: cannot make the directory: {exc.strerror}") from None
    paths = folder / "domain.hddl", folder / "problem.hddl"
    fresh = not paths[0].exists()
    try:
        with uninterrupted():  # Ctrl-C never leaves a new domain beside an old problem
            atomic_write(paths[0], domain)
            atomic_write(paths[1], problem)
    except FileFormatError as exc:
        if fresh:  # never leave a domain without its problem
            paths[0].unlink(missing_ok=True)
        raise ExportError(str(exc)) from None
    return paths


def read_hddl(domain_path: str | Path, problem_path: str | Path) -> Any:
    """Parse an HDDL domain and problem with unified-planning's reader.

    Returns:
        The ``HierarchicalProblem``.

    Raises:
        ExportError: when unified-planning is missing, the files cannot be parsed or hold no HTN problem.
    """
    _require_up()
    from unified_planning.io import PDDLReader
    from unified_planning.model.htn import HierarchicalProblem

    try:
        problem = PDDLReader().parse_problem(str(domain_path), str(problem_path))
    except Exception as exc:  # the reader raises pyparsing, UP and OS errors alike
        raise ExportError(f"{domain_path}, {problem_path}: cannot read HDDL: {exc}") from exc
    if not isinstance(problem, HierarchicalProblem):
        raise ExportError(f"{domain_path}, {problem_path}: not a hierarchical (HDDL) problem")
    return problem


def solve_hddl(problem: Any, htn: HTN | None = None, *, timeout: float | None = 60.0) -> list[str] | None:
    """Solve a hierarchical problem with the Aries planner.

    Args:
        problem: From :func:`htn_to_problem` or :func:`read_hddl`.
        htn: The HTN the problem was exported from. Needed to map a problem read back from files to action
            ids; a problem from :func:`htn_to_problem` carries that mapping itself. Without either, the plan
            keeps its HDDL action names.
        timeout: Seconds to give the planner (``None``: no limit). Aries cannot prove that a recursive
            hierarchy (any clique) has no plan, so it searches until the timeout.

    Returns:
        The primitive plan as the original action ids (a repeated action appears once per performance), or
        ``None`` when no plan was found (unsolvable or out of time).

    Raises:
        ExportError: when the planning extra is missing, the planner fails or a plan step is no leaf of
            ``htn``.
    """
    _require_up(planner=True)
    from unified_planning.engines import PlanGenerationResultStatus as Status
    from unified_planning.shortcuts import OneshotPlanner

    with OneshotPlanner(name="aries") as planner:
        result = planner.solve(problem, timeout=timeout)
    if result.status in (Status.INTERNAL_ERROR, Status.UNSUPPORTED_PROBLEM):
        raise ExportError(f"the Aries planner failed ({result.status.name}): {result.log_messages}")
    if result.plan is None:
        return None
    plan = getattr(result.plan, "action_plan", result.plan)
    steps = [step.action.name for step in plan.actions]
    leaves: Mapping[str, Leaf] | None = getattr(problem, _LEAVES, None)
    if htn is not None:
        leaves = {name: leaf for leaf, name in _leaf_names(htn, _Namer()).items()}
    if leaves is None:
        return steps
    unknown = [step for step in steps if step not in leaves]
    if unknown:
        raise ExportError(f"plan steps {unknown} are not leaves of task {htn.task if htn else '?'}")
    return [leaves[step][0] for step in steps]
