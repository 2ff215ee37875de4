"""Understanding what a person asks for (§3.3.3–3.3.4.3): utterances to subtasks, behaviors and regions.

* A condition phrase ("the seat is in place and the seat is not attached to the left frame") is split by the
  grammar into a DNF of phrases (:func:`~supportive.language.grammar.parse_condition`); each phrase is matched
  to a literal by comparing it with every literal the task can speak (each atom's template, said positively
  and negatively, :meth:`TaskStates.say`): the exact words first, then the best bag-of-words overlap.
* A subtask phrase is grounded with Algorithm 6 (:class:`~supportive.language.grounding.PhraseMatcher`).
* A behavior phrase is matched against the task's behaviors; an unknown one becomes a new behavior whose
  category is told by its verb of help ("give", "hold", "point", …); one with no such verb ("juggle") is
  refused, not made up.

:class:`Understanding` turns a :class:`~supportive.language.grammar.Preference` into the updated behavior (by the
rule of :mod:`supportive.language.preferences`: do it during the named subtasks, or, for "don't …", not there),
tells whether it needs the person to confirm the subtask it chose, and says truthfully what changed.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

from supportive.errors import LanguageError, UnderstandingError, UnknownHelpError
from supportive.language.explain import initiation_states, scope
from supportive.language.grammar import Preference, parse_condition
from supportive.language.grounding import Candidate, Matcher, from_task, is_confident, normalise_words
from supportive.language.preferences import prefer, refuse
from supportive.language.states import TaskStates
from supportive.tasks.behaviors import BehaviorCategory, SupportiveBehavior
from supportive.tasks.formula import DNF, Conjunction, Literal

__all__ = [
    "MATCHERS",
    "ConditionReader",
    "Understanding",
    "Understood",
    "category_of",
    "guess_category",
]

MATCHERS = ("bow", "embeddings")
"""The subtask matchers: bag of words (Algorithm 6 as in the thesis) or sentence embeddings."""

_CATEGORY_VERBS: dict[BehaviorCategory, tuple[str, ...]] = {
    BehaviorCategory.MATERIALS_RETRIEVAL: ("give", "hand", "bring", "fetch", "pass", "get", "find"),
    BehaviorCategory.MATERIALS_STABILIZATION: ("hold", "steady", "keep", "brace", "stabilize", "stabilise"),
    BehaviorCategory.COLLABORATIVE_OBJECT_MANIPULATION: ("lift", "carry", "move", "turn", "flip", "rotate"),
    BehaviorCategory.TASK_PROGRESSION_GUIDANCE: ("point", "show", "tell", "remind", "guide", "suggest"),
    BehaviorCategory.ENHANCING_AWARENESS: ("light", "warn", "watch", "announce", "alert", "look"),
}


def category_of(phrase: str) -> BehaviorCategory | None:
    """The taxonomy category (§3.1) of a behavior phrase, from its verbs; None when no word of it is a verb of
    help the robot knows (the phrase asks for something it cannot do).

    >>> category_of("hold the rear frame steady").value, category_of("give me screws").value
    ('materials stabilization', 'materials retrieval')
    >>> category_of("juggle") is None
    True
    """
    words = phrase.lower().split()
    for category, verbs in _CATEGORY_VERBS.items():
        if words and words[0] in verbs:
            return category
    for category, verbs in _CATEGORY_VERBS.items():
        if any(w in verbs for w in words):
            return category
    return None


def guess_category(phrase: str) -> BehaviorCategory:
    """:func:`category_of`, materials retrieval when no verb tells.

    >>> guess_category("hold the rear frame steady").value, guess_category("give me screws").value
    ('materials stabilization', 'materials retrieval')
    """
    return category_of(phrase) or BehaviorCategory.MATERIALS_RETRIEVAL


def _no_such_help(phrase: str, known: Sequence[str]) -> str:
    """What the robot answers a request for help it has no behavior and no verb of help for."""
    kinds = ", ".join(verbs[0] for verbs in _CATEGORY_VERBS.values())
    have = "; ".join(known) or "nothing yet"
    return (
        f"I don't know how to {_second_person(phrase)}. I can help by doing what I already do ({have}), or "
        f"something new that starts with a verb of help ({kinds}, …)."
    )


_FINISHED = re.compile(
    r"\b(?:is|are|was|were|has been|have been|gets?|got)\s+(?:\w+ly\s+)?\w+(?:ed|en|wn)\b"
    r"|\b(?:finished|done|completed?|over)\b"
)
"""A phrase about something finished: "the seat is screwed", "has been fastened", "once screwing seat is done"."""


def _in_tense(literal: Literal, text: str) -> Literal:
    """A subtask literal read by its words in the tense the phrase has: "the seat is screwed" names the
    subtask Screw seat as its words do "you are screwing seat" (``active``), but it says the subtask is
    finished (``done``); any other literal as it is.

    >>> str(_in_tense(Literal("active(Screw seat)"), "the seat is screwed"))
    'done(Screw seat)'
    >>> str(_in_tense(Literal("active(Screw seat)"), "you are screwing the seat"))
    'active(Screw seat)'
    """
    name, _, rest = literal.atom.partition("(")
    if name in ("active", "ready") and _FINISHED.search(text):
        return Literal(f"done({rest}", literal.positive)
    return literal


def _content(text: str) -> frozenset[str]:
    return frozenset(normalise_words(text))


class ConditionReader:
    """Reads condition phrases as formulas over a task's predicates.

    Args:
        states: The task's states (its truth table names every atom it can speak of).
        cutoff: Least word overlap (Jaccard, 0–1) a phrase needs with a literal's words to be read as it.

    >>> from supportive.examples import load
    >>> reader = ConditionReader(TaskStates.of(load("ikea-chair")))
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
        chosen = _in_tense(best[1], text)
        return chosen if positive else chosen.negated()

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
        before: The behavior as it was (None for a new one).
        named: The subtasks the preference was applied to.
        negative: The person asked the robot not to.
        acknowledgement: What the robot says it did (Algorithm 7's explanation of the behavior follows it).
    """

    behavior: SupportiveBehavior
    created: bool
    subtasks: tuple[tuple[Candidate, ...], ...]
    confident: bool
    confirmation: str
    before: SupportiveBehavior | None = None
    named: tuple[str, ...] = ()
    negative: bool = False
    acknowledgement: str = ""


class Understanding:
    """Applies people's preferences to a task's supportive behaviors (the rule: :mod:`.preferences`).

    Args:
        states: The task's states (and, through them, its spec and behaviors).
        alpha: Candidates Algorithm 6 returns per subtask phrase.
        matcher: ``"bow"`` (bag of words, naive Bayes) or ``"embeddings"`` (sentence embeddings; the
            ``embeddings`` extra).

    Raises:
        LanguageError: for another matcher name.
    """

    def __init__(self, states: TaskStates, alpha: int = 3, matcher: str = "bow") -> None:
        if matcher not in MATCHERS:
            raise LanguageError(f"unknown matcher {matcher!r} (choose {' or '.join(MATCHERS)})")
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

    def with_states(self, states: TaskStates) -> Understanding:
        """The same understanding of a task whose behaviors changed; the subtask matcher is kept (behaviors do
        not change the subtasks), so it is not built again."""
        other = Understanding(states, self.alpha, self.matcher)
        other.subtask_matcher = self.subtask_matcher
        return other

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

    def ground(self, preference: Preference) -> tuple[tuple[Candidate, ...], ...]:
        """Algorithm 6 for each subtask phrase of a preference: the ``alpha`` best candidates, best first."""
        return tuple(tuple(self.subtask_matcher.candidates(p, self.alpha)) for p in preference.subtask_phrases)

    def apply(
        self,
        preference: Preference,
        behavior_phrase: str | None = None,
        subtasks: Sequence[str] | None = None,
    ) -> Understood:
        """The behavior a preference asks for, changed as it says (not yet saved).

        Args:
            preference: The parsed request.
            behavior_phrase: Which of its behavior phrases (default: the first).
            subtasks: The subtasks its subtask phrases mean, as the person confirmed them (default: the best
                candidate of each; the result then says whether to confirm).

        Raises:
            UnderstandingError: when a condition is not in the task's words, when the person asks the robot not
                to do something it does not do, or for "don't … until …".
        """
        phrase = behavior_phrase or preference.behavior_phrases[0]
        ranked = self.ground(preference)
        chosen = tuple(dict.fromkeys(subtasks if subtasks is not None else (r[0].key for r in ranked if r)))
        confident = subtasks is not None or all(is_confident(list(r)) for r in ranked)
        start = self.conditions.read(preference.start) if preference.start else None
        stop = self.conditions.read(preference.stop) if preference.stop else None
        existing = self.behavior_for(phrase)
        if preference.negative:
            if existing is None:
                known = ", ".join(b.text for b in self.states.spec.behaviors) or "nothing yet"
                raise UnderstandingError(phrase, None, "", f"one of the behaviors I have ({known})")
            if stop is not None:
                raise UnderstandingError(
                    preference.stop or "", f"don't {phrase}", "'until …' in a request not to", "Don't …, when I am …"
                )
            updated = refuse(self.states, existing, chosen, start)
        elif existing is None:
            category = category_of(phrase)
            if category is None:
                raise UnknownHelpError(phrase, _no_such_help(phrase, [b.text for b in self.states.spec.behaviors]))
            updated = SupportiveBehavior(
                name=_slug(phrase),
                text=_second_person(phrase),
                category=category,
                subtasks=chosen,
                initiation="true" if start is None else str(start),
                termination="false" if stop is None else str(stop),
            )
        else:
            updated = prefer(self.states, existing, chosen, start, stop)
        names = " or ".join(chosen) or "any subtask"
        if confident:
            will = "will not" if preference.negative else "will"
            confirmation = f"OK: when you are {self._activities(chosen)}, I {will} {updated.text}."
        else:
            options = "; ".join(", ".join(f"{c.key} ({c.probability:.0%})" for c in r) for r in ranked)
            confirmation = f"Do you mean {names}? (I considered: {options}) Yes or no?"
        acknowledgement = self._acknowledge(existing, updated, chosen, preference.negative)
        return Understood(
            updated, existing is None, ranked, confident, confirmation, existing, chosen, preference.negative,
            acknowledgement,
        )

    def _activities(self, subtasks: Sequence[str]) -> str:
        return " or ".join(self.states.activity(s) for s in subtasks) or "doing anything"

    def _acknowledge(
        self,
        before: SupportiveBehavior | None,
        after: SupportiveBehavior,
        named: tuple[str, ...],
        negative: bool,
    ) -> str:
        """What the robot says it did, truthfully: whether anything changed, and where it now (never) starts."""
        if before is None:
            return f"OK. I will now {after.text}."
        where = f" while you are {self._activities(named)}" if named else ""
        if _same(self.states, before, after):
            anyway = "do not" if negative else "already"
            return f"I {anyway} {after.text}{where}{' anyway' if negative else ''}; I changed nothing."
        if negative:
            return f"OK. I will no longer {after.text}{where}."
        added = before.subtasks and [s for s in named if s not in before.subtasks]
        said = f"OK. I will now also {after.text}{where}." if added else f"OK. I updated how I {after.text}{where}."
        starts = initiation_states(self.states, after)
        never = [s for s in named if not starts & self.states.during(s)]
        if never:
            said += f" (But that condition never holds while you are {self._activities(never)}: I will not start then.)"
        return said


def _same(states: TaskStates, before: SupportiveBehavior, after: SupportiveBehavior) -> bool:
    """True when a change leaves the behavior where it starts and stops."""
    return (
        initiation_states(states, before) == initiation_states(states, after)
        and scope(states, before) == scope(states, after)
        and states.region(before.termination) & scope(states, before)
        == states.region(after.termination) & scope(states, after)
    )


def _slug(phrase: str) -> str:
    words = [w for w in re.sub(r"[^\w\s]", " ", phrase.lower()).split() if w not in {"me", "the", "a", "an"}]
    return "-".join(words[:4]) or "behavior"


def _second_person(phrase: str) -> str:
    """The behavior as the robot says it: "give me screws" → "give you screws"."""
    swapped = {"me": "you", "my": "your", "i": "you", "myself": "yourself"}
    return " ".join(swapped.get(w, w) for w in phrase.split())
