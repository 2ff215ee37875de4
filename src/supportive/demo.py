"""``supportive demo``: learn the IKEA chair from its demonstrations and say what the data did and did not pin
down, against the ground truth in the task file."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from rich.console import Console
from rich.markup import escape
from rich.panel import Panel
from rich.table import Table

from supportive import examples
from supportive.errors import LearningError
from supportive.inference import ObservationModel, ProgressHMM
from supportive.io.tables import fitted_table
from supportive.io.tree import htn_tree
from supportive.learning.active import QuerySchedule, TeachingSession, run_session
from supportive.learning.instructors import SimulatedInstructor
from supportive.learning.learner import HTNLearner, learn
from supportive.learning.precedence import implied_precedences
from supportive.safety.episode import Frame, run_episode
from supportive.safety.render import LEGEND, render_frame
from supportive.tasks.htn import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Leaf,
    canonical,
    count_orderings,
    internal_nodes,
    to_leaves,
)
from supportive.tasks.naming import known_names
from supportive.tasks.spec import TaskSpec
from supportive.teach import ask_in_words
from supportive.worlds.household import Collision, load_map

__all__ = [
    "CaregiverContrast",
    "SubtaskFinding",
    "TeachingOutcome",
    "WatchedStep",
    "caregiver_contrast",
    "keep_novice_safe",
    "rearrange_the_table",
    "run_demo",
    "subtask_findings",
    "talk_about_helping",
    "teach_tower",
    "teach_with_questions",
    "watch",
    "watch_held_out",
]


@dataclass(frozen=True)
class SubtaskFinding:
    """Whether one ground-truth subtask was learned, and how many orders of its parts the data showed."""

    name: str
    kind: str
    learned: bool
    orders_seen: int
    orders_valid: int


def _child_orders(node: ChainNode | CliqueNode, demonstrations: list[tuple[Leaf, ...]]) -> int:
    """Distinct orders in which the demonstrations performed ``node``'s children (by first leaf)."""
    owner = {leaf: i for i, child in enumerate(node.children) for leaf in child.leaves}
    orders = set()
    for demo in demonstrations:
        order: list[int] = []
        for leaf in demo:
            child = owner.get(leaf)
            if child is not None and child not in order:
                order.append(child)
        orders.add(tuple(order))
    return len(orders)


def subtask_findings(spec: TaskSpec, htn: HTN) -> list[SubtaskFinding]:
    """For every subtask of the spec's ground-truth structure: learned exactly or not, and the evidence."""
    if spec.structure is None:
        return []
    learned = {canonical(node) for root in (htn.roots) for node in internal_nodes(root)}
    demos = [to_leaves(d) for d in spec.action_sequences()]
    findings = []
    for node in internal_nodes(spec.structure):
        valid = math.factorial(len(node.children)) if isinstance(node, CliqueNode) else 1
        findings.append(
            SubtaskFinding(
                name=node.name or "(unnamed)",
                kind=node.kind,
                learned=canonical(node) in learned,
                orders_seen=_child_orders(node, demos),
                orders_valid=valid,
            )
        )
    return findings


def _root_names(htn: HTN) -> dict[Leaf, str]:
    names = {}
    for root in htn.roots:
        label = root.label if isinstance(root, ActionNode) else (root.name or root.kind)
        for leaf in root.leaves:
            names[leaf] = label
    return names


def run_demo(console: Console, example: str = "ikea-chair") -> HTNLearner:
    """Print the demo to ``console`` and return the fitted learner."""
    spec = examples.load(example)
    learner = learn(spec)
    htn, stats = learner.htn_, learner.stats_
    people = sorted({d.agent for d in spec.demonstrations if d.agent})
    console.rule(f"[bold]supportive demo[/] — learning {spec.name} from its demonstrations")
    console.print(
        f"{len(spec.demonstrations)} demonstrations by {len(people)} people ({', '.join(people)}), "
        f"{stats.actions} primitive actions. The robot builds the environment-space task graph, its conjugate "
        "(Algorithm 1), and compacts cliques and chains into a hierarchy (Algorithm 2).\n"
    )
    console.print(htn_tree(htn, spec.texts()))
    valid = count_orderings(spec.structure) if spec.structure is not None else None
    table = Table(title="What the robot has seen", show_header=False, box=None)
    table.add_row(
        "known valid orders", f"{stats.task_graph['paths']:,}" + (f" of {valid:,}" if valid else "")
    )
    table.add_row(
        "task graph", f"{stats.task_graph['states']} states, {stats.task_graph['edges']} transitions"
    )
    table.add_row("conjugate task graph", f"{stats.ctg['vertices']} vertices, {stats.ctg['edges']} edges")
    table.add_row(
        "hierarchy",
        f"{stats.htn['nodes']} nodes, {len(htn.roots)} top-level part(s), "
        f"mean depth of an action {stats.htn['mean_action_depth']:.2f}",
    )
    table.add_row("learning time", f"{stats.seconds * 1000:.1f} ms")
    console.print(table)

    findings = subtask_findings(spec, htn)
    if findings:
        console.print("\n[bold]What the demonstrations pinned down[/] (against the file's ground truth)")
        for f in findings:
            mark = "[green]✓[/]" if f.learned else "[red]✗[/]"
            inferred = "inferred from " if f.learned and f.orders_seen < f.orders_valid else ""
            how = (
                "in order"
                if f.kind == "chain"
                else f"any order, {inferred}{f.orders_seen} of {f.orders_valid} orders seen"
            )
            console.print(f"  {mark} {f.name} ({how})")
    if not htn.complete and htn.top_level is not None:
        tops = htn.top_level.count_orderings()
        console.print(
            f"\n[bold]Still open:[/] {len(htn.roots)} top-level parts, seen in {tops} of their "
            f"{math.factorial(len(htn.roots)):,} conceivable orders."
        )
        if spec.structure is not None:
            truth = implied_precedences(HTN(spec.name, (spec.structure,)))
            wrong = implied_precedences(htn) - truth
            names = _root_names(htn)
            beliefs = sorted({(names[a], names[b]) for a, b in wrong if names[a] != names[b]})
            if beliefs:
                console.print(
                    "  The robot still believes these must come first, though the true task does not require it:"
                )
                for first, then in beliefs[:6]:
                    console.print(f"    • {first} before {then}")
                if len(beliefs) > 6:
                    console.print(f"    • … and {len(beliefs) - 6} more")
            missing = [f for f in findings if not f.learned and f.kind == "clique"]
            if missing:
                console.print(
                    "  A few more demonstrations showing "
                    + ", ".join(f"{f.name.lower()}" for f in missing)
                    + " in other orders would settle it."
                )
    if htn.alternatives:
        console.print(f"\n[bold]Alternative readings[/] ({len(htn.alternatives)}), best first:")
        for alternative in htn.alternatives[:3]:
            console.print(htn_tree(alternative, spec.texts()))
    if all(a.observations for a in spec.actions) and len(spec.demonstrations) > 1:
        watch_held_out(console, spec)
    teach_with_questions(console)
    talk_about_helping(console, spec)
    rearrange_the_table(console)
    keep_novice_safe(console)
    console.print(Panel.fit("Try it on your own task:  supportive learn my-task.yaml --format json"))
    return learner


@dataclass(frozen=True)
class WatchedStep:
    """What the robot believed at the last moment of one action of a watched demonstration."""

    truth: str
    subgoal: tuple[str, float]
    subtask: tuple[str, float]
    next_subgoal: tuple[str, float]


def watch(spec: TaskSpec, held_out: int = -1, seed: int = 7, mean_duration: float = 4.0) -> list[WatchedStep]:
    """Learn from every demonstration but one, then replay that one as a stream of contact events (drawn from
    the task's observation model) through the hierarchical HMM, and report the belief at the end of each action."""
    demos = list(spec.demonstrations)
    watched = demos.pop(held_out)
    htn = HTNLearner(names=known_names(spec.structure)).fit(demos, spec.name).htn_
    model = ObservationModel.from_spec(spec)
    running = ProgressHMM(htn, model, mean_duration=mean_duration).filter()
    rng = np.random.default_rng(seed)
    steps = []
    for action in watched.actions:
        for _ in range(int(rng.geometric(1.0 / mean_duration))):
            belief = running.update(model.sample(action, rng))
        steps.append(
            WatchedStep(
                truth=action,
                subgoal=running.top(belief.subgoals, running.subgoal_labels, 1)[0],
                subtask=running.top(belief.enclosing, running.enclosing_labels, 1)[0],
                next_subgoal=max(belief.next_actions.items(), key=lambda kv: (kv[1], kv[0])),
            )
        )
    return steps


@dataclass(frozen=True)
class TeachingOutcome:
    """A simulated teaching session: the questions asked and the valid orders the learner came to know."""

    strategy: str
    known_orders: int
    questions: tuple[tuple[int, int, str, bool | None], ...]


def teach_tower(strategy: str | None, demonstrations: int = 4, seed: int = 3) -> TeachingOutcome:
    """A simulated instructor (§2.2.10.1) teaches block task 1 (red, six blocks in any order, blue) for a few
    demonstrations, with the learner asking as in the pilot study (``strategy``) or never (None)."""
    spec = examples.load("blocks-tower")
    if spec.structure is None:
        raise LearningError("the bundled blocks-tower example lost its ground-truth structure")
    schedule = QuerySchedule.thesis(1) if strategy else QuerySchedule(after_steps=())
    session = TeachingSession(spec.action_ids(), strategy or "random", schedule, seed)
    run_session(session, SimulatedInstructor(spec.structure, seed=seed), demonstrations)
    questions = tuple((q.demonstration + 1, q.step, q.action, q.honoured) for q in session.queries)
    return TeachingOutcome(strategy or "none", session.learner.task_graph_.path_count(), questions)


def teach_with_questions(console: Console) -> None:
    """Print a short simulated teaching session with and without questions."""
    texts = examples.load("blocks-tower").texts()
    quiet, asking = teach_tower(None), teach_tower("distance")
    console.print(
        "\n[bold]Teaching with questions[/] (§2.2): a simulated person teaches the block tower (720 valid orders) "
        "four times. Without questions the robot comes to know "
        f"[bold]{quiet.known_orders}[/] valid orders; asking distance-based questions it knows "
        f"[bold]{asking.known_orders}[/]:"
    )
    for demonstration, step, action, honoured in asking.questions:
        answer = "yes" if honoured else "no, did something else"
        console.print(
            f"  demonstration {demonstration}, after step {step}: “{ask_in_words(action, texts)}” — {answer}"
        )


def watch_held_out(console: Console, spec: TaskSpec) -> None:
    """Print :func:`watch` as a table."""
    held_out = spec.demonstrations[-1]
    steps = watch(spec)
    console.print(
        f"\n[bold]Watching a teammate[/]: demonstration {held_out.id} ({held_out.agent or 'someone'}) was held out "
        "of learning and is replayed as contact events (which objects touch). After each action, the progress-aware "
        "tracker's belief about the current action, the subtask it belongs to, and what comes next (it knows what "
        "is done: never a done action, and <end> after the last):"
    )
    hits = 0
    rows = []
    for step in steps:
        right = step.subgoal[0] == step.truth
        hits += right
        rows.append(
            [
                step.truth,
                f"{step.subgoal[0]}{'' if right else ' (!)'}",
                f"{step.subgoal[1]:.2f}",
                step.subtask[0],
                f"{step.subtask[1]:.2f}",
                step.next_subgoal[0],
                f"{step.next_subgoal[1]:.2f}",
            ]
        )
    headers = ["truth", "believed action", "p", "subtask", "p", "expected next", "p"]
    console.print(fitted_table(console, "", headers, rows, numeric={2, 4, 6}))
    console.print(
        f"  right action at the end of {hits} of {len(steps)} actions; pegs, bolts and nuts look alike, so the "
        "subtask column is where the hierarchy earns its keep."
    )


@dataclass(frozen=True)
class CaregiverContrast:
    """One short household episode played twice from the same seed, with and without the caregiver.

    Attributes:
        map_name: The map played on.
        epsilon: The novice's share of random moves.
        steps: Novice steps per episode.
        with_caregiver: Damage with the caregiver; ``without``: damage alone.
        frames: The caregiver episode's frames around the first step where the two runs differ (or its first
            steps, when they never do).
        moment: That step, or None.
        bumps: What the novice bumped into at that step with and without the caregiver (None: nothing).
    """

    map_name: str
    epsilon: float
    steps: int
    with_caregiver: int
    without: int
    frames: tuple[Frame, ...]
    moment: int | None
    bumps: tuple[Collision | None, Collision | None] = (None, None)


def caregiver_contrast(
    map_name: str = "playroom", epsilon: float = 0.75, steps: int = 40, seed: int = 8
) -> CaregiverContrast:
    """Play a novice on ``map_name`` with and without the caregiver (common random numbers: the same seed gives
    the same start and first goal), and pick the frames where the caregiver first made a difference."""
    grid = load_map(map_name)
    helped = run_episode(grid, epsilon, caregiver=True, steps=steps, seed=seed, record=True)
    alone = run_episode(grid, epsilon, caregiver=False, steps=steps, seed=seed, record=True)
    moment = next(
        (a.step for a, b in zip(helped.frames, alone.frames, strict=True) if a.collision != b.collision), None
    )
    end = moment if moment is not None else 2
    frames = helped.frames[max(0, end - 2) : end]
    bumps = (
        (helped.frames[moment - 1].collision, alone.frames[moment - 1].collision)
        if moment is not None
        else (None, None)
    )
    return CaregiverContrast(map_name, epsilon, steps, helped.damage, alone.damage, frames, moment, bumps)


def _bump_words(collision: Collision | None) -> str:
    if collision is None:
        return "walked on"
    thing = "stairwell" if collision.kind == "stairs" else collision.kind
    return f"bumped into the {thing} at {collision.cell} (damage {collision.damage})"


def keep_novice_safe(console: Console) -> CaregiverContrast:
    """Print the caregiver section of the demo (§3.5): a few frames of a short episode and the damage with and
    without the caregiver."""
    contrast = caregiver_contrast()
    grid = load_map(contrast.map_name)
    console.print(
        f"\n[bold]Keeping a novice safe[/] (§3.5): a novice making {contrast.epsilon:.0%} random moves plays "
        f"{contrast.steps} steps in the {contrast.map_name}, once with the caregiver robot and once alone, from the "
        "same seed. The caregiver estimates P(safe | τ) from the novice's moves, the damage each hazard threatens, "
        f"and acts on the best trade of benefit against time ({LEGEND}):"
    )
    for frame in contrast.frames:
        console.print(render_frame(grid, frame, steps=contrast.steps))
    if contrast.moment is not None:
        helped, alone = contrast.bumps
        console.print(
            f"  At step {contrast.moment} the novice {_bump_words(helped)}; alone, it {_bump_words(alone)}."
        )
    console.print(
        f"  damage over {contrast.steps} steps: [bold]{contrast.with_caregiver}[/] with the caregiver, "
        f"[bold]{contrast.without}[/] without. Watch a whole episode: supportive caregiver --map house --novice 0.5"
    )
    return contrast


CHAT_SCRIPT: tuple[str, ...] = (
    "How will you help me screw the seat?",
    "When I am tightening the bolts, I want you to shine a light on the bolt until the rear left bolt is tight",
    "When will you hold the seat?",
)
"""What the person says in the demo's dialogue (§3.3)."""


def talk_about_helping(console: Console, spec: TaskSpec) -> list[tuple[str, str]]:
    """Print the dialogue section of the demo (§3.3): a person asks how the robot will help, states a new
    preference (the robot grounds it, asks to confirm, and says back what it will do) and asks about a behavior.
    Nothing is saved. Returns the exchange as (who, what) pairs."""
    from dataclasses import replace

    from supportive.language.explain import explain_behavior, explain_subtask
    from supportive.language.grammar import ExplainBehavior, ExplainSubtask, Preference, parse_utterance
    from supportive.language.states import TaskStates
    from supportive.language.understand import Understanding

    if not spec.behaviors or spec.structure is None:
        return []
    states = TaskStates.of(spec)
    understanding = Understanding(states)
    exchange: list[tuple[str, str]] = []
    for line in CHAT_SCRIPT:
        exchange.append(("person", line))
        utterance = parse_utterance(line)
        if isinstance(utterance, ExplainSubtask):
            key = understanding.subtask_matcher.best(utterance.subtask_phrase).key
            exchange.append(("robot", explain_subtask(states, key).text))
        elif isinstance(utterance, ExplainBehavior):
            behavior = understanding.behavior_for(utterance.behavior_phrase)
            if behavior is not None:
                exchange.append(("robot", explain_behavior(states, behavior).text))
        elif isinstance(utterance, Preference):
            understood = understanding.apply(utterance)
            if not understood.confident:
                exchange.append(("robot", understood.confirmation))
                exchange.append(("person", "yes"))
            states = TaskStates.of(
                replace(spec, behaviors=(*spec.behaviors, understood.behavior)), states.structure
            )
            understanding = Understanding(states)
            exchange.append(("robot", f"OK. {explain_behavior(states, understood.behavior).text}"))
    console.print(
        "\n[bold]Asking for help, and hearing it explained[/] (§3.3): the chair's task file lists supportive "
        "behaviors, each with the states where it starts and stops. A person talks to the robot; it grounds what "
        "they say in the task's subtasks (Algorithm 6) and explains its policy with the smallest description of "
        "those states in the task's own words (Algorithm 7):"
    )
    for who, what in exchange:
        console.print(f"  [bold]{who}:[/] {escape(what)}")
    console.print("  Talk to it yourself: supportive chat examples/ikea-chair.yaml")
    return exchange


@dataclass(frozen=True)
class TableContrast:
    """A slow lead building the bundled circuit alone and with a fast support robot."""

    actions: tuple[str, ...]
    expected_saving: float
    alone: float
    supported: float
    support_actions: int


def rearrange_the_table(console: Console, scenario_name: str = "two-cells-led") -> TableContrast:
    """Print the support-planning section of the demo (§3.2): one decision of the support robot at the bundled
    circuit table, and the lead's makespan alone and supported. Returns what it showed."""
    from supportive.envs.circuits.advice import advise, describe_plan, simulate
    from supportive.envs.circuits.scenario import parse_scenario_file

    scenario = parse_scenario_file(examples.circuit_path(scenario_name))
    plans = scenario.plans()
    advice, _ = advise(scenario, plans)
    alone, helped = simulate(scenario, plans)
    console.print(
        "\n[bold]Helping without touching the goal[/] (§3.2): a slow lead builds a circuit (two cells in series "
        f"drive an LED through a switch) from {len(scenario.world.items)} pieces scattered on a table; the "
        "support robot may not touch the board. It samples single-piece moves, estimates how long each of the "
        f"{len(plans)} known plans would take after each (Algorithm 5), weights the plans and picks the best move:"
    )
    for line in advice.lines()[1:]:
        console.print(f"  {escape(line)}")
    quickest = describe_plan(plans[0])
    console.print(
        f"  Simulated with both arms moving at once (the lead follows the quickest plan, {quickest}): alone "
        f"{alone.makespan:.1f} s, supported {helped.makespan:.1f} s after {helped.support_actions} supportive "
        f"actions ({100 * (1 - helped.makespan / alone.makespan):.0f} % faster)."
    )
    console.print(
        "  Try it: supportive support two-cells-led --simulate --render table.png;"
        " supportive reproduce support-tamp --workers 2"
    )
    return TableContrast(
        advice.actions, advice.expected_saving, alone.makespan, helped.makespan, helped.support_actions
    )
