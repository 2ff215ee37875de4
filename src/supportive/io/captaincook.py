"""Load the CaptainCook4D recipes: error-free recordings as demonstrations, published task graphs as truth.

The dataset (annotations only) lives in a directory with ``annotation_json/complete_step_annotations.json``,
``annotation_json/error_annotations.json`` and ``task_graphs/<recipe>.json``. Each recipe becomes one
:class:`Recipe`: a :class:`TaskSpec` whose actions are the published steps and whose demonstrations are the
recordings without any error, plus the published "must come before" pairs over leaves.

The published graph's node ids are not the recordings' ``step_id``: steps are matched by description text.
A text that occurs k times in a graph is one action performed k times; the k-th performance in a recording is
the k-th node with that text in the graph's topological order (on this dataset such nodes are always ordered
by the graph itself). Steps are kept in the order the annotation lists them, which is the order performed
(annotated start times sometimes overlap and are not used for ordering).

Mistake labels (:data:`~supportive.tasks.spec.MISTAKE_LABELS`) come from ``error_annotations.json``: each
recording's ``step_annotations[k].errors[*].tag`` belongs to the k-th step of the recording. On the recordings
with errors (``errors=True``), a step tagged "Missing Step" that was skipped (start time -1) becomes a
placeholder in :attr:`~supportive.tasks.spec.Demonstration.skipped`, placed where the person moved past it:
before the first performed step the published graph puts after it, or at the end when none is performed. (The
annotations give a skipped step no time and list it where the annotator wrote it — 242 of the 281 after every
performed step, where no verdict but the last could name it at its place.) A performed step
takes ``order`` when one of its tags is "Order Error" (the kind visible in the sequence of steps wins), else its
first tag (``technique``, ``measurement``, ``timing``, ``temperature``, ``preparation``, ``other``). A few steps
are tagged "Missing Step" yet have times: they stay performed steps, as every step with times does, the tag set
aside (their other tags decide, ``other`` when there is none). A skipped step without the tag (an optional
step, "if desired") is left out unlabelled.
"""

from __future__ import annotations

import json
import os
import re
from collections import Counter, defaultdict
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from supportive.errors import DatasetError
from supportive.tasks.htn import Leaf
from supportive.tasks.spec import Action, Demonstration, Step, TaskSpec

__all__ = ["ENV_VAR", "Recipe", "default_root", "load_captaincook", "load_recipe", "recipe_slug"]

ENV_VAR = "SUPPORTIVE_CAPTAINCOOK4D"
"""Environment variable naming the dataset directory."""

_RELATIVE = Path("..") / "shared" / "data" / "captaincook4d"
_STEPS_FILE = Path("annotation_json") / "complete_step_annotations.json"
_ERRORS_FILE = Path("annotation_json") / "error_annotations.json"
_GRAPHS_DIR = Path("task_graphs")
_TAGS = {
    "Order Error": "order",
    "Missing Step": "missing",
    "Technique Error": "technique",
    "Measurement Error": "measurement",
    "Timing Error": "timing",
    "Temperature Error": "temperature",
    "Preparation Error": "preparation",
    "Other": "other",
}
"""The dataset's error tags as mistake labels."""
_TERMINALS = frozenset({"START", "END"})
_FILLERS = ("a", "an", "and", "at", "by", "for", "from", "in", "into", "of", "on", "onto", "or", "the", "to")
_UNITS = ("cup", "cups", "inch", "min", "minute", "minutes", "oz", "sec", "seconds", "tbsp", "tsp")
_STOPWORDS = frozenset((*_FILLERS, "with", *_UNITS, "tablespoon", "tablespoons", "teaspoon", "teaspoons"))
"""Words left out of action ids: fillers and units."""
_SLUG_WORDS = 3


@dataclass(frozen=True)
class Recipe:
    """One CaptainCook4D recipe.

    Attributes:
        name: Slug of the activity name (its task-graph file name without ``.json``).
        title: The activity name as the annotations spell it.
        spec: One task: the published steps as actions, the error-free recordings as demonstrations.
        published: Pairs ``(a, b)`` of leaves ``(action id, occurrence)`` such that the published graph puts
            ``a`` before ``b`` (the transitive closure of its edges, START and END left out).
        graph_edges: The published graph's edges as given, ``(earlier, later)``, between leaves and the
            ``"START"`` and ``"END"`` terminals (the ground truth of the task-graph protocol,
            :mod:`supportive.learning.graph_edges`).
    """

    name: str
    title: str
    spec: TaskSpec
    published: frozenset[tuple[Leaf, Leaf]]
    graph_edges: frozenset[tuple[Leaf | str, Leaf | str]] = frozenset()

    @property
    def steps(self) -> frozenset[Leaf]:
        """The published graph's steps, as leaves."""
        return frozenset(node for edge in self.graph_edges for node in edge if not isinstance(node, str))


def recipe_slug(title: str) -> str:
    """The task-graph file stem of an activity: ``'Microwave Egg Sandwich' -> 'microwaveeggsandwich'``."""
    return re.sub(r"[^a-z]", "", title.lower())


def default_root() -> Path:
    """The dataset directory: ``$SUPPORTIVE_CAPTAINCOOK4D``, else ``../shared/data/captaincook4d`` relative to
    the current directory or to the repository root, whichever exists first.

    Raises:
        DatasetError: when the variable names a missing directory, or no candidate exists.
    """
    named = os.environ.get(ENV_VAR)
    if named:
        path = Path(named)
        if not path.is_dir():
            raise DatasetError(
                f"{ENV_VAR}={named}: no such directory (expected the CaptainCook4D annotations)"
            )
        return path
    candidates = [Path.cwd() / _RELATIVE, Path(__file__).resolve().parents[3] / _RELATIVE]
    for candidate in candidates:
        if candidate.is_dir():
            return candidate.resolve()
    tried = ", ".join(str(c) for c in candidates)
    raise DatasetError(f"CaptainCook4D data not found (tried {tried}); set {ENV_VAR} to its directory")


def load_captaincook(root: Path | None = None, *, errors: bool = False) -> list[Recipe]:
    """Every recipe of the dataset, sorted by name.

    Args:
        root: The dataset directory (see :func:`default_root` when None).
        errors: Also take the recordings with errors as demonstrations (their skipped steps left out; every
            other step, however badly performed, kept where it was performed), labelled with their mistakes
            (see the module's docstring). Their ids end in ``!``.

    Raises:
        DatasetError: when a file is missing or malformed (the message names it).
    """
    root = _checked_root(root)
    recordings = _recordings(root)
    by_title: dict[str, list[Mapping[str, Any]]] = defaultdict(list)
    for recording in recordings:
        by_title[recording["activity_name"]].append(recording)
    recipes = [_recipe(root, title, recs, errors) for title, recs in by_title.items()]
    return sorted(recipes, key=lambda r: r.name)


def load_recipe(name: str, root: Path | None = None, *, errors: bool = False) -> Recipe:
    """One recipe, by slug (``'mugcake'``) or title (``'Mug Cake'``); ``errors`` as for
    :func:`load_captaincook`.

    Raises:
        DatasetError: when no recording has that recipe, or a file is missing or malformed.
    """
    root = _checked_root(root)
    slug = recipe_slug(name)
    recs = [r for r in _recordings(root) if recipe_slug(r["activity_name"]) == slug]
    if not recs:
        raise DatasetError(f"{root / _STEPS_FILE}: no recording of recipe {name!r}")
    return _recipe(root, recs[0]["activity_name"], recs, errors)


# ---------------------------------------------------------------------------------------------- files


def _checked_root(root: Path | None) -> Path:
    root = default_root() if root is None else Path(root)
    if not root.is_dir():
        raise DatasetError(f"{root}: no such directory (expected the CaptainCook4D annotations)")
    return root


def _read_json(path: Path) -> Any:
    try:
        with path.open(encoding="utf-8") as handle:
            return json.load(handle)
    except FileNotFoundError:
        raise DatasetError(f"{path}: file not found") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise DatasetError(f"{path}: unreadable JSON ({exc})") from None


def _recordings(root: Path) -> list[dict[str, Any]]:
    """The recordings with ``clean`` set: true when neither the recording nor any step has an error; each
    step with its ``tags``, the mistake labels of its annotated errors in order."""
    steps_path, errors_path = root / _STEPS_FILE, root / _ERRORS_FILE
    annotations = _read_json(steps_path)
    errors = _read_json(errors_path)
    if not isinstance(annotations, dict):
        raise DatasetError(f"{steps_path}: expected an object recording_id -> recording")
    if not isinstance(errors, list):
        raise DatasetError(f"{errors_path}: expected a list of recordings")
    try:
        is_error = {str(e["recording_id"]): bool(e["is_error"]) for e in errors}
        tagged = {str(e["recording_id"]): e.get("step_annotations", []) for e in errors}
    except (KeyError, TypeError, AttributeError) as exc:
        raise DatasetError(f"{errors_path}: every entry needs recording_id and is_error ({exc})") from None
    out = []
    for key in sorted(annotations, key=_natural):
        rec = annotations[key]
        try:
            steps = [
                {
                    "description": str(s["description"]),
                    "start": float(s["start_time"]),
                    "end": float(s["end_time"]),
                    "has_errors": bool(s["has_errors"]),
                    "skipped": float(s["start_time"]) < 0,
                }
                for s in rec["steps"]
            ]
            out.append(
                {
                    "recording_id": str(rec.get("recording_id", key)),
                    "activity_name": str(rec["activity_name"]),
                    "person_id": rec["person_id"],
                    "steps": steps,
                }
            )
        except (KeyError, TypeError, ValueError) as exc:
            raise DatasetError(f"{steps_path}: recording {key}: missing or bad field ({exc})") from None
        if key not in is_error:
            raise DatasetError(f"{errors_path}: no entry for recording {key}")
        out[-1]["clean"] = not is_error[key] and not any(s["has_errors"] for s in steps)
        for step, tags in zip(steps, _tags(tagged[key], steps, f"{errors_path}: recording {key}"), strict=True):
            step["tags"] = tags
    return out


def _tags(annotated: Any, steps: Sequence[Mapping[str, Any]], where: str) -> list[tuple[str, ...]]:
    """The mistake labels of each step, from the error file's ``step_annotations`` (one per step, in the same
    order; none given: no labels)."""
    if not annotated:
        return [()] * len(steps)
    if not isinstance(annotated, list) or len(annotated) != len(steps):
        raise DatasetError(f"{where}: step_annotations must list the recording's {len(steps)} steps")
    out = []
    for index, (note, step) in enumerate(zip(annotated, steps, strict=True)):
        try:
            described, tags = str(note["description"]), [str(e["tag"]) for e in note.get("errors", [])]
        except (KeyError, TypeError, AttributeError) as exc:
            raise DatasetError(f"{where}: step {index + 1}: missing or bad field ({exc})") from None
        if described != step["description"]:
            raise DatasetError(f"{where}: step {index + 1} is {described!r} here but {step['description']!r} in {_STEPS_FILE}")
        unknown = [tag for tag in tags if tag not in _TAGS]
        if unknown:
            raise DatasetError(f"{where}: step {index + 1}: unknown error tag {unknown[0]!r} (known: {', '.join(_TAGS)})")
        out.append(tuple(_TAGS[tag] for tag in tags))
    return out


def _natural(text: str) -> tuple[tuple[int, int | str], ...]:
    return tuple((0, int(p)) if p.isdigit() else (1, p) for p in re.split(r"[_\W]+", text))


# ---------------------------------------------------------------------------------------------- recipe


def _recipe(root: Path, title: str, recordings: Sequence[Mapping[str, Any]], errors: bool = False) -> Recipe:
    slug = recipe_slug(title)
    path = root / _GRAPHS_DIR / f"{slug}.json"
    nodes, all_edges = _graph(path)
    texts = {k: v for k, v in nodes.items() if v not in _TERMINALS}
    edges = [(a, b) for a, b in all_edges if a in texts and b in texts]
    order = _topological(texts, edges, path)
    ids = _action_ids(dict.fromkeys(texts[n] for n in order))
    leaf_of: dict[str, Leaf] = {}
    seen: Counter[str] = Counter()
    for node in order:
        seen[texts[node]] += 1
        leaf_of[node] = (ids[texts[node]], seen[texts[node]])
    expected = Counter(texts.values())
    demos = tuple(_demonstration(rec, ids, expected, path) for rec in recordings if rec["clean"])
    published = frozenset(
        (leaf_of[a], leaf_of[b]) for a, after in _closure(order, edges).items() for b in after
    )
    if errors:
        later: defaultdict[Leaf, set[Leaf]] = defaultdict(set)
        for first, then in published:
            later[first].add(then)
        demos += tuple(_erroneous(rec, ids, later) for rec in recordings if not rec["clean"])
    actions = tuple(dict.fromkeys(Action(action_id, text) for text, action_id in ids.items()))
    spec = TaskSpec(name=slug, actions=actions, demonstrations=demos)
    named: dict[str, Leaf | str] = {k: v for k, v in nodes.items() if v in _TERMINALS} | leaf_of
    graph_edges = frozenset((named[a], named[b]) for a, b in all_edges)
    return Recipe(name=slug, title=title, spec=spec, published=published, graph_edges=graph_edges)


def _graph(path: Path) -> tuple[dict[str, str], list[tuple[str, str]]]:
    """The graph file's node texts by id (START and END included) and all its edges, checked."""
    data = _read_json(path)
    try:
        steps = {str(k): str(v) for k, v in data["steps"].items()}
        edges = [(str(a), str(b)) for a, b in data["edges"]]
    except (KeyError, TypeError, ValueError, AttributeError) as exc:
        raise DatasetError(
            f"{path}: expected {{'steps': {{id: text}}, 'edges': [[a, b], ...]}} ({exc})"
        ) from None
    for a, b in edges:
        if a not in steps or b not in steps:
            raise DatasetError(f"{path}: edge [{a}, {b}] names an unknown step")
    if all(text in _TERMINALS for text in steps.values()):
        raise DatasetError(f"{path}: no steps")
    return steps, edges


def _topological(texts: Mapping[str, str], edges: Iterable[tuple[str, str]], path: Path) -> list[str]:
    """Kahn's order, smallest node id first among ready nodes (deterministic)."""
    indegree = dict.fromkeys(texts, 0)
    out: dict[str, list[str]] = defaultdict(list)
    for a, b in edges:
        out[a].append(b)
        indegree[b] += 1
    ready = sorted((n for n, d in indegree.items() if d == 0), key=_natural)
    order = []
    while ready:
        node = ready.pop(0)
        order.append(node)
        for nxt in out[node]:
            indegree[nxt] -= 1
            if indegree[nxt] == 0:
                ready.append(nxt)
        ready.sort(key=_natural)
    if len(order) != len(texts):
        raise DatasetError(f"{path}: the graph has a cycle")
    return order


def _closure(order: Sequence[str], edges: Iterable[tuple[str, str]]) -> dict[str, set[str]]:
    """Node -> every node after it, computed in reverse topological order."""
    out: dict[str, list[str]] = defaultdict(list)
    for a, b in edges:
        out[a].append(b)
    after: dict[str, set[str]] = {}
    for node in reversed(order):
        after[node] = set()
        for nxt in out[node]:
            after[node] |= {nxt} | after[nxt]
    return after


def _demonstration(
    rec: Mapping[str, Any], ids: Mapping[str, str], expected: Counter[str], path: Path
) -> Demonstration:
    performed = Counter(s["description"] for s in rec["steps"])
    if performed != expected:
        missing = sorted((expected - performed).elements())
        extra = sorted((performed - expected).elements())
        raise DatasetError(
            f"{path}: error-free recording {rec['recording_id']} does not perform the published steps "
            f"(missing {missing}, not in the graph {extra})"
        )
    steps = tuple(Step(ids[s["description"]], start=s["start"], end=s["end"]) for s in rec["steps"])
    return Demonstration(steps=steps, id=rec["recording_id"], agent=f"person_{rec['person_id']}")


def _erroneous(rec: Mapping[str, Any], ids: dict[str, str], later: Mapping[Leaf, set[Leaf]]) -> Demonstration:
    """A recording with errors as it was performed, labelled: the performed steps in the order listed; skipped
    steps left out, those tagged missing as placeholders before the first performed step that ``later`` (the
    leaves the published graph puts after each leaf) names for them, else at the end; a step whose text is not
    in the graph gets an id of its own (``off_graph_…``, added to ``ids``). A step is the leaf of its action
    and how many of the listed steps so far (itself included) have that action."""
    performed: list[tuple[Leaf, Step]] = []
    skipped: list[Leaf] = []
    listed: Counter[str] = Counter()
    for s in rec["steps"]:
        if s["skipped"] and "missing" not in s["tags"]:
            continue
        text = s["description"]
        if text not in ids:
            ids[text] = "off_graph_" + "_".join(_words(text)[:_SLUG_WORDS])
        action = ids[text]
        listed[action] += 1
        if s["skipped"]:
            skipped.append((action, listed[action]))
        else:
            step = Step(action, start=s["start"], end=s["end"], mistake=_label(s["tags"]))
            performed.append(((action, listed[action]), step))
    places: defaultdict[int, list[Step]] = defaultdict(list)
    for leaf in skipped:
        after = later.get(leaf, set())
        place = next((i for i, (done, _) in enumerate(performed) if done in after), len(performed))
        places[place].append(Step(leaf[0], mistake="missing"))
    entries = [e for i, (_, step) in enumerate(performed) for e in (*places[i], step)] + places[len(performed)]
    return Demonstration.from_entries(entries, id=f"{rec['recording_id']}!", agent=f"person_{rec['person_id']}")


def _label(tags: Sequence[str]) -> str | None:
    """A performed step's label: ``order`` when tagged so, else its first tag; a "Missing Step" tag on a
    performed step is set aside (``other`` when it is the only one)."""
    kinds = [tag for tag in tags if tag != "missing"]
    if "order" in kinds:
        return "order"
    if kinds:
        return kinds[0]
    return "other" if tags else None


def _action_ids(texts: Iterable[str]) -> dict[str, str]:
    """Text -> short unique slug: its first content words, as few as keep it apart from the others."""
    words = {text: _words(text) for text in texts}
    ids: dict[str, str] = {}
    for text, mine in words.items():
        count = _SLUG_WORDS
        others = [w for t, w in words.items() if t != text]
        while count < len(mine) and any(w[:count] == mine[:count] for w in others):
            count += 1
        base = "_".join(mine[:count]) or "step"
        slug, n = base, 2
        while slug in ids.values():
            slug, n = f"{base}_{n}", n + 1
        ids[text] = slug
    return ids


def _words(text: str) -> list[str]:
    """Lowercase content words, each once (``'Peel-Peel 1 garlic clove'`` -> peel, garlic, clove)."""
    words = (w for w in re.findall(r"[a-z]+", text.lower()) if w not in _STOPWORDS)
    return list(dict.fromkeys(words))
