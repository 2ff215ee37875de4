"""``supportive demo``: learn the IKEA chair from its demonstrations and say what the data did and did not pin
down, against the ground truth in the task file."""

from __future__ import annotations

import math
from dataclasses import dataclass

from rich.console import Console
from rich.markup import escape
from rich.panel import Panel
from rich.table import Table

from supportive import examples
from supportive.cli.teach_console import ask_in_words
from supportive.errors import LearningError
from supportive.evaluation.findings import subtask_findings
from supportive.evaluation.replay import watch
from supportive.learning.active import QuerySchedule, TeachingSession, run_session
from supportive.learning.instructors import SimulatedInstructor
from supportive.learning.learner import HTNLearner, learn
from supportive.learning.precedence import implied_precedences
from supportive.render.household import LEGEND, render_frame
from supportive.render.tables import fitted_table
from supportive.render.tree import htn_tree
from supportive.safety.contrast import CaregiverContrast, caregiver_contrast
from supportive.tasks.htn import (
    HTN,
    ActionNode,
    Leaf,
    count_orderings,
)
from supportive.tasks.spec import TaskSpec
from supportive.worlds.household import Collision, load_map

__all__ = [
    "TeachingOutcome",
    "keep_novice_safe",
    "rearrange_the_table",
    "run_demo",
    "talk_about_helping",
    "teach_tower",
    "teach_with_questions",
    "watch_held_out",
]


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
    from supportive.language.dialogue import scripted_dialogue

    if not spec.behaviors or spec.structure is None:
        return []
    exchange = scripted_dialogue(spec, CHAT_SCRIPT)
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
    simulation = simulate(scenario, plans)
    alone, helped = simulation.alone, simulation.supported
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
        f"actions ({simulation.gain_percent:.0f} % faster)."
    )
    console.print(
        "  Try it: supportive support two-cells-led --simulate --render table.png;"
        " supportive reproduce support-tamp --workers 2"
    )
    return TableContrast(
        advice.actions, advice.expected_saving, alone.makespan, helped.makespan, helped.support_actions
    )
