"""The ``supportive`` command: parses arguments, calls the library, prints. No logic of its own.

Bad input never shows a traceback: any :class:`~supportive.errors.SupportiveError` becomes one line on stderr
and exit status 2.
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from enum import StrEnum
from pathlib import Path
from typing import Annotated, Any

import typer

from supportive.bag_cli import bag_app
from supportive.errors import (
    ExperimentError,
    FileFormatError,
    MissingExtraError,
    SupportiveError,
    TaskFileError,
)
from supportive.extras import require_extra
from supportive.io.terminal import markup_safe, printable, terminal_console

__all__ = ["app", "main"]

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    help="Supportive behaviors for human-robot teaming: learn CC-HTNs from demonstrations, and more.",
)
app.add_typer(bag_app, name="bag")
out = terminal_console(soft_wrap=False)  # wraps at words to the terminal's width (COLUMNS when set)
err = terminal_console(stderr=True)  # an error is one line, whatever its length


def say(line: object, *, to_stderr: bool = False) -> None:
    """Print one line that may hold a user's text: as text (never markup or emoji), escaped for the terminal
    (:mod:`supportive.io.terminal`)."""
    (err if to_stderr else out).print(printable(str(line)), markup=False)


class LearnFormat(StrEnum):
    """Output formats of ``learn``."""

    tree = "tree"
    json = "json"
    dot = "dot"
    hddl = "hddl"


class LearnMode(StrEnum):
    """Which learner (see :class:`~supportive.learning.learner.HTNLearner`)."""

    general = "general"
    strict = "strict"


class Profile(StrEnum):
    """Generator profiles."""

    ikea = "ikea"
    uniform = "uniform"


def _finite(value: float | None) -> float | None:
    """A float option's value when it is a number (click lets ``nan`` through its ranges)."""
    if value is not None and not math.isfinite(value):
        raise typer.BadParameter(f"expected a finite number, got {value}")
    return value


@contextmanager
def _about(path: Path) -> Iterator[None]:
    """Name ``path`` in an error the library raises about its contents (a demonstration, the task) without
    naming the file; file errors name it already, and a missing extra is not the file's fault."""
    try:
        yield
    except (FileFormatError, MissingExtraError):
        raise
    except SupportiveError as exc:
        raise SupportiveError(f"{path}: {exc}") from None


def _write_text(text: str, output: Path | None) -> None:
    if output is None:
        sys.stdout.write(text)
        return
    from supportive.io.atomic import atomic_write

    atomic_write(output, text, error=TaskFileError)


@app.command()
def learn(
    file: Annotated[
        Path, typer.Argument(help="Task file (.yaml, .yml, .json or .csv) or a bundled example's name.")
    ],
    format: Annotated[LearnFormat, typer.Option("--format", "-f", help="What to print.")] = LearnFormat.tree,
    output: Annotated[
        Path | None, typer.Option("--output", "-o", help="File to write (a directory for hddl).")
    ] = None,
    mode: Annotated[
        LearnMode,
        typer.Option(
            "--mode",
            help="general: what the evidence supports (optional steps, repeats, slips); "
            "strict: only what was seen in full (the thesis's reading).",
        ),
    ] = LearnMode.general,
) -> None:
    """Learn the CC-HTN of a task from its demonstrations and print or write it."""
    from supportive.examples import task_path
    from supportive.io.dot import htn_to_dot
    from supportive.io.htn_json import htn_to_dict
    from supportive.io.taskfile import parse_task_file
    from supportive.io.tree import render_tree
    from supportive.learning.learner import learn as learn_htn

    spec = parse_task_file(task_path(file))
    if not spec.demonstrations:
        raise TaskFileError("no demonstrations to learn from", path=file, place="demonstrations")
    with _about(file):
        learner = learn_htn(spec, mode=mode.value)
    if format is LearnFormat.hddl:
        from supportive.io.hddl import write_hddl

        if output is None:
            raise TaskFileError("--format hddl needs --output DIR (it writes domain.hddl and problem.hddl)")
        domain, problem = write_hddl(learner.htn_, output)
        say(f"wrote {domain} and {problem}", to_stderr=True)
        return
    if format is LearnFormat.json:
        data = htn_to_dict(learner.htn_, learner.stats_.as_dict())
        ids = [d.id for d in spec.demonstrations]
        data["deviations"] = [d.as_dict(ids) for d in learner.deviations_]
        text = json.dumps(data, indent=2) + "\n"
    elif format is LearnFormat.dot:
        text = htn_to_dot(learner.htn_)
    else:
        text = render_tree(learner.htn_, spec.texts(), width=120 if output is not None else out.width)
    _write_text(text, output)


class InferenceModel(StrEnum):
    """Goal-inference models."""

    progress = "progress"
    hierarchical = "hierarchical"
    flat = "flat"


@app.command()
def infer(
    file: Annotated[
        Path,
        typer.Argument(help="Task file whose actions declare their 'observations', or a bundled example's name."),
    ],
    observations: Annotated[
        Path | None,
        typer.Option("--observations", "-O", help="Observation stream: .jsonl, .json, .yaml or .yml."),
    ] = None,
    actions: Annotated[
        Path | None,
        typer.Option("--actions", "-A", help="Known actions instead, one action id per line (progress model)."),
    ] = None,
    model: Annotated[
        InferenceModel,
        typer.Option("--model", help="progress: knows what is done (default); or the thesis's HMMs."),
    ] = InferenceModel.progress,
    top: Annotated[
        int, typer.Option("--top", min=1, max=10_000, help="How many entries of each belief to print.")
    ] = 3,
    mean_duration: Annotated[
        float,
        typer.Option("--mean-duration", min=1.0, max=1e6, callback=_finite, help="Mean observations per subgoal."),
    ] = 5.0,
    bag: Annotated[
        Path | None, typer.Option("--bag", help="Read contact events from a ROS bag instead (ros extra).")
    ] = None,
    contacts_topic: Annotated[
        str, typer.Option("--contacts-topic", help="The bag's contacts topic (see docs/ros.md).")
    ] = "/contacts",
    write_bag: Annotated[
        Path | None,
        typer.Option("--write-bag", help="Also write the beliefs as a new MCAP bag (with --bag)."),
    ] = None,
    types: Annotated[
        list[Path] | None,
        typer.Option(
            "--types", help="A .msg/.idl file or folder of message types the bag lacks; repeatable."
        ),
    ] = None,
) -> None:
    """Learn the task's CC-HTN, then print what the teammate is doing after each observation or known action
    (one JSON line each: top subgoals, enclosing subtasks and next steps, with probabilities)."""
    from supportive.bag_inference import belief_record, infer_bag
    from supportive.examples import task_path
    from supportive.inference import FlatHMM, HierarchicalHMM, ObservationModel, ProgressHMM
    from supportive.io.action_file import parse_action_file
    from supportive.io.htn_json import htn_to_dict
    from supportive.io.observation_file import parse_observation_file
    from supportive.io.taskfile import parse_task_file
    from supportive.learning.learner import learn as learn_htn

    if sum(source is not None for source in (observations, bag, actions)) != 1:
        raise SupportiveError("give one source: --observations FILE, --actions FILE or --bag BAG")
    if write_bag is not None and bag is None:
        raise SupportiveError("--write-bag needs --bag: it writes the beliefs beside a recording")
    if actions is not None and model is not InferenceModel.progress:
        raise SupportiveError("--actions needs --model progress (the HMMs read contact events)")
    spec = parse_task_file(task_path(file))
    if not spec.demonstrations:
        raise TaskFileError("no demonstrations to learn from", path=file, place="demonstrations")
    steps = parse_action_file(actions) if actions is not None else []
    stream = parse_observation_file(observations) if observations is not None else []
    with _about(file):
        learner = learn_htn(spec)
        if model is InferenceModel.progress:
            events = ObservationModel.from_spec(spec) if actions is None else None
            running: Any = ProgressHMM(learner.htn_, events, mean_duration=mean_duration).filter()
        else:
            kind = HierarchicalHMM if model is InferenceModel.hierarchical else FlatHMM
            model_events = ObservationModel.from_spec(spec)
            running = kind(learner.htn_, model_events, mean_duration=mean_duration).filter()

    def emit(record: dict[str, object]) -> None:
        sys.stdout.write(json.dumps(record) + "\n")

    if bag is not None:
        hierarchy = htn_to_dict(learner.htn_, learner.stats_.as_dict())
        infer_bag(
            running,
            bag,
            contacts_topic,
            top=top,
            emit=emit,
            write_bag=write_bag,
            hierarchy=hierarchy,
            definitions=types or (),
        )
    for moment, time in stream:
        emit(belief_record(running, running.update(moment), top, time))
    for action in steps:
        emit(belief_record(running, running.observe(action), top, None))


@app.command()
def generate(
    actions: Annotated[
        int, typer.Option("--actions", "-n", min=2, max=100_000, help="Number of primitive actions.")
    ] = 20,
    seed: Annotated[int, typer.Option("--seed", min=0, help="Random seed (same seed, same task).")] = 0,
    demonstrations: Annotated[
        int,
        typer.Option(
            "--demonstrations", "-d", min=0, max=10_000, help="Valid orderings to sample as demonstrations."
        ),
    ] = 4,
    profile: Annotated[Profile, typer.Option("--profile", help="Shape of the structure.")] = Profile.ikea,
    output: Annotated[
        Path | None, typer.Option("--output", "-o", help="Task file to write (.yaml, .json or .csv).")
    ] = None,
) -> None:
    """Generate a random nested chain/clique task with sampled demonstrations (a task file)."""
    from supportive.generate import generate_task
    from supportive.io.taskfile import dump_task, format_of

    spec = generate_task(actions, seed, demonstrations=demonstrations, profile=profile.value)
    fmt = format_of(output) if output is not None else "yaml"
    _write_text(dump_task(spec, fmt), output)


@app.command()
def evaluate(
    file: Annotated[Path, typer.Argument(help="Task file with at least two demonstrations.")],
    folds: Annotated[
        str, typer.Option("--folds", help="loo (leave one out) or a number of folds K.")
    ] = "loo",
    seed: Annotated[int, typer.Option("--seed", min=0, help="Seeds the folds (K folds only).")] = 0,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of a table.")] = False,
) -> None:
    """Cross-validate your demonstrations: does the hierarchy learned from the others admit the one held out
    (with a ground-truth structure: recall and precision of its orderings), and how well the progress-aware
    next-step predictor and three simple baselines predict each step."""
    from supportive.evaluation import evaluate_task
    from supportive.examples import task_path
    from supportive.experiments.progress import progress_bar
    from supportive.io.tables import fitted_table
    from supportive.io.taskfile import parse_task_file

    if folds != "loo" and not (folds.isdigit() and int(folds) >= 2):
        raise SupportiveError(f"--folds: expected loo or a number of folds of at least 2, got {folds!r}")
    spec = parse_task_file(task_path(file))
    if len(spec.demonstrations) < 2:
        raise TaskFileError("cross-validation needs at least two demonstrations", path=file, place="demonstrations")
    k = None if folds == "loo" else int(folds)
    with progress_bar(f"evaluate {printable(spec.name)}", len(spec.demonstrations)) as advance, _about(file):
        result = evaluate_task(spec, k=k, seed=seed, progress=advance)
    data = result.as_dict()
    if as_json:
        out.print_json(json.dumps(data))
        return
    learning = [
        f"{data['admitted']} of {data['held_out']} held-out demonstrations admitted ({data['admission']:.1%})",
    ]
    if data["recall"] is not None:
        learning.append(f"orderings of the structure: recall {data['recall']:.3f}, precision {data['precision']:.3f}")
    say(f"{spec.name}: {'leave one out' if k is None else f'{k} folds'}, {result.folds} folds")
    for line in learning:
        say("  " + line)
    rows = [
        [
            name,
            f"{m['top1']:.3f}",
            f"{m['top3']:.3f}",
            f"{m['zero']:.3f}",
            f"{m['log2']:.3f}",
            f"{m['done_top1']:.3f}",
        ]
        for name, m in result.as_dict()["prediction"].items()  # type: ignore[attr-defined]
    ]
    headers = ["next-step predictor", "top-1", "top-3", "P = 0", "log2 P / step", "top-1 done"]
    out.print(fitted_table(out, f"{result.prediction['progress-aware'].steps} steps", headers, rows, numeric=range(1, 6)))


@app.command()
def captaincook(
    data: Annotated[
        Path | None,
        typer.Option("--data", help="CaptainCook4D directory (default: ../shared/data/captaincook4d)."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of a table.")] = False,
) -> None:
    """Learn every CaptainCook4D recipe from its error-free recordings and score the "must come before" pairs
    the learned model implies against the recipe's published task graph."""
    from supportive.experiments.captaincook.recipes import captaincook_report, recipe_means
    from supportive.io.captaincook import load_captaincook
    from supportive.io.tables import fitted_table

    reports = captaincook_report(load_captaincook(data))
    if as_json:
        rows = [r.as_dict() for r in reports]
        sys.stdout.write(json.dumps(rows, indent=2) + "\n")
        return
    headers = ["recipe", "demos", "actions", "known orders", "roots", "precision", "recall", "F1"]
    cells = [
        [
            r.recipe,
            str(r.demonstrations),
            str(r.actions),
            str(r.known_paths),
            str(r.roots),
            f"{r.score.precision:.3f}",
            f"{r.score.recall:.3f}",
            f"{r.score.f1:.3f}",
        ]
        for r in reports
    ]
    title = "CaptainCook4D: implied precedences vs the published task graphs"
    out.print(fitted_table(out, title, headers, cells, numeric=range(1, len(headers))))
    means = recipe_means(reports)
    out.print(
        f"mean over {means.recipes} recipes: precision {means.precision:.3f}, recall {means.recall:.3f}, "
        f"F1 {means.f1:.3f}; every learned model admits all its recordings: {means.all_admitted}"
    )


@app.command()
def teach(
    file: Annotated[
        Path, typer.Argument(help="Task file (.yaml or .json) or a bundled example's name; it is not changed.")
    ],
    save: Annotated[
        Path | None,
        typer.Option(
            "--save",
            help="The copy your demonstrations are saved to (default: NAME.edited.yaml beside FILE, or here for "
            "a bundled example); when it exists, teaching carries on in it.",
        ),
    ] = None,
    strategy: Annotated[
        str, typer.Option("--strategy", help="Query strategy: distance, connectivity or random.")
    ] = "distance",
    after: Annotated[
        str,
        typer.Option("--ask-after", help="Ask after these step counts (0: at the start), comma-separated."),
    ] = "1,3,5",
    demonstrations: Annotated[
        int | None, typer.Option("--demonstrations", "-d", min=1, help="Stop after this many.")
    ] = None,
    seed: Annotated[
        int, typer.Option("--seed", min=0, help="Seeds the choice among equally good questions.")
    ] = 0,
) -> None:
    """Teach a task by demonstration at the terminal; the robot asks for actions as you go (§2.2)."""
    from supportive.errors import LearningError
    from supportive.examples import task_path
    from supportive.io.working_copy import working_copy
    from supportive.learning.active import QuerySchedule, strategy_names
    from supportive.teach import TeachingConsole

    if strategy not in strategy_names():
        raise LearningError(
            f"--strategy: unknown strategy {strategy!r}; choose one of {', '.join(strategy_names())}"
        )
    try:
        steps = tuple(int(x) for x in after.split(",") if x.strip())
    except ValueError:
        raise LearningError(f"--ask-after: expected step counts like 1,3,5, got {after!r}") from None
    schedule = QuerySchedule(after_steps=steps, max_per_demonstration=len(steps))

    def read() -> str:
        return input("> ")

    copy = working_copy(task_path(file), save)
    with _about(file):
        console = TeachingConsole(copy.start(), read, say, strategy, schedule, seed)
        out.print(printable(copy.describe()), markup=False, soft_wrap=True)  # a path stays whole, to copy and paste
        console.run(demonstrations)


@app.command()
def chat(
    file: Annotated[
        Path,
        typer.Argument(help="Task file with a structure, or a bundled example's name; it is not changed."),
    ],
    save: Annotated[
        Path | None,
        typer.Option(
            "--save",
            help="The copy changed behaviors are saved to (default: NAME.edited.yaml beside FILE, or here for a "
            "bundled example); when it exists, the conversation carries on in it.",
        ),
    ] = None,
    matcher: Annotated[
        str,
        typer.Option(
            "--matcher", help="Subtask matcher: bow (bag of words) or embeddings (needs the extra)."
        ),
    ] = "bow",
) -> None:
    """Tell the robot how to help and ask it to explain its policy, in plain sentences (§3.3)."""
    from supportive.chat import ChatConsole
    from supportive.errors import LearningError
    from supportive.examples import task_path
    from supportive.io.working_copy import working_copy
    from supportive.language.understand import MATCHERS

    if matcher not in MATCHERS:
        raise LearningError(f"--matcher: unknown matcher {matcher!r}; choose {' or '.join(MATCHERS)}")

    def read() -> str:
        return input("> ")

    copy = working_copy(task_path(file), save)
    with _about(file):
        console = ChatConsole(copy.reads(), read, say, matcher)
        console.path = copy.start()  # made once the console is ready: a missing extra leaves no copy behind
        out.print(printable(copy.describe()), markup=False, soft_wrap=True)  # a path stays whole, to copy and paste
        console.run()


@app.command()
def demo() -> None:
    """Learn the bundled IKEA chair task and show what the demonstrations did and did not pin down."""
    from supportive.demo import run_demo

    run_demo(out)


@app.command()
def caregiver(
    map_name: Annotated[
        str, typer.Option("--map", help="A shipped map (house, playroom, apartment) or a map file.")
    ] = "house",
    novice: Annotated[
        float, typer.Option("--novice", help="The novice's share of random moves ε, in [0, 1].")
    ] = 0.5,
    seed: Annotated[int, typer.Option("--seed", min=0, help="Random seed (same seed, same episode).")] = 0,
    steps: Annotated[int, typer.Option("--steps", min=1, max=100_000, help="Novice steps in the episode.")] = 200,
    no_caregiver: Annotated[bool, typer.Option("--no-caregiver", help="Let the novice play alone.")] = False,
    gif: Annotated[
        Path | None,
        typer.Option("--gif", help="Also draw the episode as an animated GIF (needs matplotlib)."),
    ] = None,
    every: Annotated[int, typer.Option("--every", min=1, help="Print every k-th step (and the last).")] = 1,
    delay: Annotated[
        float,
        typer.Option(
            "--delay",
            min=0.0,
            max=60.0,
            callback=_finite,
            help="Seconds between printed steps (on a terminal: redrawn in place).",
        ),
    ] = 0.0,
) -> None:
    """Watch a novice play in a house, with the caregiver robot keeping it safe (§3.5): the map and what the
    caregiver believes and does, step by step, then the episode's damage, steps until the critical damage and
    cells explored."""
    import time
    from contextlib import nullcontext

    from rich.live import Live

    from supportive.safety.episode import THRESHOLD, run_episode
    from supportive.safety.render import LEGEND, render_frame, summary, write_gif
    from supportive.worlds.household import load_map

    if not 0.0 <= novice <= 1.0:
        raise ExperimentError(f"--novice: ε must be in [0, 1] (the share of random moves), got {novice}")
    if gif is not None:
        require_extra("drawing an episode as a GIF (--gif)", "matplotlib", "plot")
    grid = load_map(map_name)
    with_caregiver = not no_caregiver
    result = run_episode(grid, novice, caregiver=with_caregiver, steps=steps, seed=seed, record=True)
    who = "with the caregiver" if with_caregiver else "without a caregiver"
    out.print(
        f"[bold]{markup_safe(grid.name)}[/]: a novice making {novice:.0%} random moves (ε = {novice:g}), {who}, "
        f"{steps} steps, seed {seed}"
    )
    out.print(LEGEND, markup=False)
    shown = [f for f in result.frames if f.step % every == 0 or f.step == len(result.frames)]
    live = Live(console=out, auto_refresh=False) if delay > 0 and out.is_terminal else None
    with live or nullcontext():
        for i, frame in enumerate(shown):
            if delay > 0 and i:
                time.sleep(delay)
            if live is not None:  # a terminal: redraw the step in place
                live.update(render_frame(grid, frame, steps=steps), refresh=True)
            else:
                out.print(render_frame(grid, frame, steps=steps))
    out.print(f"[bold]{who}:[/] " + summary(result, threshold=THRESHOLD, steps=steps), highlight=False)
    if gif is not None:
        write_gif(result.frames, grid, gif)
        say(f"wrote {gif} ({len(result.frames)} frames)", to_stderr=True)


class SupportLead(StrEnum):
    """Leads ``support --simulate`` can run."""

    plans = "plans"
    greedy = "greedy"


@app.command()
def support(
    file: Annotated[
        Path, typer.Argument(help="Circuit scenario file (.yaml, .yml or .json), or a bundled one's name.")
    ],
    seed: Annotated[
        int, typer.Option("--seed", min=0, help="Seeds the sampling (same seed, same choice).")
    ] = 0,
    environments: Annotated[
        int | None,
        typer.Option("--environments", "-e", min=1, max=100_000, help="Hypothetical environments to sample."),
    ] = None,
    scheme: Annotated[
        str | None, typer.Option("--scheme", help="Plan weights: conservative, greedy or aggressive.")
    ] = None,
    workers: Annotated[
        int, typer.Option("--workers", "-w", min=1, max=256, help="Local processes scoring them.")
    ] = 1,
    render: Annotated[
        Path | None,
        typer.Option("--render", help="Draw the table before and after as a PNG (needs matplotlib)."),
    ] = None,
    simulate: Annotated[
        bool, typer.Option("--simulate", help="Also run the lead alone and with the support agent.")
    ] = False,
    lead: Annotated[
        SupportLead, typer.Option("--lead", help="The lead --simulate runs.")
    ] = SupportLead.plans,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of sentences.")] = False,
) -> None:
    """Show what a support robot would do at a circuit table (§3.2): the supportive action it chooses, the
    known plans it favours and the lead's expected saving."""
    from dataclasses import replace

    from supportive.envs.circuits.advice import advise
    from supportive.envs.circuits.advice import simulate as run_simulation
    from supportive.envs.circuits.render import write_before_after
    from supportive.envs.circuits.scenario import parse_scenario_file
    from supportive.examples import circuit_names, circuit_path
    from supportive.planning.weighting import parse_scheme

    if render is not None:
        require_extra("drawing the circuit table (--render)", "matplotlib", "plot")
    if not file.suffix and not file.exists() and str(file) in circuit_names():
        file = circuit_path(str(file))
    scenario = parse_scenario_file(file)
    if environments is not None:
        scenario = replace(scenario, environments=environments)
    if scheme is not None:
        scenario = replace(scenario, scheme=parse_scheme(scheme))
    with _about(file):
        plans = scenario.plans()
        advice, decision = advise(scenario, plans, seed=seed, workers=workers)
    report: dict[str, object] = advice.as_dict()
    if simulate:
        with _about(file):
            alone, helped = run_simulation(scenario, plans, lead.value, seed=seed, workers=workers)
        report["simulation"] = {
            "lead": lead.value,
            "alone": {
                "makespan": alone.makespan,
                "completed": alone.completed,
                "lead_nodes": alone.lead_nodes,
            },
            "supported": {
                "makespan": helped.makespan,
                "completed": helped.completed,
                "lead_nodes": helped.lead_nodes,
                "support_actions": helped.support_actions,
                "conflicts": dict(helped.conflicts),
            },
        }
    if as_json:
        sys.stdout.write(json.dumps(report, indent=2) + "\n")
    else:
        for line in advice.lines():
            say(line)
        if simulate:
            gain = 100.0 * (1.0 - helped.makespan / alone.makespan) if alone.makespan else 0.0
            say(
                f"Simulated ({lead.value} lead): alone {alone.makespan:.1f} s, with support {helped.makespan:.1f} s "
                f"({gain:+.1f} % faster, {helped.support_actions} supportive actions); lead search nodes "
                f"{alone.lead_nodes} -> {helped.lead_nodes}"
            )
    if render is not None:
        world = scenario.world
        after = decision.chosen.state
        write_before_after(world, world.initial_state, after, render, moved=decision.chosen.move)
        say(f"wrote {render}", to_stderr=True)


@app.command()
def serve(
    task: Annotated[
        Path | None,
        typer.Option(
            "--task",
            help="Task file (or a bundled example's name) whose structure or learned HTN is the board "
            "(default: the chair).",
        ),
    ] = None,
    db: Annotated[
        str,
        typer.Option(
            "--db", help="Database URL: sqlite:///board.db or postgresql+psycopg://user@127.0.0.1/db."
        ),
    ] = "sqlite:///board.db",
    host: Annotated[str, typer.Option("--host", help="Address to listen on.")] = "127.0.0.1",
    port: Annotated[int, typer.Option("--port", min=1, max=65535, help="Port to listen on.")] = 8000,
    agent: Annotated[
        list[str] | None,
        typer.Option(
            "--agent",
            help="name:kind:role[:token], repeatable (default: alice lead, robot assistant, screen observer).",
        ),
    ] = None,
    lead_only: Annotated[
        list[str] | None,
        typer.Option("--lead-only", help="A subtask (name or action id) only leads may do; repeatable."),
    ] = None,
    client_timeout: Annotated[
        float,
        typer.Option(
            "--client-timeout",
            min=0.1,
            max=3600.0,
            callback=_finite,
            help="Seconds a client has to send a request's head, then its body; idle ones are closed.",
        ),
    ] = 10.0,
) -> None:
    """Serve the shared task board (§3.4.3): a web page and a JSON/WebSocket API that people and robots claim
    subtasks through. The database is checked before the URL and tokens are printed; SIGTERM stops it
    gracefully (exit status 0)."""
    from supportive.examples import task_path
    from supportive.service.launch import prepare
    from supportive.service.launch import serve as run_service

    launch = prepare(
        task_path(task or "ikea-chair"),
        db,
        host=host,
        port=port,
        agents=agent or (),
        lead_only=lead_only or (),
        client_timeout=client_timeout,
    )

    def announce() -> None:
        say(f"task board for {launch.settings.board.task} at {launch.url()}")
        for spec in launch.settings.agents:
            say(f"  {spec.id} ({spec.kind}, {spec.role}): token {spec.token}")
        if launch.tokens_file is not None:
            say(f"  (tokens kept in {launch.tokens_file}; API docs at http://{host}:{port}/docs)")

    run_service(launch, announce)


@app.command("workbench-sim")
def workbench_sim(
    role: Annotated[
        str, typer.Option("--role", help="The robot's role: student, peer or instructor.")
    ] = "student",
    seconds: Annotated[
        float, typer.Option("--seconds", min=1.0, max=3600.0, callback=_finite, help="Simulated seconds at most.")
    ] = 40.0,
    url: Annotated[
        str | None,
        typer.Option(
            "--url", help="A running board of the workbench task (default: one started in this process)."
        ),
    ] = None,
    seed: Annotated[int, typer.Option("--seed", min=0, help="Breaks the robot's ties.")] = 0,
) -> None:
    """Run the Collaborative Workbench (§3.4) on this machine: a board service, a simulated person's hand and
    a simulated robot that reads the person's social force and acts as a student, a peer or an instructor."""
    from supportive.errors import SupportiveError
    from supportive.workbench import ROLES, run_workbench

    if role not in ROLES:
        raise SupportiveError(f"--role: unknown role {role!r}; choose {', '.join(ROLES)}")
    say(f"workbench-blocks, the robot as {role}:")
    run_workbench(role, url=url, seconds=seconds, seed=seed, tell=say)


@app.command()
def reproduce(
    name: Annotated[str, typer.Argument(help="Experiment to run (e.g. edge-reduction), or 'all'.")],
    trials: Annotated[
        int | None,
        typer.Option("--trials", "-n", min=1, max=1_000_000, help="Trials per experiment (default: a full run)."),
    ] = None,
    seed: Annotated[int, typer.Option("--seed", min=0, help="Random seed (same seed, same metrics).")] = 0,
    workers: Annotated[
        int | None,
        typer.Option(
            "--workers",
            "-w",
            min=1,
            max=256,
            help="Worker processes on a local dask cluster (default: 1, in process).",
        ),
    ] = None,
    scheduler: Annotated[
        str | None, typer.Option("--scheduler", help="Run on an existing dask cluster: tcp://HOST:PORT.")
    ] = None,
    output: Annotated[
        Path | None,
        typer.Option("--output", "-o", help="Directory to write (default: out/reproduce/<name>)."),
    ] = None,
    reading: Annotated[
        list[str] | None,
        typer.Option(
            "--reading",
            "-r",
            help="Run only this reading of the experiment (repeatable; default: every reading side by side).",
        ),
    ] = None,
) -> None:
    """Reproduce a thesis experiment: write metrics.json, report.md and PNG plots, the thesis's numbers beside
    this run's (for 'all', also summary.md: every experiment's findings in one table)."""
    from supportive.experiments import reproduce as run_reproduce
    from supportive.io.tables import fitted_table

    if workers is not None and scheduler is not None:
        raise ExperimentError("--workers and --scheduler are mutually exclusive: give one or the other")
    require_extra("plotting experiment results", "matplotlib", "plot")
    results = run_reproduce(name, trials, seed, workers or 1, scheduler, output, readings=reading or None)
    for result in results:
        files = ", ".join(path.name for path in result.files)
        say(f"{result.experiment}: {result.trials} trials ({result.backend}) -> {result.output}/: {files}")
        rows = [list(row) for row in result.headline]
        title = f"{result.experiment}: this run beside the thesis"
        out.print(fitted_table(out, title, ["quantity", "this run", "thesis"], rows))
    if name == "all" and results and results[0].output is not None:
        out.print(
            f"findings of every experiment, beside the thesis: {results[0].output.parent / 'summary.md'}"
        )


def _print_version(wanted: bool) -> None:
    if wanted:
        from importlib.metadata import version

        out.print(f"supportive {version('supportive')}", markup=False)
        raise typer.Exit


@app.callback()
def _options(
    version: Annotated[
        bool,
        typer.Option("--version", is_eager=True, callback=_print_version, help="Print the version and exit."),
    ] = False,
) -> None:
    """Supportive behaviors for human-robot teaming: learn CC-HTNs from demonstrations, and more."""


def _plain_placeholders(command: Any) -> None:
    """Help without typer's ``<bool>``/``<str>``/``<path>`` placeholders (typer ≥ 0.2x shows every parameter's
    Python type): a flag shows none, a value its kind in capitals (``TEXT``, ``INTEGER``, ``NUMBER``,
    ``PATH``), a choice its choices, an argument its name (``FILE``) and no type. A typer without them has no
    ``display_type`` and is left alone."""
    kinds = {"str": "TEXT", "int": "INTEGER", "float": "NUMBER", "path": "PATH", "file": "PATH"}
    helper = command.get_help_option(command.context_class(command))
    for param in [*command.params, *([helper] if helper is not None else [])]:
        if param.metavar is not None or not hasattr(param, "display_type"):
            continue
        if param.param_type_name == "argument":
            param.metavar = str(param.name).upper()
            param.display_type_rich = lambda ctx: None  # the name says it; no type column
        elif getattr(param, "is_flag", False):
            param.metavar = ""
        else:
            label = str(param.display_type(None)).strip("<>").removesuffix(" range")
            param.metavar = kinds.get(label, label)
    for sub in getattr(command, "commands", {}).values():
        _plain_placeholders(sub)


def main() -> None:
    """Entry point: run the app, turning library errors into one line and exit status 2 (a missing optional
    dependency too: the line names the extra that installs it)."""
    from supportive.extras import missing_extra

    command = typer.main.get_command(app)
    _plain_placeholders(command)
    try:
        command()
    except SupportiveError as exc:
        say(f"supportive: error: {printable(str(exc), newlines=False)}", to_stderr=True)
        sys.exit(2)
    except ModuleNotFoundError as exc:
        problem = missing_extra(exc, " ".join(sys.argv[1:2]) or "this command")
        if problem is None:
            raise
        say(f"supportive: error: {problem}", to_stderr=True)
        sys.exit(2)


if __name__ == "__main__":  # pragma: no cover
    main()
