"""Transfer, the explorer: an ε-greedy Q-learning agent discovering a task's SMDP (§2.1.7.4, Figure 2.6).

**The task SMDP.** A state is the set of the task's actions completed so far (a bitmask; every action of a
transfer task occurs once). An episode starts from the empty state. At each state the agent picks one option
of its dictionary: a primitive action (the 39 shared ones) or, in condition (c), a macro action (a subtask
performed as a sequence of primitives). A primitive that the task allows next
(:func:`~supportive.tasks.htn.allowed_next`) advances the state; any other primitive *fails*: the step is
spent and the state does not change. A macro performs one of its sequences in order and stops at the first
action that is not allowed (that one fails): a macro with several sequences (a clique's, performing any
admissible order of its subtask) draws one uniformly each time it is chosen, from the run's generator. An episode ends when the
task is complete or after ``step_cap`` primitive attempts (a macro spends one attempt per action it tries).

**Rewards.** ``FAIL`` (−1) for a failed primitive; ``STEP`` (−0.01) for a valid one, plus ``NOVELTY`` (+1)
when the agent has never performed that transition (state, action) before, plus ``COMPLETION`` (+1) when it
completes the task along an ordering never completed before. Only discoveries pay: once a part of the task is
known its Q values sink below 0 (the step cost), below the 0 of options never tried at a state, so the greedy
choice pushes toward what is still unexplored; ε adds random options. A macro's reward is the discounted sum of its primitives' rewards, and its Q-learning update uses
``γ^k`` for the k primitives it tried (the SMDP update).

**The agent.** Q-learning (``ALPHA`` 0.5, ``GAMMA`` 0.9), ε-greedy (``EPSILON`` 0.1): with probability ε a
uniformly random option, else one of the options of highest Q (ties broken uniformly at random). Q rows are
created lazily, the first time a state is reached, from the *initial values* of the state's feature: the last
action performed (``START`` at the empty state). No transfer means all zeros; with transfer they come from
:mod:`.sources`.

**Full task comprehension.** The completed episodes' primitive paths are added to a
:class:`~supportive.tasks.task_graph.TaskGraph`; the task is comprehended when that graph has as many paths as
the task has valid orderings (:func:`~supportive.tasks.htn.count_orderings`) — every valid transition of the
task's state space then lies on an observed complete execution. The measure is the number of episodes
(iterations) until then, or ``None`` when ``max_episodes`` pass first (censored).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from supportive.errors import ExperimentError
from supportive.seeding import Seed, stdlib_random
from supportive.tasks.htn import Node, allowed_next, count_orderings, leaf_actions, to_leaves
from supportive.tasks.task_graph import TaskGraph

__all__ = [
    "ALPHA",
    "COMPLETION",
    "EPSILON",
    "FAIL",
    "GAMMA",
    "NOVELTY",
    "START",
    "ActionSequence",
    "ExplorationResult",
    "Option",
    "TaskModel",
    "execute",
    "explore",
]

ALPHA = 0.5
"""Q-learning rate."""
GAMMA = 0.9
"""Discount per primitive step."""
EPSILON = 0.1
"""Probability of a uniformly random option."""
FAIL = -1.0
"""Reward of a primitive the task does not allow next."""
STEP = -0.01
"""Reward of a valid primitive (a small cost of acting)."""
NOVELTY = 1.0
"""Extra reward of a valid transition never performed before."""
COMPLETION = 1.0
"""Extra reward of the primitive that completes the task along an ordering never completed before."""
START = "<start>"
"""The feature of the empty state (no last action)."""

ActionSequence = tuple[str, ...]
Option = tuple[ActionSequence, ...]
"""An entry of the agent's dictionary, as the action sequences it may perform: a primitive ``((a,),)``, a
macro that always runs one order ``((a, b, c),)``, or one that runs any of its admissible orders
``((a, b, c), (a, c, b))`` (one drawn uniformly each time)."""


@dataclass(frozen=True)
class TaskModel:
    """A task's state space: bitmask states over its actions and what each allows next.

    Attributes:
        name: The task's name.
        actions: Its action ids; bit ``i`` of a state stands for ``actions[i]``.
        allowed: State -> {action id: bit} of the actions allowed next (every reachable state).
        full: The complete state.
        orderings: Number of valid orderings.
    """

    name: str
    actions: tuple[str, ...]
    allowed: Mapping[int, Mapping[str, int]]
    full: int
    orderings: int

    @classmethod
    def from_structure(cls, name: str, structure: Node) -> TaskModel:
        """Enumerate the reachable states of ``structure`` (each action once).

        >>> from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode
        >>> model = TaskModel.from_structure("t", ChainNode((ActionNode("a"), CliqueNode((ActionNode("b"),
        ...     ActionNode("c"))))))
        >>> len(model.allowed), model.orderings
        (5, 2)
        """
        actions = leaf_actions(structure)
        if len(set(actions)) != len(actions):
            raise ExperimentError(f"task {name}: an action occurs more than once")
        bit = {a: 1 << i for i, a in enumerate(actions)}
        allowed: dict[int, dict[str, int]] = {}
        frontier = [0]
        while frontier:
            state = frontier.pop()
            if state in allowed:
                continue
            done = to_leaves(a for a in actions if state & bit[a])
            nxt = {a: bit[a] for a, _ in sorted(allowed_next(structure, done))}
            allowed[state] = nxt
            frontier.extend(state | b for b in nxt.values())
        return cls(name, actions, allowed, (1 << len(actions)) - 1, count_orderings(structure))


@dataclass(frozen=True)
class Step:
    """What executing one option did."""

    state: int
    performed: tuple[str, ...]
    reward: float
    tried: int
    last: str


def execute(
    model: TaskModel,
    state: int,
    option: ActionSequence,
    seen: set[tuple[int, str]],
    last: str,
    path: list[str],
    paths: set[tuple[str, ...]],
) -> Step:
    """Perform the action sequence ``option`` from ``state``: its primitives in order, stopping after the first one the task does
    not allow (which fails) or when the task is complete. ``seen`` (valid transitions performed so far) and
    ``path`` (the episode's primitives so far) are updated; ``last`` is the last action performed before;
    ``paths`` holds the orderings completed before.

    >>> from supportive.tasks.htn import ActionNode, ChainNode
    >>> m = TaskModel.from_structure("t", ChainNode((ActionNode("a"), ActionNode("b"), ActionNode("c"))))
    >>> step = execute(m, 0, ("a", "c", "b"), set(), START, [], set())
    >>> step.performed, step.tried, step.reward
    (('a',), 2, 0.09)
    """
    reward = 0.0
    discount = 1.0
    performed: list[str] = []
    tried = 0
    for action in option:
        tried += 1
        bit = model.allowed[state].get(action)
        if bit is None:
            reward += discount * FAIL
            break
        r = STEP
        if (state, action) not in seen:
            seen.add((state, action))
            r += NOVELTY
        state |= bit
        performed.append(action)
        path.append(action)
        last = action
        if state == model.full:
            if tuple(path) not in paths:
                r += COMPLETION
            reward += discount * r
            break
        reward += discount * r
        discount *= GAMMA
    return Step(state, tuple(performed), round(reward, 12), tried, last)


@dataclass(frozen=True)
class ExplorationResult:
    """One exploration run.

    Attributes:
        episodes: Episodes until full comprehension, ``None`` when censored at ``max_episodes``.
        episodes_run: Episodes run (``episodes`` or ``max_episodes``).
        completed: Episodes that completed the task.
        paths_found: Distinct valid orderings observed as complete episodes.
        paths_known: Paths of the completed episodes' task graph at the end.
        orderings: Valid orderings of the task.
        macro_uses: Macro options chosen.
        steps: Primitive attempts in all.
    """

    episodes: int | None
    episodes_run: int
    completed: int
    paths_found: int
    paths_known: int
    orderings: int
    macro_uses: int
    steps: int


def explore(
    model: TaskModel,
    options: Sequence[Option],
    seed: Seed,
    *,
    initial: Mapping[str, Sequence[float]] | None = None,
    max_episodes: int = 5000,
    step_cap: int = 400,
    epsilon: float = EPSILON,
) -> ExplorationResult:
    """Run ε-greedy Q-learning episodes on ``model`` until full comprehension or ``max_episodes``.

    Args:
        model: The task.
        options: The agent's dictionary (primitives and macros, each as the sequences it may perform).
        seed: The run's random numbers (see :func:`~supportive.seeding.stdlib_random`).
        initial: Feature (last action, or :data:`START`) -> initial Q values, one per option; missing
            features start at 0 (no transfer: ``None``).
        max_episodes: Episodes before giving up (censored).
        step_cap: Primitive attempts per episode.
        epsilon: Probability of a random option.
    """
    rng = stdlib_random(seed)
    n = len(options)
    zeros = [0.0] * n
    initial = initial or {}
    q: dict[int, list[float]] = {}
    seen: set[tuple[int, str]] = set()
    graph = TaskGraph()
    paths: set[tuple[str, ...]] = set()
    completed = macro_uses = steps = 0
    is_macro = [len(o[0]) > 1 for o in options]

    def row(state: int, last: str) -> list[float]:
        values = q.get(state)
        if values is None:
            values = q[state] = list(initial.get(last, zeros))
        return values

    for episode in range(1, max_episodes + 1):
        state, last, spent = 0, START, 0
        path: list[str] = []
        values = row(state, last)
        while state != model.full and spent < step_cap:
            if rng.random() < epsilon:
                choice = rng.randrange(n)
            else:
                best = max(values)
                ties = [i for i, v in enumerate(values) if v >= best - 1e-12]
                choice = ties[0] if len(ties) == 1 else ties[rng.randrange(len(ties))]
            macro_uses += is_macro[choice]
            sequences = options[choice]
            sequence = sequences[0] if len(sequences) == 1 else sequences[rng.randrange(len(sequences))]
            step = execute(model, state, sequence, seen, last, path, paths)
            spent += step.tried
            if step.state == model.full:
                target = step.reward
                nxt = values
            else:
                nxt = row(step.state, step.last)
                target = step.reward + GAMMA**step.tried * max(nxt)
            values[choice] += ALPHA * (target - values[choice])
            state, last, values = step.state, step.last, nxt
        steps += spent
        if state == model.full:
            completed += 1
            key = tuple(path)
            if key not in paths:
                paths.add(key)
                if graph.add(key).changed and graph.path_count() >= model.orderings:
                    return ExplorationResult(
                        episode, episode, completed, len(paths), graph.path_count(), model.orderings,
                        macro_uses, steps,
                    )  # fmt: skip
    known = graph.path_count() if paths else 0
    return ExplorationResult(
        None, max_episodes, completed, len(paths), known, model.orderings, macro_uses, steps
    )
