"""The learning commands: ``learn`` (a task's CC-HTN as a tree, JSON, DOT or HDDL), ``generate`` (a random
task file), ``evaluate`` (cross-validation of a user's demonstrations) and ``captaincook`` (the real recipes
against their published graphs)."""

from __future__ import annotations

import json
import sys
from collections.abc import Sequence
from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from supportive.cli.output import about, csv_note, finite, out, say, write_text
from supportive.errors import OptionError, TaskFileError
from supportive.extras import require_extra
from supportive.io.values import is_digits
from supportive.render.terminal import printable

if TYPE_CHECKING:
    from supportive.io.captaincook import Recipe

__all__ = ["captaincook", "evaluate", "generate", "learn"]


class LearnFormat(StrEnum):
    """Output formats of ``learn``."""

    tree = "tree"
    json = "json"
    dot = "dot"
    hddl = "hddl"


class LearnMode(StrEnum):
    """Which reading of the demonstrations (see :class:`~supportive.learning.learner.HTNLearner`)."""

    auto = "auto"
    general = "general"
    strict = "strict"
    partial_order = "partial-order"
    general_consistent = "general-consistent"
    partial_order_consistent = "partial-order-consistent"

    @property
    def learner_mode(self) -> str:
        """The learner's name for it (``partial order``, ``general (consistent orders)``)."""
        from supportive.learning.selection import CONSISTENT

        reading = self.value.removesuffix("-consistent").replace("-", " ")
        return f"{reading}{CONSISTENT}" if self.value.endswith("-consistent") else reading


class Profile(StrEnum):
    """Generator profiles."""

    ikea = "ikea"
    uniform = "uniform"


DetectorThreshold = Annotated[
    float | None,
    typer.Option("--threshold", min=0.0, max=1.0, callback=finite, help="The detector's threshold (--mistakes; default: its own)."),
]
"""``--threshold`` of ``evaluate --mistakes`` and ``captaincook --mistakes``."""


class LearnFrom(StrEnum):
    """What each fold of a mistake evaluation learns from (``evaluation.mistakes.LEARN_FROM``)."""

    all = "all"
    correct = "correct"


DetectorLearnFrom = Annotated[
    LearnFrom,
    typer.Option(
        "--learn-from",
        help="--mistakes: learn each fold from all the other demonstrations, or only the correct ones (no "
        "skipped step and no label a step sequence shows).",
    ),
]
"""``--learn-from`` of ``evaluate --mistakes`` and ``captaincook --mistakes``."""


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
            help="auto: the reading that best predicts held-out demonstrations; general: what the evidence "
            "supports (optional steps, repeats, subtasks, slips); strict: only what was seen in full (the "
            "thesis's reading); partial-order: no subtasks, the orders the evidence establishes; "
            "general-consistent, partial-order-consistent: as those, every order two or more demonstrations "
            "keep without exception taken as established.",
        ),
    ] = LearnMode.auto,
) -> None:
    """Learn the CC-HTN of a task from its demonstrations and print or write it."""
    from supportive.examples import task_path
    from supportive.io.dot import htn_to_dot
    from supportive.io.htn_json import htn_to_dict
    from supportive.io.taskfile import parse_task_file
    from supportive.learning.learner import learn as learn_htn
    from supportive.render.tree import render_tree

    spec = parse_task_file(task_path(file))
    if not spec.demonstrations:
        raise TaskFileError("no demonstrations to learn from", path=file, place="demonstrations")
    with about(file):
        learner = learn_htn(spec, mode=mode.learner_mode)
    if format is LearnFormat.hddl:
        from supportive.io.hddl import write_hddl

        if output is None:
            raise OptionError("--format hddl needs --output DIR (it writes domain.hddl and problem.hddl)")
        domain, problem = write_hddl(learner.htn_, output)
        say(f"wrote {domain} and {problem}", to_stderr=True)
        return
    ids = [d.id for d in spec.demonstrations]
    if format is LearnFormat.json:
        data = htn_to_dict(learner.htn_, learner.stats_.as_dict())
        data["deviations"] = [d.as_dict(ids) for d in learner.deviations_]
        if learner.noise_ is not None:
            data["noise"] = learner.noise_.as_dict()
        data["reading"] = learner.reading_
        if learner.selection_ is not None:
            data["selection"] = learner.selection_.as_dict()
        text = json.dumps(data, indent=2) + "\n"
    elif format is LearnFormat.dot:
        text = htn_to_dot(learner.htn_)
    else:
        text = render_tree(learner.htn_, spec.texts(), width=120 if output is not None else out.width)
    write_text(text, output)
    if format is not LearnFormat.json:  # said once the result is out (a refused output says one line only)
        if learner.selection_ is not None:
            say(learner.selection_.describe(), to_stderr=True)
        if learner.deviations_:
            say(_slips_notice([d.as_dict(ids) for d in learner.deviations_]), to_stderr=True)


SLIPS_SHOWN = 5
"""Slips named in ``learn``'s notice; ``--format json`` lists every one."""

NAMED = 10
"""Held-out demonstrations ``evaluate`` names as not admitted; ``--json`` lists every one."""


def _slips_notice(slips: list[dict[str, object]]) -> str:
    """One line: how many steps were set aside as slips, the first few, where to find the rest."""
    named = []
    for slip in slips[:SLIPS_SHOWN]:
        where = f" step {slip['step']}" if "step" in slip else ""
        named.append(printable(f"{slip['demonstration']}{where} {slip['action']} ({slip['kind']})"))
    more = f", and {len(slips) - SLIPS_SHOWN} more" if len(slips) > SLIPS_SHOWN else ""
    return (
        f"set aside as slips ({len(slips)}; the hierarchy need not admit them, --format json lists them): "
        + "; ".join(named)
        + more
    )


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
    from supportive.io.limits import MAX_FILE_BYTES, MAX_GENERATED_STEPS
    from supportive.io.taskfile import dump_task, format_of

    fmt = format_of(output) if output is not None else "yaml"
    if actions * demonstrations > MAX_GENERATED_STEPS:
        raise OptionError(
            f"{actions:,} actions × {demonstrations:,} demonstrations = {actions * demonstrations:,} steps, more than "
            f"the {MAX_GENERATED_STEPS:,} a generated task may have (docs/limits.md)",
            "--demonstrations",
        )
    spec = generate_task(actions, seed, demonstrations=demonstrations, profile=profile.value)
    text = dump_task(spec, fmt)
    if len(text.encode("utf-8")) > MAX_FILE_BYTES:
        raise TaskFileError(
            f"the task would be {len(text.encode('utf-8')):,} bytes, more than the {MAX_FILE_BYTES:,} supportive "
            "reads back (docs/limits.md): fewer actions or demonstrations",
            path=output or "<stdout>",
        )
    write_text(text, output)
    csv_note(spec, fmt, output)


def evaluate(
    file: Annotated[Path, typer.Argument(help="Task file with at least two demonstrations.")],
    folds: Annotated[
        str,
        typer.Option(
            "--folds",
            metavar="auto|loo|K",
            help="auto (leave one out up to 50 demonstrations, 10 folds above), loo (leave one out) or a number "
            "of folds K.",
        ),
    ] = "auto",
    seed: Annotated[int, typer.Option("--seed", min=0, help="Seeds the folds (K folds only).")] = 0,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of a table.")] = False,
    plot: Annotated[
        Path | None,
        typer.Option("--plot", help="Draw the predictors' reliability diagram as a PNG (needs matplotlib)."),
    ] = None,
    mistakes: Annotated[
        bool,
        typer.Option("--mistakes", help="Score online mistake detection on the file's labelled steps instead."),
    ] = False,
    threshold: DetectorThreshold = None,
    learn_from: DetectorLearnFrom = LearnFrom.all,
) -> None:
    """Cross-validate your demonstrations: does the hierarchy learned from the others admit the one held out
    (with a ground-truth structure: recall and precision of its orderings), and how well the progress-aware
    next-step predictor and three simple baselines predict each step, and how well calibrated their
    probabilities are (expected calibration error and the reliability table of the top-1 probability).
    With --mistakes: leave each demonstration out and detect its labelled mistakes step by step, beside a
    precondition check and an unseen-bigram rule."""
    from supportive.evaluation import evaluate_task
    from supportive.evaluation.crossval import default_folds
    from supportive.examples import task_path
    from supportive.experiments.progress import progress_bar
    from supportive.io.taskfile import parse_task_file
    from supportive.render.tables import fitted_table

    if folds not in ("auto", "loo") and not (is_digits(folds) and int(folds) >= 2):
        raise OptionError(f"expected auto, loo or a number of folds of at least 2, got {folds!r}", "--folds")
    if plot is not None:
        require_extra("drawing the reliability diagram (--plot)", "matplotlib", "plot")
    spec = parse_task_file(task_path(file))
    if len(spec.demonstrations) < 2:
        raise TaskFileError("cross-validation needs at least two demonstrations", path=file, place="demonstrations")
    if mistakes:
        from supportive.cli.mistakes import print_mistakes
        from supportive.evaluation.mistakes import STRUCTURE_REFERENCE, evaluate_mistakes
        from supportive.learning.precedence import implied_precedences
        from supportive.tasks.htn import HTN

        if folds not in ("auto", "loo") or plot is not None:
            raise OptionError("--mistakes leaves one demonstration out and draws nothing: drop --folds and --plot")
        if not any(demo.labelled for demo in spec.demonstrations):
            raise TaskFileError(
                "no step carries a mistake label (see docs/task-files.md: 'mistake: order', …)",
                path=file,
                place="demonstrations",
            )
        truth = None if spec.structure is None else implied_precedences(HTN(spec.name, (spec.structure,)))
        with progress_bar(f"mistakes {printable(spec.name)}", len(spec.demonstrations)) as advance, about(file):
            found = evaluate_mistakes(
                spec,
                thresholds=(_threshold(threshold),),
                learn_from=learn_from.value,
                truth=truth,
                reference=STRUCTURE_REFERENCE,
                progress=advance,
            )
        print_mistakes(found, printable(spec.name), as_json=as_json)
        return
    _without_mistakes(learn_from)
    k = default_folds(len(spec.demonstrations)) if folds == "auto" else None if folds == "loo" else int(folds)
    with progress_bar(f"evaluate {printable(spec.name)}", len(spec.demonstrations)) as advance, about(file):
        result = evaluate_task(spec, k=k, seed=seed, progress=advance)
    data = result.as_dict()
    prediction: dict[str, dict[str, Any]] = data["prediction"]  # type: ignore[assignment]
    if plot is not None:
        from supportive.render.reliability import write_reliability

        tables = {name: scores["reliability"] for name, scores in prediction.items()}
        write_reliability(tables, plot, f"{spec.name}: next-step reliability")
        say(f"wrote {plot}", to_stderr=True)
    if as_json:
        out.print_json(json.dumps(data))
        return
    learning = [
        f"{data['admitted']} of {data['held_out']} held-out demonstrations admitted ({data['admission']:.1%})",
    ]
    if result.not_admitted:
        shown = ", ".join(result.not_admitted[:NAMED])
        more = f", … and {len(result.not_admitted) - NAMED} more" if len(result.not_admitted) > NAMED else ""
        learning.append(f"not admitted when held out: {shown}{more}")
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
            f"{m['ece']:.3f}",
        ]
        for name, m in prediction.items()
    ]
    headers = ["next-step predictor", "top-1", "top-3", "P = 0", "log2 P / step", "top-1 done", "calibration error"]
    out.print(fitted_table(out, f"{result.prediction['progress-aware'].steps} steps", headers, rows, numeric=range(1, 7)))
    reliability = [
        [f"{row['from']:.1f}–{row['to']:.1f}", str(row["predictions"]), f"{row['confidence']:.3f}", f"{row['accuracy']:.3f}"]
        for row in prediction["progress-aware"]["reliability"]
    ]
    headers = ["top-1 probability", "predictions", "mean probability", "right"]
    out.print(fitted_table(out, "progress-aware: reliability", headers, reliability, numeric=range(1, 4)))


def captaincook(
    data: Annotated[
        Path | None,
        typer.Option("--data", help="CaptainCook4D directory (default: ../shared/data/captaincook4d)."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of a table.")] = False,
    mistakes: Annotated[
        bool,
        typer.Option(
            "--mistakes", help="Score online mistake detection on every recording's labels instead (slow: minutes)."
        ),
    ] = False,
    threshold: DetectorThreshold = None,
    learn_from: DetectorLearnFrom = LearnFrom.all,
    uniform: Annotated[
        int,
        typer.Option(
            "--uniform",
            min=0,
            metavar="N",
            help="Also learn N sets of recordings drawn uniformly from each published graph's orders (default "
            "and strict learners) and give their task-graph F1, and count the pairs the graphs leave unordered "
            "that every recording keeps in one order: how much of the shortfall the recordings' habits make "
            '(seconds per set; with --json the output becomes {"recipes": [...], "uniform": {...}, '
            '"free_pairs": {...}}).',
        ),
    ] = 0,
) -> None:
    """Learn every CaptainCook4D recipe from its error-free recordings and score the "must come before" pairs
    the learned model implies against the recipe's published task graph. With --mistakes: leave each
    recording out and detect its order errors and missing steps step by step (the other labels, which a step
    sequence cannot show, are counted apart), beside a precondition check and an unseen-bigram rule."""
    from supportive.experiments.captaincook.recipes import captaincook_report, recipe_means
    from supportive.experiments.statistics import format_ci
    from supportive.io.captaincook import load_captaincook
    from supportive.learning.graph_edges import PEERS
    from supportive.render.tables import fitted_table

    if mistakes:
        if uniform:
            raise OptionError("draws recordings for the task graphs, not for mistake detection: give it without --mistakes", "--uniform")
        _captaincook_mistakes(data, threshold, learn_from.value, as_json)
        return
    _without_mistakes(learn_from)

    recipes = load_captaincook(data)
    reports = captaincook_report(recipes)
    habits = _habits(recipes, uniform)
    if as_json:
        rows = [r.as_dict() for r in reports]
        shown: object = rows if habits is None else {"recipes": rows, **habits}
        sys.stdout.write(json.dumps(shown, indent=2) + "\n")
        return
    headers = ["recipe", "demos", "actions", "roots", "precision", "recall", "F1", "edge F1", "5-shot"]
    cells = [
        [
            r.recipe,
            str(r.demonstrations),
            str(r.actions),
            str(r.roots),
            f"{r.score.precision:.3f}",
            f"{r.score.recall:.3f}",
            f"{r.score.f1:.3f}",
            f"{r.edges.f1:.3f}",
            f"{r.few_shot_edges.f1:.3f}",
        ]
        for r in reports
    ]
    title = "CaptainCook4D: implied precedences and task-graph edges vs the published task graphs"
    out.print(fitted_table(out, title, headers, cells, numeric=range(1, len(headers))))
    means = recipe_means(reports)
    out.print(
        f"mean over {means.recipes} recipes: precedence precision {means.precision:.3f}, recall "
        f"{means.recall:.3f}, F1 {means.f1:.3f}; every learned model admits all its recordings: "
        f"{means.all_admitted}"
    )
    for setting, scores, errors in (
        ("full", means.edges, means.edge_errors),
        ("5-shot", means.few_shot_edges, means.few_shot_edge_errors),
    ):
        peers = ", ".join(f"{name} {f1[setting]:.3f}" for name, f1 in PEERS.items() if setting in f1)
        out.print(
            f"task-graph edges ({setting}, the protocol of Differentiable Task Graph Learning): precision "
            f"{scores['precision']:.3f}, recall {scores['recall']:.3f}, F1 {format_ci(means.edge_f1[setting])} "
            f"(95 % interval over the recipes); published: {peers}"
        )
        out.print(f"  wrong edges ({setting}, all recipes): " + "; ".join(f"{n} {kind}" for kind, n in errors.items()))
    if habits is not None:
        _print_habits(habits)


def _habits(recipes: Sequence[Recipe], draws: int) -> dict[str, dict[str, Any]] | None:
    """``captaincook --uniform``: the default and the strict learner on ``draws`` sets of uniformly drawn
    recordings of each recipe, and the free pairs the real recordings keep (None for 0 draws)."""
    from supportive.experiments.captaincook.uniform import kept_free_pairs, uniform_draws

    if not draws:
        return None
    return {
        "uniform": {
            "default": uniform_draws(recipes, draws).as_dict(),
            "strict": uniform_draws(recipes, draws, learner_options={"mode": "strict"}).as_dict(),
        },
        "free_pairs": kept_free_pairs(recipes).as_dict(),
    }


def _print_habits(habits: dict[str, dict[str, Any]]) -> None:
    """The lines ``captaincook --uniform`` adds to the table."""
    from supportive.experiments.statistics import format_ci

    pairs = habits["free_pairs"]
    out.print(
        f"pairs of steps the published graphs leave unordered, done by two or more recordings: {pairs['free']}; "
        f"every recording in one order: {pairs['kept']} (uniform draws from the graphs' orders: "
        f"{pairs['expected']:.1f} on average)"
    )
    for learner, figures in habits["uniform"].items():
        out.print(
            f"the {learner} learner on {figures['draws']} set{'' if figures['draws'] == 1 else 's'} of recordings "
            f"drawn uniformly from each published graph's orders (seed {figures['seed']}): task-graph F1 full "
            f"{format_ci(figures['full'])}, 5-shot {format_ci(figures['5-shot'])}"
        )


def _without_mistakes(learn_from: LearnFrom) -> None:
    """Refuse ``--learn-from`` given without ``--mistakes`` (it chooses nothing else)."""
    if learn_from is not LearnFrom.all:
        raise OptionError("--learn-from chooses what mistake detection learns from: give --mistakes too", "--learn-from")


def _threshold(given: float | None) -> float:
    """The detector's threshold: ``--threshold``, or the detector's default."""
    from supportive.inference.mistakes import DEFAULT_THRESHOLD

    if given is None:
        return DEFAULT_THRESHOLD
    if given <= 0.0:
        raise OptionError(f"the threshold must be above 0, got {given}", "--threshold")
    return given


def _captaincook_mistakes(data: Path | None, given: float | None, learn_from: str, as_json: bool) -> None:
    """``captaincook --mistakes``: every recipe left one recording out, summed."""
    from supportive.cli.mistakes import print_mistakes
    from supportive.evaluation.mistakes import MistakeEvaluation, evaluate_mistakes
    from supportive.experiments.mistake_detection.measure import POSITIVES
    from supportive.experiments.progress import progress_bar
    from supportive.io.captaincook import load_captaincook

    threshold = _threshold(given)
    recipes = load_captaincook(data, errors=True)
    total = MistakeEvaluation("captaincook4d", (threshold,), learn_from)
    with progress_bar("captaincook mistakes", sum(len(r.spec.demonstrations) for r in recipes)) as advance:
        for recipe in recipes:
            total.merge(
                evaluate_mistakes(
                    recipe.spec,
                    thresholds=(threshold,),
                    positives=POSITIVES,
                    learn_from=learn_from,
                    truth=recipe.published,
                    progress=advance,
                )
            )
    extra = {"positives": list(POSITIVES), "recipes": len(recipes)}
    print_mistakes(total, f"CaptainCook4D, {len(recipes)} recipes ({' and '.join(POSITIVES)} as mistakes)", as_json=as_json, extra=extra)
