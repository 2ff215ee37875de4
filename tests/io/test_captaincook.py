"""The CaptainCook4D loader: a tiny synthetic copy of the layout, and the real annotations when present."""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from supportive.errors import DatasetError
from supportive.io.captaincook import (
    ENV_VAR,
    Recipe,
    default_root,
    load_captaincook,
    load_recipe,
    recipe_slug,
)

# ------------------------------------------------------------------------------------------- synthetic


def _step(text: str, start: float, errors: bool = False) -> dict[str, Any]:
    return {
        "step_id": 0,
        "description": text,
        "start_time": start,
        "end_time": start + 1,
        "has_errors": errors,
    }


def _recording(recording_id: str, person: int, steps: list[dict[str, Any]]) -> dict[str, Any]:
    return {"activity_name": "Test Soup!", "person_id": person, "recording_id": recording_id, "steps": steps}


def _write_dataset(root: Path) -> Path:
    """A two-step-repeated recipe: Boil -> Stir -> Boil -> Stir, Chop anywhere before the second Stir."""
    (root / "annotation_json").mkdir(parents=True)
    (root / "task_graphs").mkdir()
    graph = {
        "steps": {
            "0": "START",
            "1": "Stir-Stir it",
            "2": "Boil-Boil water",
            "3": "Stir-Stir it",
            "4": "Boil-Boil water",
            "5": "Chop-Chop 1 onion",
            "6": "END",
        },
        "edges": [[0, 4], [4, 3], [3, 2], [2, 1], [0, 5], [5, 1], [1, 6]],
    }
    (root / "task_graphs" / "testsoup.json").write_text(json.dumps(graph))
    order = ["Boil-Boil water", "Stir-Stir it", "Chop-Chop 1 onion", "Boil-Boil water", "Stir-Stir it"]
    other = ["Chop-Chop 1 onion", "Boil-Boil water", "Stir-Stir it", "Boil-Boil water", "Stir-Stir it"]
    recordings = {
        "9_1": _recording("9_1", 2, [_step(t, i) for i, t in enumerate(order)]),
        "9_2": _recording("9_2", 3, [_step(t, i) for i, t in enumerate(other)]),
        "9_3": _recording("9_3", 3, [_step(t, i, errors=i == 1) for i, t in enumerate(order)]),
        "9_4": _recording("9_4", 4, [_step(t, i) for i, t in enumerate(order[::-1])]),
    }
    errors = [{"recording_id": r, "is_error": r == "9_4"} for r in recordings]
    (root / "annotation_json" / "complete_step_annotations.json").write_text(json.dumps(recordings))
    (root / "annotation_json" / "error_annotations.json").write_text(json.dumps(errors))
    return root


@pytest.fixture
def tiny(tmp_path: Path) -> Path:
    return _write_dataset(tmp_path / "cc")


def test_synthetic_recipe(tiny: Path) -> None:
    (recipe,) = load_captaincook(tiny)
    assert (recipe.name, recipe.title) == ("testsoup", "Test Soup!")
    assert {a.text for a in recipe.spec.actions} == {"Stir-Stir it", "Boil-Boil water", "Chop-Chop 1 onion"}
    ids = {a.text: a.id for a in recipe.spec.actions}
    boil, stir, chop = ids["Boil-Boil water"], ids["Stir-Stir it"], ids["Chop-Chop 1 onion"]
    # Only the error-free recordings, in the annotated order, with agents and times.
    assert [d.id for d in recipe.spec.demonstrations] == ["9_1", "9_2"]
    first = recipe.spec.demonstrations[0]
    assert first.actions == (boil, stir, chop, boil, stir)
    assert first.agent == "person_2"
    assert (first.steps[1].start, first.steps[1].end) == (1.0, 2.0)
    # Repeated texts: node 4 is the first Boil, node 2 the second, in the graph's topological order.
    chain = [(boil, 1), (stir, 1), (boil, 2), (stir, 2)]
    expected = {(a, b) for i, a in enumerate(chain) for b in chain[i + 1 :]} | {((chop, 1), (stir, 2))}
    assert recipe.published == expected
    assert load_recipe("Test Soup!", tiny) == load_recipe("testsoup", tiny) == recipe


def test_missing_root_raises(tmp_path: Path) -> None:
    with pytest.raises(DatasetError, match="no such directory"):
        load_captaincook(tmp_path / "absent")


def test_env_var_must_name_a_directory(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(ENV_VAR, str(tmp_path / "absent"))
    with pytest.raises(DatasetError, match=ENV_VAR):
        default_root()
    monkeypatch.setenv(ENV_VAR, str(tmp_path))
    assert default_root() == tmp_path


def test_missing_and_bad_files_are_named(tiny: Path) -> None:
    (tiny / "task_graphs" / "testsoup.json").unlink()
    with pytest.raises(DatasetError, match=r"testsoup\.json: file not found"):
        load_captaincook(tiny)
    (tiny / "task_graphs" / "testsoup.json").write_text("{not json")
    with pytest.raises(DatasetError, match=r"testsoup\.json: unreadable JSON"):
        load_captaincook(tiny)
    (tiny / "annotation_json" / "error_annotations.json").unlink()
    with pytest.raises(DatasetError, match=r"error_annotations\.json"):
        load_captaincook(tiny)


def test_unknown_recipe(tiny: Path) -> None:
    with pytest.raises(DatasetError, match="no recording of recipe"):
        load_recipe("Mug Cake", tiny)


def test_slug() -> None:
    assert recipe_slug("Microwave Egg Sandwich") == "microwaveeggsandwich"
    assert recipe_slug("Herb Omelet with Fried Tomatoes") == "herbomeletwithfriedtomatoes"


# ------------------------------------------------------------------------------------------- real data


@pytest.fixture(scope="module")
def root() -> Path:
    return default_root()  # the dataset ships in ../shared; its absence is a failure, not a skip


@pytest.fixture(scope="module")
def recipes(root: Path) -> list[Recipe]:
    return load_captaincook(root)


def test_all_recipes_map(root: Path, recipes: list[Recipe]) -> None:
    graphs = {p.stem for p in (root / "task_graphs").glob("*.json")}
    assert len(recipes) == 24
    assert {r.name for r in recipes} == graphs
    assert all(recipe_slug(r.title) == r.name == r.spec.name for r in recipes)


def test_only_error_free_recordings(root: Path, recipes: list[Recipe]) -> None:
    steps = json.loads((root / "annotation_json" / "complete_step_annotations.json").read_text())
    errors = json.loads((root / "annotation_json" / "error_annotations.json").read_text())
    flagged = {e["recording_id"] for e in errors if e["is_error"]}
    faulty = {r for r, rec in steps.items() if any(s["has_errors"] for s in rec["steps"])}
    clean = set(steps) - flagged - faulty
    used = [d.id for r in recipes for d in r.spec.demonstrations]
    assert len(used) == len(set(used)) and set(used) == clean
    assert all(r.spec.demonstrations for r in recipes)


def test_actions_and_demonstrations(recipes: list[Recipe]) -> None:
    for recipe in recipes:
        ids = [a.id for a in recipe.spec.actions]
        assert len(ids) == len(set(ids))
        assert all(i.replace("_", "").isalpha() and i.islower() for i in ids)
        leaves = {leaf for pair in recipe.published for leaf in pair}
        for demo in recipe.spec.demonstrations:
            assert demo.agent is not None and demo.agent.startswith("person_")
            assert all(s.start is not None and s.end is not None for s in demo.steps)
            counts = Counter(demo.actions)
            performed = {(a, k) for a, n in counts.items() for k in range(1, n + 1)}
            assert leaves <= performed


def test_repeated_steps_become_occurrences(recipes: list[Recipe]) -> None:
    by_name = {r.name: r for r in recipes}
    meatballs = by_name["dressedupmeatballs"]
    stir = next(a.id for a in meatballs.spec.actions if a.label.startswith("Stir-Stir the contents"))
    heat = next(a.id for a in meatballs.spec.actions if a.label.startswith("Microwave-Microwave the plate"))
    assert ((stir, 1), (stir, 2)) in meatballs.published
    # Published chain: Microwave #1 -> Stir #1 -> Microwave #2 -> Stir #2.
    assert {((heat, 1), (stir, 1)), ((stir, 1), (heat, 2)), ((heat, 2), (stir, 2))} <= meatballs.published
    assert all(Counter(d.actions)[stir] == 2 for d in meatballs.spec.demonstrations)
    pinwheels = by_name["pinwheels"]
    slicing = next(a.id for a in pinwheels.spec.actions if a.label.startswith("slicing-"))
    assert {((slicing, 1), (slicing, 2)), ((slicing, 2), (slicing, 3))} <= pinwheels.published


def test_published_pairs_are_a_strict_transitive_order(recipes: list[Recipe]) -> None:
    for recipe in recipes:
        pairs = recipe.published
        after: dict[tuple[str, int], set[tuple[str, int]]] = {}
        for a, b in pairs:
            after.setdefault(a, set()).add(b)
        assert all((b, a) not in pairs for a, b in pairs), recipe.name
        for a, b in pairs:
            assert after.get(b, set()) <= after[a], recipe.name
        actions = {leaf[0] for pair in pairs for leaf in pair}
        assert actions <= {a.id for a in recipe.spec.actions}
        texts = {a.text for a in recipe.spec.actions}
        assert not texts & {"START", "END"}


# ------------------------------------------------------------------------------------------- mistake labels


def _label_errors(root: Path, notes: dict[str, dict[int, list[str]]]) -> None:
    """Give recordings' steps error tags (``notes[recording][step index]``) in the error file."""
    steps = json.loads((root / "annotation_json" / "complete_step_annotations.json").read_text())
    errors = json.loads((root / "annotation_json" / "error_annotations.json").read_text())
    for entry in errors:
        tags = notes.get(entry["recording_id"], {})
        entry["step_annotations"] = [
            {"description": s["description"]} | ({"errors": [{"tag": t} for t in tags[i]]} if i in tags else {})
            for i, s in enumerate(steps[entry["recording_id"]]["steps"])
        ]
    (root / "annotation_json" / "error_annotations.json").write_text(json.dumps(errors))


def _skip(root: Path, recording: str, *indices: int) -> None:
    path = root / "annotation_json" / "complete_step_annotations.json"
    steps = json.loads(path.read_text())
    for i in indices:
        steps[recording]["steps"][i] |= {"start_time": -1.0, "end_time": -1.0, "has_errors": True}
    path.write_text(json.dumps(steps))


def test_synthetic_mistake_labels(tiny: Path) -> None:
    # 9_4 (reversed order): Stir, Boil, Chop, Stir, Boil; Boil (1) and Stir (3) skipped, only Boil tagged missing.
    _skip(tiny, "9_4", 1, 3)
    _label_errors(
        tiny,
        {
            "9_3": {1: ["Technique Error", "Order Error"], 2: ["Measurement Error", "Timing Error"]},
            "9_4": {1: ["Missing Step"], 2: ["Missing Step"], 4: ["Missing Step", "Preparation Error"]},
        },
    )
    (recipe,) = load_captaincook(tiny, errors=True)
    ids = {a.text: a.id for a in recipe.spec.actions}
    boil, stir, chop = ids["Boil-Boil water"], ids["Stir-Stir it"], ids["Chop-Chop 1 onion"]
    demos = {d.id: d for d in recipe.spec.demonstrations}
    assert not demos["9_1"].labelled and not demos["9_2"].labelled
    assert [s.mistake for s in demos["9_3!"].steps] == [None, "order", "measurement", None, None]
    four = demos["9_4!"]
    assert four.actions == (stir, chop, boil)  # skipped steps left out, as before labels
    # the untagged skipped Stir (an optional step) leaves no placeholder; the missing Boil, listed after the first
    # Stir, is placed before it: the published graph puts every Stir after the first Boil
    assert four.skipped == ((0, boil),)
    assert [s.mistake for s in four.steps] == [None, "other", "preparation"]  # Missing Step on a timed step set aside
    assert [d.id for d in load_captaincook(tiny)[0].spec.demonstrations] == ["9_1", "9_2"]


def test_a_skipped_step_is_placed_where_the_person_moved_past_it(tiny: Path) -> None:
    """The annotations list a skipped step where the annotator wrote it, most often after every performed step:
    it is placed before the first performed step the published graph puts after it, else at the end."""
    path = tiny / "annotation_json" / "complete_step_annotations.json"
    steps = json.loads(path.read_text())
    listed = steps["9_4"]["steps"]  # Stir, Boil, Chop, Stir, Boil: the Chop and the last Boil skipped, listed last
    steps["9_4"]["steps"] = [listed[0], listed[1], listed[3], listed[2], listed[4]]
    path.write_text(json.dumps(steps))
    _skip(tiny, "9_4", 3, 4)
    _label_errors(tiny, {"9_4": {3: ["Missing Step"], 4: ["Missing Step"]}})
    (recipe,) = load_captaincook(tiny, errors=True)
    ids = {a.text: a.id for a in recipe.spec.actions}
    four = {d.id: d for d in recipe.spec.demonstrations}["9_4!"]
    assert four.actions == (ids["Stir-Stir it"], ids["Boil-Boil water"], ids["Stir-Stir it"])
    # the Chop and the second Boil (listed last) are both needed by the second Stir, performed third
    assert four.skipped == ((2, ids["Chop-Chop 1 onion"]), (2, ids["Boil-Boil water"]))


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (lambda notes: notes[0].update(description="Peel-Peel it"), r"step 1 is 'Peel-Peel it' here but"),
        (lambda notes: notes[1].update(errors=[{"tag": "Spelling Error"}]), r"step 2: unknown error tag 'Spelling Error'"),
        (lambda notes: notes.pop(), r"step_annotations must list the recording's 5 steps"),
        (lambda notes: notes[1].update(errors=[{"kind": "Other"}]), r"step 2: missing or bad field"),
    ],
)
def test_bad_error_annotations_are_named(tiny: Path, edit: Callable[[list[dict[str, Any]]], object], message: str) -> None:
    _label_errors(tiny, {})
    path = tiny / "annotation_json" / "error_annotations.json"
    errors = json.loads(path.read_text())
    edit(errors[2]["step_annotations"])
    path.write_text(json.dumps(errors))
    with pytest.raises(DatasetError, match=r"error_annotations\.json: recording 9_3: " + message):
        load_captaincook(tiny)


def test_real_mistake_labels(root: Path) -> None:
    """The issue counts 795 order errors and 285 missing steps (tags). As labels: one step is tagged Order Error
    twice (794 steps labelled order), and 4 steps tagged Missing Step have times, so they stay performed steps
    (281 placeholders); every recording is loaded, none is skipped."""
    raw = json.loads((root / "annotation_json" / "error_annotations.json").read_text())
    tags = Counter(e["tag"] for r in raw for s in r["step_annotations"] for e in s.get("errors", []))
    assert (tags["Order Error"], tags["Missing Step"]) == (795, 285)
    recipes = load_captaincook(root, errors=True)
    demos = [d for r in recipes for d in r.spec.demonstrations]
    assert len(demos) == len(raw) == 384
    labels = Counter(s.mistake for d in demos for s in d.steps if s.mistake)
    skipped = sum(len(d.skipped) for d in demos)
    assert (labels["order"], skipped) == (794, 281)
    assert labels == Counter(
        order=794, technique=324, preparation=229, measurement=202, timing=106, temperature=21, other=7
    )
    assert sum(d.labelled for d in demos) == sum(r["is_error"] for r in raw) == 220
    assert not any(d.labelled for d in demos if not d.id.endswith("!"))
    steps = json.loads((root / "annotation_json" / "complete_step_annotations.json").read_text())
    for demo in demos:
        if demo.id.endswith("!"):  # performed steps as before: the ones with times, in the order listed
            performed = [s["start_time"] for s in steps[demo.id[:-1]]["steps"] if s["start_time"] >= 0]
            assert [s.start for s in demo.steps] == performed
    assert not any(d.labelled for r in load_captaincook(root) for d in r.spec.demonstrations)


def test_real_skipped_steps_sit_before_the_first_step_the_graph_puts_after_them(root: Path) -> None:
    """Each step of the listing is the leaf of its action and how many listed steps so far have it (the
    annotator lists a skipped step where it was missed, or at the end); a skipped one sits before the first
    performed step whose leaf the published graph puts after its leaf, else at the end."""
    listings = json.loads((root / "annotation_json" / "complete_step_annotations.json").read_text())
    places: Counter[str] = Counter()
    for recipe in load_captaincook(root, errors=True):
        ids = {a.text: a.id for a in recipe.spec.actions}
        for demo in recipe.spec.demonstrations:
            if not demo.skipped:
                continue
            listed: Counter[str] = Counter()
            leaves = []  # (leaf, performed?) in the listed order
            for entry in listings[demo.id[:-1]]["steps"]:
                listed[ids[entry["description"]]] += 1
                leaves.append(((ids[entry["description"]], listed[ids[entry["description"]]]), entry["start_time"] >= 0))
            performed = [leaf for leaf, done in leaves if done]
            expected = []
            for leaf, done in leaves:
                if not done and leaf[0] in {action for _, action in demo.skipped}:
                    after = {b for a, b in recipe.published if a == leaf}
                    expected.append((next((i for i, p in enumerate(performed) if p in after), len(performed)), leaf[0]))
            assert demo.skipped == tuple(sorted(expected, key=lambda e: e[0])), demo.id
            places.update("at the end" if p == len(performed) else "inside" for p, _ in demo.skipped)
    assert places == Counter({"inside": 237, "at the end": 44})
