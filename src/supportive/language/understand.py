"""Understanding what a person asks for (§3.3.3–3.3.4.3): utterances to subtasks, behaviors and regions.

* A condition phrase ("the seat is in place and the seat is not attached to the left frame") is split by the
  grammar into a DNF of phrases (:func:`~supportive.language.grammar.parse_condition`); each phrase is matched
  to a literal by comparing it with every literal the task can speak (each atom's template, said positively
  and negatively, :meth:`TaskStates.say`): the exact words first, then the best bag-of-words overlap.
* A subtask phrase is grounded with Algorithm 6 (:class:`~supportive.language.grounding.PhraseMatcher`).
* A behavior phrase is matched against the task's behaviors; an unknown one becomes a new behavior whose
  category is guessed from its verb.

:class:`Understanding` turns a :class:`~supportive.language.grammar.Preference` into the updated behavior and
tells whether it needs the person to confirm the subtask it chose.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from functools import cached_property

from supportive.language.grammar import Preference, UnderstandingError, parse_condition
from supportive.language.grounding import Candidate, Matcher, from_task, is_confident, normalise_words
from supportive.language.states import TaskStates
from supportive.tasks.behaviors import BehaviorCategory, SupportiveBehavior
from supportive.tasks.formula import DNF, Conjunction, Literal

__all__ = ["MATCHERS", "ConditionReader", "Understanding", "Understood", "guess_category"]

MATCHERS = ("bow", "embeddings")
"""The subtask matchers: bag of words (Algorithm 6 as in the thesis) or sentence embeddings."""

_CATEGORY_VERBS: dict[BehaviorCategory, tuple[str, ...]] = {
    BehaviorCategory.MATERIALS_RETRIEVAL: ("give", "hand", "bring", "fetch", "pass", "get", "find"),
    BehaviorCategory.MATERIALS_STABILIZATION: ("hold", "steady", "keep", "brace", "stabilize", "stabilise"),
    BehaviorCategory.COLLABORATIVE_OBJECT_MANIPULATION: ("lift", "carry", "move", "turn", "flip", "rotate"),
    BehaviorCategory.TASK_PROGRESSION_GUIDANCE: ("point", "show", "tell", "remind", "guide", "suggest"),
    BehaviorCategory.ENHANCING_AWARENESS: ("light", "warn", "watch", "announce", "alert", "look"),
}


def guess_category(phrase: str) -> BehaviorCategory:
    """The taxonomy category (§3.1) a behavior phrase most likely belongs to, from its verbs.

    >>> guess_category("hold the rear frame steady").value, guess_category("give me screws").value
    ('materials stabilization', 'materials retrieval')
    """
    words = phrase.lower().split()
    for category, verbs in _CATEGORY_VERBS.items():
        if words and words[0] in verbs:
            return category
    for category, verbs in _CATEGORY_VERBS.items():
        if any(w in verbs for w in words):
            return category
    return BehaviorCategory.MATERIALS_RETRIEVAL


def _content(text: str) -> frozenset[str]:
    return frozenset(normalise_words(text))


class ConditionReader:
    """Reads condition phrases as formulas over a task's predicates.

    Args:
        states: The task's states (its truth table names every atom it can speak of).
        cutoff: Least word overlap (Jaccard, 0–1) a phrase needs with a literal's words to be read as it.

    >>> from supportive.io import parse_task_file
    >>> reader = ConditionReader(TaskStates.of(parse_task_file("examples/ikea-chair.yaml")))
    >>> str(reader.read("the seat is in place and the seat is not attached to the left frame"))
    'not attached(seat, left_frame) and placed(seat)'
    """

    def __init__(self, states: TaskStates, cutoff: float = 0.6) -> None:
        self.states = states
        self.cutoff = cutoff

    @cached_property
    def _spoken(self) -> list[tuple[str, frozenset[str], Literal]]:
        out = []
        for atom in self.states.table.atoms:
            for positive in (True, False):
                literal = Literal(atom, positive)
                words = self.states.say(literal)
                out.append((" ".join(words.lower().split()), _content(words), literal))
        return out

    def literal(self, phrase: str, positive: bool = True) -> Literal:
        """The literal a phrase says (``positive`` False: the phrase was negated by the grammar).

        Raises:
            UnderstandingError: when no literal is near enough, naming the phrase.
        """
        text = " ".join(re.sub(r"[^\w\s']", " ", phrase.lower()).split())
        for spoken, _, literal in self._spoken:
            if spoken == text:
                return literal if positive else literal.negated()
        words = _content(text)
        scored = []
        for _, content, literal in self._spoken:
            union = words | content
            if union and literal.positive:
                scored.append((len(words & content) / len(union), literal))
        best = max(scored, key=lambda x: x[0], default=(0.0, None))
        if best[1] is None or best[0] < self.cutoff:
            example = self.states.say(Literal(self.states.table.atoms[-1]))
            raise UnderstandingError(
                phrase, None, "", f"a condition in the task's words, like '{example}'"
            )
        return best[1] if positive else best[1].negated()

    def read(self, text: str) -> DNF:
        """A whole condition ("A and not B or C") as a formula.

        Raises:
            UnderstandingError: when the grammar cannot split it or a part is not a known condition.
        """
        clauses = []
        for clause in parse_condition(text):
            clauses.append(Conjunction(frozenset(self.literal(phrase, positive) for phrase, positive in clause)))
        return DNF(tuple(clauses))


@dataclass(frozen=True)
class Understood:
    """What the robot made of a preference.

    Attributes:
        behavior: The behavior as it will be after the change.
        created: True when it is a new behavior.
        subtasks: For each subtask phrase, the candidates Algorithm 6 ranked (best first).
        confident: False when the person should confirm the subtasks chosen.
        confirmation: The question to ask (or the statement to make when confident).
    """

    behavior: SupportiveBehavior
    created: bool
    subtasks: tuple[tuple[Candidate, ...], ...]
    confident: bool
    confirmation: str


class Understanding:
    """Applies people's preferences to a task's supportive behaviors.

    Args:
        states: The task's states (and, through them, its spec and behaviors).
        alpha: Candidates Algorithm 6 returns per subtask phrase.
        matcher: ``"bow"`` (bag of words, naive Bayes) or ``"embeddings"`` (sentence embeddings; the
            ``embeddings`` extra).

    Raises:
        ValueError: for another matcher name.
    """

    def __init__(self, states: TaskStates, alpha: int = 3, matcher: str = "bow") -> None:
        if matcher not in MATCHERS:
            raise ValueError(f"unknown matcher {matcher!r} (choose {' or '.join(MATCHERS)})")
        self.states = states
        self.alpha = alpha
        self.matcher = matcher
        self.conditions = ConditionReader(states)

    @cached_property
    def subtask_matcher(self) -> Matcher:
        """Algorithm 6 over the task's named subtasks, with the chosen matcher."""
        if self.matcher == "embeddings":
            from supportive.language.embeddings import from_task_embeddings

            return from_task_embeddings(self.states.spec, self.states.structure)
        return from_task(self.states.spec, self.states.structure)

    def behavior_for(self, phrase: str) -> SupportiveBehavior | None:
        """The task's behavior a phrase names (by name or words), or None for a new one."""
        words = _content(phrase)
        best: tuple[float, SupportiveBehavior | None] = (0.0, None)
        for behavior in self.states.spec.behaviors:
            content = _content(behavior.text) | _content(behavior.name.replace("-", " "))
            union = words | content
            score = len(words & content) / len(union) if union else 0.0
            if score > best[0]:
                best = (score, behavior)
        return best[1] if best[0] >= 0.5 else None

    def apply(self, preference: Preference, behavior_phrase: str | None = None) -> Understood:
        """The behavior a preference asks for, changed as it says (not yet saved).

        Args:
            preference: The parsed request.
            behavior_phrase: Which of its behavior phrases (default: the first).

        Raises:
            UnderstandingError: when a condition is not in the task's words.
        """
        phrase = behavior_phrase or preference.behavior_phrases[0]
        ranked = tuple(tuple(self.subtask_matcher.candidates(p, self.alpha)) for p in preference.subtask_phrases)
        chosen = tuple(dict.fromkeys(r[0].key for r in ranked if r))
        confident = all(is_confident(list(r)) for r in ranked)
        existing = self.behavior_for(phrase)
        base = existing or SupportiveBehavior(
            name=_slug(phrase), text=_second_person(phrase), category=guess_category(phrase)
        )
        subtasks = tuple(dict.fromkeys((*base.subtasks, *chosen)))
        initiation = str(self.conditions.read(preference.start)) if preference.start else base.initiation
        termination = str(self.conditions.read(preference.stop)) if preference.stop else base.termination
        updated = replace(base, subtasks=subtasks, initiation=initiation, termination=termination)
        names = " or ".join(chosen) or "any subtask"
        if confident:
            confirmation = f"OK: when you are at {names}, I will {updated.text}."
        else:
            options = "; ".join(
                ", ".join(f"{c.key} ({c.probability:.0%})" for c in r) for r in ranked
            )
            confirmation = f"Do you mean {names}? (I considered: {options}) Yes or no?"
        return Understood(updated, existing is None, ranked, confident, confirmation)


def _slug(phrase: str) -> str:
    words = [w for w in re.sub(r"[^\w\s]", " ", phrase.lower()).split() if w not in {"me", "the", "a", "an"}]
    return "-".join(words[:4]) or "behavior"


def _second_person(phrase: str) -> str:
    """The behavior as the robot says it: "give me screws" → "give you screws"."""
    swapped = {"me": "you", "my": "your", "i": "you", "myself": "yourself"}
    return " ".join(swapped.get(w, w) for w in phrase.split())
