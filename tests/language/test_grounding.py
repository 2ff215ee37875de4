"""Algorithm 6: tying a phrase to a subtask with a bag of words and naive Bayes."""

from __future__ import annotations

import contextlib
import io
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from supportive.errors import LearningError, MissingExtraError
from supportive.examples import load
from supportive.language.evaluation import matcher_accuracy, read_utterance_set
from supportive.language.grounding import (
    Candidate,
    PhraseMatcher,
    from_task,
    is_confident,
    normalise_words,
    stem,
    subtask_descriptions,
)
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode
from supportive.tasks.spec import Action, TaskSpec

HELD_OUT = Path(__file__).parents[1] / "data" / "chair-utterances.yaml"

# Measured on tests/data/chair-utterances.yaml (82 subtask phrases from 77 utterances) with the default
# matcher: top-1 0.902, top-3 0.951; the floors sit a little below.
TOP1_FLOOR = 0.85
TOP3_FLOOR = 0.92


def shelf() -> TaskSpec:
    """A small shelf whose answers are known by construction."""
    actions = (
        Action("get_board", "pick up the bottom board"),
        Action("place_board", "lay the bottom board on the floor"),
        Action("glue_left", "glue the left side panel to the board"),
        Action("glue_right", "glue the right side panel to the board"),
        Action("nail_back", "nail the back panel"),
        Action("paint", "paint the shelf white"),
    )
    a = {x.id: ActionNode(x.id) for x in actions}
    structure = ChainNode(
        (
            ChainNode((a["get_board"], a["place_board"]), name="Prepare base"),
            CliqueNode((a["glue_left"], a["glue_right"]), name="Attach sides"),
            ChainNode((a["nail_back"],)),  # unnamed: never a candidate
            ChainNode((a["paint"],), name="Finish shelf"),
        ),
        name="Build shelf",
    )
    return TaskSpec("shelf", actions, structure)


@pytest.fixture(scope="module")
def matcher() -> PhraseMatcher:
    return from_task(shelf())


@pytest.fixture(scope="module")
def chair() -> PhraseMatcher:
    return from_task(load("ikea-chair"))


def test_stem_joins_verb_forms() -> None:
    assert len({stem(w) for w in ["attaching", "attached", "attaches", "attach"]}) == 1
    assert len({stem(w) for w in ["placing", "place", "placed", "places"]}) == 1
    assert len({stem(w) for w in ["putting", "put", "puts"]}) == 1
    assert stem("screws") == stem("screw") and stem("frames") == stem("frame")


def test_normalise_words_drops_stop_words_and_punctuation() -> None:
    assert normalise_words("When I'm gluing the LEFT side-panel, please!") == ["glu", "left", "sid", "panel"]
    assert normalise_words("the a of and please robot") == []


def test_subtask_descriptions_of_named_nodes_only() -> None:
    described = subtask_descriptions(shelf())
    assert list(described) == ["Build shelf", "Prepare base", "Attach sides", "Finish shelf"]
    assert described["Attach sides"] == [
        "Attach sides",
        "glue the left side panel to the board",
        "glue the right side panel to the board",
    ]
    assert "nail the back panel" in described["Build shelf"]
    assert all("nail the back panel" not in texts for key, texts in described.items() if key != "Build shelf")


def test_subtask_descriptions_of_a_learned_htn_and_ids_without_text() -> None:
    spec = TaskSpec("t", (Action("pick_up_cup"), Action("pour", "pour the tea")))
    htn = HTN(
        "t",
        (ChainNode((ActionNode("pick_up_cup"),), name="Cup"), ChainNode((ActionNode("pour"),), name="Cup")),
    )
    assert subtask_descriptions(spec, htn) == {"Cup": ["Cup", "pick_up_cup", "pour the tea"]}
    assert from_task(spec, htn).best("picking up the cup").key == "Cup"


@pytest.mark.parametrize(
    ("phrase", "key"),
    [
        ("gluing the side panels", "Attach sides"),
        ("gluing on the left panel", "Attach sides"),
        ("painting", "Finish shelf"),
        ("painting the shelf white", "Finish shelf"),
        ("laying down the bottom board", "Prepare base"),
        ("picking up the board", "Prepare base"),
        ("nailing the back panel", "Build shelf"),  # its own node is unnamed: the root holds it
        ("building the shelf", "Build shelf"),
    ],
)
def test_known_answers_on_a_small_structure(matcher: PhraseMatcher, phrase: str, key: str) -> None:
    assert matcher.best(phrase).key == key


def test_candidates_follow_algorithm_6(matcher: PhraseMatcher) -> None:
    candidates = matcher.candidates("gluing the side panels", alpha=3)
    assert [c.key for c in candidates] == ["Attach sides", "Build shelf", "Prepare base"]
    probabilities = [c.probability for c in candidates]
    assert probabilities == sorted(probabilities, reverse=True)
    posterior, grounded = matcher.posterior("gluing the side panels")
    assert grounded and posterior.sum() == pytest.approx(1.0)
    # the loop of Algorithm 6 is the posterior's order (ties by key order)
    order = sorted(range(len(matcher.keys)), key=lambda i: (-posterior[i], i))
    assert [c.key for c in matcher.candidates("gluing the side panels", alpha=4)] == [
        matcher.keys[i] for i in order
    ]
    assert len(matcher.candidates("gluing", alpha=10)) == len(matcher.keys)
    assert matcher.candidates("gluing", alpha=0) == []


def test_scores_are_naive_bayes(matcher: PhraseMatcher) -> None:
    """p(g | Λ) ∝ p(g) Π_i p(λ_i | g), with p(λ | g) the smoothed, length-normalised word frequency."""
    words = matcher.words("gluing the left panel")
    model = matcher._model
    index = matcher._index
    log_joint = np.log(matcher.prior) + sum(model.feature_log_prob_[:, index[w]] for w in words)
    expected = np.exp(log_joint - log_joint.max())
    expected /= expected.sum()
    posterior, _ = matcher.posterior("gluing the left panel")
    np.testing.assert_allclose(posterior, expected)


def test_prior_breaks_what_words_cannot() -> None:
    twins = PhraseMatcher({"a": ["red box"], "b": ["red box"]}, prior={"a": 1, "b": 3})
    candidates = twins.candidates("the red box")
    assert [c.key for c in candidates] == ["b", "a"]
    assert [c.probability for c in candidates] == pytest.approx([0.75, 0.25])
    leaning = from_task(
        shelf(), prior={"Build shelf": 1, "Prepare base": 1, "Attach sides": 1, "Finish shelf": 20}
    )
    assert leaning.best("gluing the side panels").key == "Attach sides"  # words outweigh a 20:1 prior here
    unknown = leaning.candidates("zebra xylophone", alpha=4)
    assert unknown[0].key == "Finish shelf"
    assert all(not c.grounded for c in unknown)
    assert [c.probability for c in unknown] == pytest.approx(
        sorted([20 / 23, 1 / 23, 1 / 23, 1 / 23], reverse=True)
    )
    assert not is_confident(unknown)


def test_unknown_words_give_the_uniform_prior(matcher: PhraseMatcher) -> None:
    candidates = matcher.candidates("zebra", alpha=4)
    assert [c.probability for c in candidates] == pytest.approx([0.25] * 4)
    assert [c.key for c in candidates] == list(matcher.keys)  # ties keep the given order
    assert not is_confident(candidates)


@pytest.mark.parametrize(
    ("phrase", "key"),
    [
        ("gluing the sdie panels", "Attach sides"),
        ("glueing the left pannel", "Attach sides"),
        ("paitning the shelf", "Finish shelf"),
        ("laying down the botom board", "Prepare base"),
    ],
)
def test_typo_tolerance(matcher: PhraseMatcher, phrase: str, key: str) -> None:
    assert matcher.best(phrase).key == key


def test_typo_tolerance_can_be_turned_off() -> None:
    strict = from_task(shelf(), typo_cutoff=1.0)
    assert strict.words("paitning") == []
    assert strict.words("painting") == ["paint"]


def test_is_confident() -> None:
    assert is_confident([Candidate("a", 0.8), Candidate("b", 0.1)])
    assert not is_confident([Candidate("a", 0.59), Candidate("b", 0.1)])
    assert is_confident([Candidate("a", 0.65), Candidate("b", 0.35)])
    assert not is_confident([Candidate("a", 0.65), Candidate("b", 0.35)], margin=0.4)
    assert not is_confident([Candidate("a", 0.5), Candidate("b", 0.4)], threshold=0.5)
    assert is_confident([Candidate("a", 0.5), Candidate("b", 0.2)], threshold=0.5)
    assert is_confident([Candidate("a", 0.7)])
    assert not is_confident([])
    assert not is_confident([Candidate("a", 0.99, grounded=False)])


def test_bad_input_is_refused() -> None:
    with pytest.raises(LearningError, match="no named subtasks"):
        PhraseMatcher({})
    with pytest.raises(LearningError, match="no descriptive words"):
        PhraseMatcher({"x": ["the", "and"]})
    with pytest.raises(LearningError, match="unknown subtasks"):
        from_task(shelf(), prior={"Nope": 1.0})
    with pytest.raises(LearningError, match="positive"):
        from_task(shelf(), prior={"Build shelf": 0.0})
    with pytest.raises(LearningError, match="no named subtasks"):
        from_task(TaskSpec("bare", (Action("a", "do a"),), ChainNode((ActionNode("a"),))))


# The development phrases the matcher's defaults (smoothing, name weight, total) were chosen on; they are not
# in the held-out set. At the defaults: top-1 0.84, top-3 0.92.
DEVELOPMENT = [
    ("getting the left frame ready", "Prepare left frame"),
    ("setting up the right frame", "Prepare right frame"),
    ("putting the pegs in the left frame", "Add left pegs"),
    ("pegs on the right side", "Add right pegs"),
    ("mounting the rails", "Mount supports"),
    ("the front support rail", "Mount front support"),
    ("seating the back rail on the pegs", "Mount back support"),
    ("the four bolts", "Fasten nuts and bolts"),
    ("tightening the nuts", "Fasten nuts and bolts"),
    ("the front right nut and bolt", "Fasten front right bolt"),
    ("bolting the rear left corner", "Fasten rear left bolt"),
    ("inserting the rear right bolt", "Fasten rear right bolt"),
    ("laying the seat on", "Attach seat"),
    ("driving the seat screws", "Screw seat"),
    ("screwing the seat on", "Screw seat"),
    ("building the chair", "Assemble chair"),
    ("making the frame", "Build frame"),
    ("preparing both frames", "Prepare side frames"),
    ("the side frames", "Prepare side frames"),
    ("putting the seat on the chair", "Attach seat"),
    ("standing the left frame on the table", "Prepare left frame"),
    ("the front left bolt", "Fasten front left bolt"),
    ("attaching the supports", "Mount supports"),
    ("the whole chair", "Assemble chair"),
    ("picking up the seat", "Attach seat"),
]


def test_development_phrases(chair: PhraseMatcher) -> None:
    ranked = [[c.key for c in chair.candidates(phrase)] for phrase, _ in DEVELOPMENT]
    assert np.mean([r[0] == gold for r, (_, gold) in zip(ranked, DEVELOPMENT, strict=True)]) >= 0.8
    assert np.mean([gold in r for r, (_, gold) in zip(ranked, DEVELOPMENT, strict=True)]) >= 0.88


def _held_out_phrases() -> list[tuple[str, str]]:
    return read_utterance_set(HELD_OUT)


def test_held_out_set_is_about_the_chairs_subtasks(chair: PhraseMatcher) -> None:
    pairs = _held_out_phrases()
    assert len(pairs) >= 60
    assert {gold for _, gold in pairs} <= set(chair.keys)


def test_held_out_accuracy(chair: PhraseMatcher) -> None:
    pairs = _held_out_phrases()
    accuracy = matcher_accuracy(chair, pairs)
    assert accuracy.n == len(pairs)
    assert accuracy.top1 >= TOP1_FLOOR, f"top-1 accuracy {accuracy.top1:.3f}"
    assert accuracy.top3 >= TOP3_FLOOR, f"top-3 accuracy {accuracy.top3:.3f}"


def test_confident_answers_are_right_on_the_held_out_set(chair: PhraseMatcher) -> None:
    confident = [(chair.candidates(p), gold) for p, gold in _held_out_phrases()]
    confident = [(c, gold) for c, gold in confident if is_confident(c)]
    assert len(confident) >= 10
    assert all(c[0].key == gold for c, gold in confident)


def test_deterministic(chair: PhraseMatcher) -> None:
    again = from_task(load("ikea-chair"))
    for phrase, _ in _held_out_phrases():
        assert chair.candidates(phrase, alpha=5) == again.candidates(phrase, alpha=5)


_SCRIPT = """
import json, yaml
from supportive.examples import load
from supportive.language.grammar import parse_utterance
from supportive.language.grounding import from_task
m = from_task(load("ikea-chair"))
out = []
for item in yaml.safe_load(open({path!r}, encoding="utf-8"))["utterances"]:
    r = parse_utterance(item["text"])
    phrases = getattr(r, "subtask_phrases", None) or (getattr(r, "subtask_phrase", None) or r.behavior_phrase,)
    out.append([repr(r)] + [[c.key, round(c.probability, 12)] for p in phrases for c in m.candidates(p)])
print(json.dumps(out))
"""


def test_same_answers_under_another_hash_seed() -> None:
    """Nothing depends on set or dict order that Python's hash seed would change: the answers here, and in a
    fresh interpreter whose hash seed is another than this one's."""
    script = _SCRIPT.format(path=str(HELD_OUT))
    here = io.StringIO()
    with contextlib.redirect_stdout(here):
        exec(script, {})  # the script the fresh interpreter runs
    other = "2" if os.environ.get("PYTHONHASHSEED") == "1" else "1"
    env = {**os.environ, "PYTHONHASHSEED": other}
    done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
    assert json.loads(here.getvalue()) == json.loads(done.stdout)


def test_without_scikit_learn_the_matcher_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    for module in ("sklearn", "sklearn.feature_extraction.text", "sklearn.naive_bayes"):
        monkeypatch.setitem(sys.modules, module, None)
    with pytest.raises(MissingExtraError, match=r"needs scikit-learn.*supportive\[language\]"):
        PhraseMatcher({"seat": ["attach the seat"]})
