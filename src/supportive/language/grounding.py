"""Which subtask a phrase means: Algorithm 6's bag of words with naive Bayes (§3.3.3).

Each subtask (a named node of the task's CC-HTN) is described by texts: its name and the texts of the actions
under it. A phrase such as "attaching the front rail" is turned into a bag of words and every subtask ``g`` is
scored by ``p(g) Π_i p(λ_i | g)`` (multinomial naive Bayes with additive smoothing, fitted with scikit-learn);
Algorithm 6 returns the ``α`` best subtasks with their probabilities, and a robot confirms with the person
when the best one is not clearly ahead (:func:`is_confident`).

Words are normalised lightly before counting: lower case, punctuation and stop words dropped, crude suffix
stemming ("attaching", "attached" and "attaches" all count as "attach"), and typo tolerance: a word the
descriptions never use is replaced by the closest one they do (difflib, similarity at least 0.8), if any;
words still unknown are ignored. There are no synonyms: a word the descriptions never use ("dowel" for
"peg", "crossbar" for "rail") is no evidence.

The word counts of a subtask are weighted so that its size does not decide (length normalisation, as Rennie
et al. 2003 recommend for naive Bayes on text): every text counts as one unit whatever its length, the name
as two, and each subtask's counts are scaled to the same total. Subtasks nest, so a phrase often fits a
subtask and its parent almost as well: the posterior is then split, and the robot asks. The defaults
(smoothing 0.3, name weight 2, total 10) were chosen on 25 development phrases about the chair, kept apart
from the held-out utterances in tests/data/chair-utterances.yaml on which accuracy is measured.

>>> from supportive.examples import load
>>> matcher = from_task(load("ikea-chair"))
>>> [(c.key, round(c.probability, 2)) for c in matcher.candidates("screwing the seat on", alpha=2)]
[('Screw seat', 0.71), ('Attach seat', 0.2)]
>>> candidates = matcher.candidates("tightening the rear left nut")
>>> candidates[0].key, is_confident(candidates)
('Fasten rear left bolt', False)
"""

from __future__ import annotations

import difflib
import math
import re
from abc import ABC, abstractmethod
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from supportive.errors import LearningError, MissingExtraError
from supportive.tasks.htn import HTN, Node, internal_nodes, leaf_actions
from supportive.tasks.spec import TaskSpec

__all__ = [
    "MIN_LIFT",
    "STOP_WORDS",
    "Candidate",
    "Matcher",
    "PhraseMatcher",
    "from_task",
    "is_confident",
    "normalise_words",
    "normalised_prior",
    "stem",
    "subtask_descriptions",
]

_STOP_TEXT = """a an the i me my mine you your we us our it its he she they them their this that these those
    to of on onto in into with without by from for at as up down out off over about through
    and or but then so also just now currently still again
    is am are was were be being been do does did doing done will would can could should shall may might must
    please robot when whenever while if until during
    some any all every each other another one thing things stuff bit part step task
    work working start starting begin beginning busy going get getting"""
STOP_WORDS = frozenset(_STOP_TEXT.split())
"""Words that say nothing about which subtask is meant; dropped from phrases and descriptions alike."""

_WORD = re.compile(r"[^\W_]+")

MIN_LIFT = 1.5
"""A phrase names a key only if its best key is at least this many times likelier than under the prior
(:meth:`Matcher.recognises`): a phrase whose words fit every subtask alike names none of them."""


def stem(word: str) -> str:
    """A crude suffix stemmer: enough for "attaching", "attached", "attaches" and "attach" to meet.

    >>> [stem(w) for w in ["attaching", "attached", "attaches", "attach", "putting", "frames", "pegs", "assembly"]]
    ['attach', 'attach', 'attach', 'attach', 'put', 'fram', 'peg', 'assembly']
    >>> stem("placing") == stem("place") == stem("placed")
    True
    """
    w = word
    if len(w) > 4 and w.endswith("ies"):
        w = w[:-3] + "y"
    elif (len(w) > 3 and w.endswith("es") and w[-3] in "sxz") or (
        len(w) > 4 and w.endswith(("ches", "shes"))
    ):
        w = w[:-2]
    elif len(w) > 3 and w.endswith("s") and not w.endswith(("ss", "us", "is")):
        w = w[:-1]
    for suffix in ("ment", "ing", "ed"):
        if w.endswith(suffix) and len(w) - len(suffix) >= 3:
            w = w[: -len(suffix)]
            break
    if len(w) > 3 and w.endswith("e"):
        w = w[:-1]
    if len(w) > 3 and w[-1] == w[-2] and w[-1] not in "lsz":
        w = w[:-1]
    return w


def normalise_words(text: str) -> list[str]:
    """The bag of words of a text: lower case, no punctuation, no stop words, stemmed.

    >>> normalise_words("When I'm attaching the front frame's rail!")
    ['attach', 'front', 'fram', 'rail']
    """
    words = []
    for raw in _WORD.findall(text.lower().replace("’", "'")):
        if len(raw) < 2 or raw in STOP_WORDS:
            continue
        words.append(stem(raw))
    return words


def _identity(words: list[str]) -> list[str]:
    return words


def _scikit_learn() -> tuple[Any, Any]:
    """scikit-learn's ``CountVectorizer`` and ``MultinomialNB``.

    Raises:
        MissingExtraError: when the ``language`` extra is not installed.
    """
    try:
        from sklearn.feature_extraction.text import CountVectorizer  # type: ignore[import-untyped]
        from sklearn.naive_bayes import MultinomialNB  # type: ignore[import-untyped]
    except ImportError:
        raise MissingExtraError("understanding what people say", "scikit-learn", "language") from None
    return CountVectorizer, MultinomialNB


@dataclass(frozen=True)
class Candidate:
    """A subtask (or other key) a phrase may mean, with its posterior probability.

    ``grounded`` is False when no word of the phrase was known: the probability is then only the prior.
    """

    key: str
    probability: float
    grounded: bool = True


class Matcher(ABC):
    """Ranks keys (subtasks, behaviors) for a phrase: Algorithm 6's loop over a posterior ``p(g | phrase)``.

    Subclasses give :meth:`posterior`; the ranking (:meth:`candidates`, :meth:`best`) is shared.

    Attributes:
        keys: The keys, in a fixed order that also breaks ties.
        prior: ``p(g)`` per key, in :attr:`keys` order.
    """

    keys: tuple[str, ...]
    prior: np.ndarray

    @abstractmethod
    def posterior(self, phrase: str) -> tuple[np.ndarray, bool]:
        """``p(g | phrase)`` for every key (in :attr:`keys` order), and whether the phrase told anything."""

    def candidates(self, phrase: str, alpha: int = 3) -> list[Candidate]:
        """Algorithm 6: the ``alpha`` most likely keys, best first, with posterior probabilities.

        Each round takes the argmax of ``p(g) Π_i p(λ_i | g)`` over the keys not yet chosen (ties go to the
        key given first). The probabilities are normalised over all keys, so they sum to 1 over all of them,
        not over the ``alpha`` returned.
        """
        probabilities, grounded = self.posterior(phrase)
        remaining = list(range(len(self.keys)))
        chosen: list[Candidate] = []
        for _ in range(min(max(alpha, 0), len(self.keys))):
            best = max(remaining, key=lambda i: (probabilities[i], -i))
            remaining.remove(best)
            chosen.append(Candidate(self.keys[best], float(probabilities[best]), grounded))
        return chosen

    def best(self, phrase: str) -> Candidate:
        """The most likely key for the phrase."""
        return self.candidates(phrase, alpha=1)[0]

    def recognises(self, candidates: Sequence[Candidate], min_lift: float = MIN_LIFT) -> bool:
        """False when the phrase the candidates were ranked for names none of the keys: no word of it was known,
        or its best key is hardly likelier than before it was heard (posterior below ``min_lift`` × prior).

        >>> m = PhraseMatcher({"frame": ["build the frame"], "seat": ["attach the seat"], "legs": ["fit legs"]})
        >>> m.recognises(m.candidates("attach the seat")), m.recognises(m.candidates("fly to the moon"))
        (True, False)
        """
        if not candidates or not candidates[0].grounded:
            return False
        prior = float(self.prior[self.keys.index(candidates[0].key)])
        return candidates[0].probability >= min_lift * prior


def normalised_prior(keys: Sequence[str], prior: Mapping[str, float] | None) -> np.ndarray:
    """``p(g)`` over ``keys`` from positive weights (uniform when None).

    Raises:
        LearningError: for unknown keys or a weight that is not positive.
    """
    if prior is None:
        return np.full(len(keys), 1.0 / len(keys))
    unknown = sorted(set(prior) - set(keys))
    if unknown:
        raise LearningError(f"prior names unknown subtasks: {', '.join(map(repr, unknown))}")
    weights = np.array([float(prior.get(key, 0.0)) for key in keys])
    if not np.all(np.isfinite(weights)) or np.any(weights <= 0):
        missing = [key for key, w in zip(keys, weights, strict=True) if not w > 0]
        raise LearningError(f"prior must be positive for every subtask; it is not for {missing[:3]!r}")
    normalised: np.ndarray = weights / weights.sum()
    return normalised


class PhraseMatcher(Matcher):
    """Algorithm 6: rank keys (subtasks) by ``p(g) Π_i p(λ_i | g)`` for a phrase's words ``λ_i``.

    Args:
        descriptions: For each key, the texts that describe it (for a subtask: its name and its actions'
            texts). Keys keep this order, which also breaks ties.
        prior: ``p(g)`` for each key (any positive weights; normalised). Uniform when None.
        smoothing: Additive (Laplace/Lidstone) smoothing of the word counts (the α of ``MultinomialNB``).
        mass: Each key's word counts are scaled to this total, so a big subtask (whose texts hold many words)
            is not penalised for its size, nor a small one favoured.
        first_weight: How many texts the first text of each key (for a subtask: its name) counts for; every
            other text counts as one, whatever its length.
        typo_cutoff: How similar (difflib ratio) an unknown word must be to a known one to stand for it;
            1 turns typo tolerance off.

    Raises:
        LearningError: for no keys, a key with no words, or a prior that is not positive for every key.
        MissingExtraError: without scikit-learn (the ``language`` extra).

    >>> m = PhraseMatcher({"frame": ["build the frame", "attach legs"], "seat": ["attach the seat", "screw it"]})
    >>> [c.key for c in m.candidates("screwing the seet on")]
    ['seat', 'frame']
    >>> m.best("build the frmae").key
    'frame'
    """

    def __init__(
        self,
        descriptions: Mapping[str, Sequence[str]],
        prior: Mapping[str, float] | None = None,
        *,
        smoothing: float = 0.3,
        mass: float = 10.0,
        first_weight: float = 2.0,
        typo_cutoff: float = 0.8,
    ) -> None:
        self.keys: tuple[str, ...] = tuple(descriptions)
        if not self.keys:
            raise LearningError("no subtasks to match phrases against: the task has no named subtasks")
        texts: list[list[str]] = []
        owner: list[int] = []
        weight: list[float] = []
        for k, key in enumerate(self.keys):
            described = [
                (j, words) for j, text in enumerate(descriptions[key]) if (words := normalise_words(text))
            ]
            if not described:
                raise LearningError(f"subtask {key!r} has no descriptive words")
            for j, words in described:
                texts.append(words)
                owner.append(k)
                weight.append(first_weight if j == 0 else 1.0)
        self.prior = normalised_prior(self.keys, prior)
        self.smoothing = smoothing
        self.typo_cutoff = typo_cutoff
        count_vectorizer, multinomial_nb = _scikit_learn()
        self._vectorizer = count_vectorizer(analyzer=_identity)
        per_text = self._vectorizer.fit_transform(texts).toarray().astype(float)
        per_text *= (np.array(weight) / per_text.sum(axis=1))[:, None]
        counts = np.zeros((len(self.keys), per_text.shape[1]))
        np.add.at(counts, np.array(owner), per_text)
        counts *= mass / counts.sum(axis=1, keepdims=True)
        self._model = multinomial_nb(alpha=smoothing, fit_prior=False, class_prior=self.prior)
        self._model.fit(counts, np.arange(len(self.keys)))
        self._index: dict[str, int] = {w: int(i) for w, i in self._vectorizer.vocabulary_.items()}
        self.vocabulary: tuple[str, ...] = tuple(sorted(self._index))
        self._known: dict[str, str | None] = {w: w for w in self._index}

    def words(self, phrase: str) -> list[str]:
        """The phrase's words as the model knows them (typos mapped, unknown words dropped).

        >>> PhraseMatcher({"seat": ["attach the seat"]}).words("attatching the seet and the dowel")
        ['attach']
        """
        out = []
        for word in normalise_words(phrase):
            if word not in self._known:
                close = difflib.get_close_matches(word, self.vocabulary, n=1, cutoff=self.typo_cutoff)
                self._known[word] = close[0] if close else None
            known = self._known[word]
            if known is not None:
                out.append(known)
        return out

    def posterior(self, phrase: str) -> tuple[np.ndarray, bool]:
        """``p(g | phrase)`` for every key (in :attr:`keys` order), and whether any word was known."""
        words = self.words(phrase)
        if not words:
            return self.prior.copy(), False
        counts = self._vectorizer.transform([words])
        joint = np.asarray(self._model.predict_joint_log_proba(counts))[0]
        joint -= joint.max()
        probabilities = np.exp(joint)
        return probabilities / probabilities.sum(), True


def is_confident(candidates: Sequence[Candidate], threshold: float = 0.6, margin: float = 0.2) -> bool:
    """True when the best candidate is likely enough to act on without asking the person to confirm.

    It must rest on at least one known word, have probability at least ``threshold``, and lead the runner-up
    by at least ``margin``.

    >>> is_confident([Candidate("a", 0.9), Candidate("b", 0.05)])
    True
    >>> is_confident([Candidate("a", 0.55), Candidate("b", 0.45)])
    False
    >>> is_confident([Candidate("a", 1.0, grounded=False)])
    False
    """
    if not candidates or not candidates[0].grounded:
        return False
    top = candidates[0].probability
    second = candidates[1].probability if len(candidates) > 1 else 0.0
    return top >= threshold and top - second >= margin and not math.isnan(top)


def subtask_descriptions(spec: TaskSpec, structure: HTN | Node | None = None) -> dict[str, list[str]]:
    """For each named subtask (internal node) of the structure: its name, then its actions' texts.

    Unnamed nodes are skipped; two nodes of the same name share one entry. An action without a text is
    described by its id ("attach_front_support" reads as "attach front support").

    Args:
        spec: The task (for the actions' texts).
        structure: A learned :class:`~supportive.tasks.htn.HTN`, a node, or None for ``spec.structure``.

    >>> from supportive.examples import load
    >>> chair = subtask_descriptions(load("ikea-chair"))
    >>> chair["Mount front support"]
    ['Mount front support', 'pick up the front support rail', 'seat the front support rail on the front pegs']
    >>> len(chair)
    17
    """
    if structure is None:
        structure = spec.structure
    roots: tuple[Node, ...]
    if structure is None:
        roots = ()
    elif isinstance(structure, HTN):
        roots = structure.roots
    else:
        roots = (structure,)
    texts = spec.texts()
    out: dict[str, list[str]] = {}
    for root in roots:
        for node in internal_nodes(root):
            if not node.name:
                continue
            entry = out.setdefault(node.name, [node.name])
            for action in dict.fromkeys(leaf_actions(node)):
                entry.append(texts.get(action, action))
    return out


def from_task(
    spec: TaskSpec,
    structure: HTN | Node | None = None,
    prior: Mapping[str, float] | None = None,
    **options: float,
) -> PhraseMatcher:
    """A :class:`PhraseMatcher` over the named subtasks of a task (see :func:`subtask_descriptions`).

    Raises:
        LearningError: when the structure has no named subtask.
    """
    return PhraseMatcher(subtask_descriptions(spec, structure), prior, **options)
