"""Understanding what a person says to the robot: preferences and questions (§3.3.3, §3.3.4.3).

One Earley grammar (lark) reads an utterance into one of three forms:

* :class:`Preference` — "When I am {attaching the front rail}, I want you to {give me screws}", with
  conjunctions ("When I am {X} or {X2}, I want you to {Y} and {Y2}") and everyday variants ("while I'm X,
  please Y", "please Y when I'm X", "give me screws while I attach the seat", "whenever I X, Y"), optionally
  with a start condition ("… when/only when/as long as C") and a stop condition ("… until Z");
* :class:`ExplainSubtask` — "How will you help me {attach the front rail}?" (Algorithm 7, first request type);
* :class:`ExplainBehavior` — "When will you {hold the rear frame steady}?" (Algorithm 7, second type).

:func:`parse_condition` splits a condition phrase into a DNF of ``(phrase, positive)`` literals with the same
grammar. Phrases come back normalised: lower case, contractions expanded ("I'm" → "i am"), punctuation
removed; which subtask or predicate a phrase means is decided elsewhere (:mod:`supportive.language.grounding`).

How the grammar decides. Phrases are free word sequences, so an utterance can often be split in several
ways; every word that lands inside a phrase costs one point (a rule priority of -1) and Earley keeps the
cheapest analysis, i.e. the one that explains the most words with structure. A later conjunct is a new
subtask or behavior only when it starts with a verb (an ``-ing`` word, or a verb from a closed list of
everyday verbs) or, for subtasks, with a determiner ("attaching the front rail or {the back rail}": the
verb of the previous conjunct is carried over); otherwise "and"/"or" stay inside the phrase ("fastening the
nuts and bolts", "give me screws and nuts"). In a condition, a later conjunct must read as a clause (hold
"is", "are", "has", "not", …, or a word in "-ed"), so "attached to the left and right frames" stays one
literal.

>>> parse_utterance("When I'm attaching the front rail, I want you to give me screws.")
Preference(subtask_phrases=('attaching the front rail',), behavior_phrases=('give me screws',), start=None, stop=None, negative=False)
>>> parse_utterance("How will you help me attach the seat?")
ExplainSubtask(subtask_phrase='attach the seat')
>>> parse_condition("the seat isn't attached and the front rail is present or the seat is placed")
[[('the seat is attached', False), ('the front rail is present', True)], [('the seat is placed', True)]]
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache
from typing import TypeAlias

from lark import Lark, Token, Tree
from lark.exceptions import LarkError

from supportive.errors import SentenceTooLongError, UnderstandingError
from supportive.io.limits import MAX_SENTENCE_CHARS
from supportive.language.wording import EVERYDAY_VERBS

__all__ = [
    "GRAMMAR",
    "ExplainBehavior",
    "ExplainSubtask",
    "Preference",
    "Utterance",
    "normalise_text",
    "parse_condition",
    "parse_utterance",
]


@dataclass(frozen=True)
class Preference:
    """ "When I am {X} [or {X2} …], I want you to {Y} [and {Y2} …]" with optional raw start/stop conditions.

    ``subtask_phrases`` is empty when the person tied the behavior to a condition only ("give me screws when
    the seat is not attached"). ``negative`` is True when they asked the robot not to ("Don't give me screws
    when I'm fastening the bolts", "never …", "stop …", "I don't want you to …").
    """

    subtask_phrases: tuple[str, ...]
    behavior_phrases: tuple[str, ...]
    start: str | None = None
    stop: str | None = None
    negative: bool = False


@dataclass(frozen=True)
class ExplainSubtask:
    """ "How will you help me {X}?": which supportive behaviors apply during a subtask."""

    subtask_phrase: str


@dataclass(frozen=True)
class ExplainBehavior:
    """ "When will you {Y}?": during which subtasks, and when, a behavior runs."""

    behavior_phrase: str


Utterance: TypeAlias = Preference | ExplainSubtask | ExplainBehavior

_PREFERENCE_FORM = "When I am …, I want you to …"
_SUBTASK_FORM = "How will you help me …?"
_BEHAVIOR_FORM = "When will you …?"


# The grammar reads the normalised text (lower-case words and commas, see `normalise_text`) with lark's
# dynamic Earley lexer. A quoted keyword matches a whole word only (`_parser` bounds each with \b); WORD matches
# any word but the clause openers in HARD, so keywords may also occur inside phrases. Sets of openers that
# many rules expect ("when", "as long as", "I'd like you to", …) are single terminals: fewer Earley items.
# VERB is the closed list `supportive.language.wording.EVERYDAY_VERBS`.
GRAMMAR = r"""
start: _lead? (preference | explain_subtask | explain_behavior) _tail?

// ----- preferences -------------------------------------------------------------------------------------------
?preference: sub_clause _sep request _conds?          -> preference
           | sub_clause _intro neg? behaviors _conds? -> preference
           | bare_preference
           | request _conds? ","? sub_clause _conds? -> preference
           | start_cond _sep request stop_cond?     -> preference
           | request _conds                         -> preference
// "When I am X give me screws": no comma, no "I want you to"; the behavior must start with a verb, and this
// reading loses every tie.
bare_preference.-1: sub_clause neg? vbehaviors _conds? -> preference

sub_clause: SUBWHEN SUBJECT subtasks
          | SUBWHEN ing_subtasks
          | "during" subtasks
subtasks: subtask (_sconj more_subtask)*
ing_subtasks: ing_subtask (_sconj more_subtask)* -> subtasks
subtask: phrase
ing_subtask: ing_phrase -> subtask
?more_subtask: SUBWHEN? SUBJECT? verb_phrase -> subtask
             | _det pw* -> gapped

request: _intro? neg? behaviors
// "don't", "never", "stop", "I don't want you to" …: the person asks the robot not to (a negative preference)
neg: NEG
behaviors: behavior (_bconj more_behavior)*
vbehaviors: first_vbehavior (_bconj more_behavior)* -> behaviors
behavior: phrase
first_vbehavior: verb_phrase -> behavior
more_behavior: _intro? verb_phrase -> behavior

_conds: start_cond stop_cond? | stop_cond start_cond?
start_cond: ","? STARTKW condition_text
stop_cond: ","? STOPKW condition_text
condition_text: pw+

_sep: "," "then"? | "then"
_sconj: ","? SCONJ
_bconj: ","? BCONJ | ","
// "I want you to", "could you", "please", "robot," …: who is asked, politely; any number of them.
_intro: (INTRO ","?)+

// ----- questions (Algorithm 7) -----------------------------------------------------------------------------
explain_subtask: ASK? _how_help _sub_ref
               | ASK? _what_do _sub_when
               | ASK? _what_do_help _sub_ref
_how_help: "how" QMODAL "you" GOING? HELP US?
         | "how" "you" QMODAL HELP US?
         | "how" "do" "you" "plan" "to" HELP US?
_what_do: "what" QMODAL "you" GOING? "do" ("for" US)?
        | "what" "you" QMODAL "do" ("for" US)?
        | "what" ("happens" | "is" "your" "plan" | "help" QMODAL "i" "get")
_what_do_help: "what" QMODAL "you" GOING? "do" "to" HELP US?
_sub_ref: subtask_ref | PREPOSITION subtask_ref | _sub_when
_sub_when: SUBWHEN SUBJECT subtask_ref | SUBWHEN ing_ref | "during" subtask_ref
subtask_ref: phrase
ing_ref: ing_phrase -> subtask_ref

explain_behavior: ASK? "when" QMODAL "you" GOING? behavior_ref
                | ASK? "when" "you" QMODAL "be"? behavior_ref
                | ASK? ("under" | "in") ("what" | "which") SITUATION QMODAL "you" GOING? behavior_ref
                | ASK? "at" "what" ("point" | "time" | "moment" | "stage") QMODAL "you" GOING? behavior_ref
                | ASK? "how" "do" "you" "decide" "when" "to" behavior_ref
behavior_ref: phrase

// ----- around the utterance --------------------------------------------------------------------------------
_lead: LEAD+ ","?
_tail: ","? TAIL+

// ----- conditions (parse_condition): a disjunction of conjunctions of literals -----------------------------
condition: conjunction ("or" more_conjunction)*
conjunction: literal ("and" more_literal)*
more_conjunction: more_literal ("and" more_literal)* -> conjunction
literal: pw+
more_literal: pw* clause_word pw* -> literal
clause_word.-1: CLAUSE_WORD | PARTICIPLE

// ----- phrases ---------------------------------------------------------------------------------------------
// Every word inside a phrase costs one point (priority -1): Earley keeps the analysis with the fewest, i.e.
// the one that explains the most words with structure.
phrase: pw+
verb_phrase: head pw*
ing_phrase: ing pw*
pw.-1: WORD
head.-1: ING | VERB
ing.-1: ING
_det.-1: DET

// ----- error diagnosis: the longest understood beginning of an utterance that failed -----------------------
partial_sub: _lead? sub_clause _sep? _intro? junk?
partial_subject: _lead? SUBWHEN SUBJECT? junk?
partial_condition: _lead? start_cond _sep? _intro? junk?
partial_how: _lead? ASK? (_how_help | _what_do | _what_do_help) junk?
partial_when: _lead? ASK? ("when" QMODAL "you" GOING? | ("under" | "in") ("what" | "which") SITUATION) junk?
partial_request: _lead? (_intro behaviors | vbehaviors) _conds? junk?
junk: skipped+
skipped.-10: WORD | HARD | ","

// ----- terminals: each ends at a word boundary; alternatives are tried in order, longest forms first ---------
SUBWHEN: /(?:whenever|when|while|if|once|as long as|only (?:when|while|if)|(?:every|each|any) time|anytime)\b/
SUBJECT: /(?:(?:i|we) (?:am|are|was|were|will be)|i|we|you (?:see|notice) (?:me|us))\b/
STARTKW: /(?:whenever|when|while|if|once|as long as|(?:but )?only (?:when|if|while)|provided(?: that)?)\b/
STOPKW: /(?:until|till|up (?:until|till)|(?:(?:and|but) )?(?:stop|finish) (?:when|once|after|if|as soon as))\b/
SCONJ: /(?:and or|and|or)\b/
BCONJ: /(?:and|or)\b/
NEG: /(?:do not|not|never|stop|no longer|i do not (?:want|need) you to|i would rather you did not)\b/
INTRO: /(?:please|kindly|then|also|just|always|robot|i (?:want|need|would (?:like|love|prefer)) you to|i would (?:like|appreciate) it if you(?: would| could| can)?|it would be (?:great|nice|helpful|good) if you(?: would| could| can)?|(?:could|can|would|will) you|you (?:need|have|ought) to|you (?:should|can|could|must|will|may)|(?:make|be) sure(?: to| you)?|remember to|go ahead and)\b/
ASK: /(?:please )?(?:(?:can|could) you (?:tell|explain to|explain) me|tell me|explain(?: to me)?|i (?:want|would like) to know|i wonder)\b/
QMODAL: /(?:will|would|can|could|do|are|should|might|shall)\b/
GOING: /going to\b/
HELP: /(?:help(?: out)?|support|assist)\b/
US: /(?:me|us)\b/
PREPOSITION: /(?:with|during|on|to|for|in)\b/
SITUATION: /(?:conditions?|situations?|circumstances|cases?)\b/
LEAD: /(?:(?:hey|hi|ok|okay) robot|robot|um|uh|so|ok|okay|well|alright|hey|hi|oh|now)\b/
TAIL: /(?:thank you|thanks|please|ok|okay|(?:hey |hi |ok |okay )?robot)\b/
CLAUSE_WORD: /(?:is|are|was|were|be|been|has|have|had|not|no|never|does|do|did|can|will|would|should)\b/
PARTICIPLE: /[^\W\d_]{3,}ed\b/
HARD: /(?:when|whenever|while|if|until|till|during|am)\b/
WORD: /(?!(?:when|whenever|while|if|until|till|during|am)\b)[^\W_]+/
ING: /[^\W\d_]+ing\b/
DET: /(?:the|a|an|my|your|its|their|this|that|these|those|both|each|every|one|another|some)\b/
VERB: /(?:{verbs})\b/
%ignore " "
""".replace("{verbs}", "|".join(EVERYDAY_VERBS))

_STARTS = (
    "start",
    "condition",
    "partial_sub",
    "partial_subject",
    "partial_condition",
    "partial_how",
    "partial_when",
    "partial_request",
)

_DETERMINER_WORDS = "the a an my your its their this that these those both each every one another some"
_DETERMINERS = frozenset(_DETERMINER_WORDS.split())
_NEGATIONS = frozenset({"not", "no", "never"})
# A phrase of only these words says nothing ("When I am X, I want you to", "How will you help me"): the
# utterance is treated as unfinished.
_EMPTY_WORDS = (
    "i we you me us it to want would like need please could can will robot the a an and or then also just"
)
_EMPTY = frozenset(_EMPTY_WORDS.split())
_UNDERSTOOD_WORDS = 2
"""Words beyond the empty ones a bare request must have before the robot says it understood it ("stop",
"help" or "I want you to juggle" fit the start of a request, but the robot understood nothing of them)."""
_REQUEST_ONLY = "when you want it"

# What each partial analysis lacks, and the form to ask for (tried in this order; ties go to the earlier).
_PARTIALS = (
    ("partial_sub", "what you want me to do", _PREFERENCE_FORM),
    ("partial_how", "which part of the task you mean", _SUBTASK_FORM),
    ("partial_when", "which of my behaviors you mean", _BEHAVIOR_FORM),
    ("partial_condition", "what you want me to do", "When …, I want you to …"),
    ("partial_subject", "what you are doing", _PREFERENCE_FORM),
    ("partial_request", _REQUEST_ONLY, _PREFERENCE_FORM),
)
_ANY_FORM = f"one of: '{_PREFERENCE_FORM}', '{_SUBTASK_FORM}', '{_BEHAVIOR_FORM}'"


_KEYWORD = re.compile(r'"([a-z]+)"')


@cache
def _parser() -> Lark:
    return Lark(
        _KEYWORD.sub(r"/\1\\b/", GRAMMAR),
        start=list(_STARTS),
        parser="earley",
        lexer="dynamic",
        ambiguity="resolve",
        priority="auto",
        keep_all_tokens=True,
    )


# ----- normalisation ------------------------------------------------------------------------------------------

_TOKEN = re.compile(r"[^\W_]+(?:['’][^\W_]+)*|[,;:—–]")

_WHOLE = {
    "im": "i am",
    "i'm": "i am",
    "i'd": "i would",
    "i've": "i have",
    "i'll": "i will",
    "won't": "will not",
    "wont": "will not",
    "can't": "can not",
    "cant": "can not",
    "cannot": "can not",
    "shan't": "shall not",
    "ain't": "is not",
    "wanna": "want to",
    "gonna": "going to",
    "gotta": "got to",
    "gimme": "give me",
    "lemme": "let me",
    "let's": "let us",
    "pls": "please",
    "plz": "please",
    "u": "you",
    "isnt": "is not",
    "arent": "are not",
    "wasnt": "was not",
    "werent": "were not",
    "hasnt": "has not",
    "havent": "have not",
    "hadnt": "had not",
    "doesnt": "does not",
    "dont": "do not",
    "didnt": "did not",
    "shouldnt": "should not",
    "couldnt": "could not",
    "wouldnt": "would not",
}
_SUFFIXES = (("n't", "not"), ("'re", "are"), ("'ll", "will"), ("'ve", "have"), ("'d", "would"), ("'m", "am"))
_IS_AFTER_WORDS = "it that what there here he she who where when how this"
_IS_AFTER = frozenset(_IS_AFTER_WORDS.split())


def _expand(word: str) -> list[str]:
    """One written word as the words the grammar reads ("isn't" → ["is", "not"])."""
    if word in {",", ";", ":", "—", "–"}:
        return [","]
    word = word.lower().replace("’", "'")
    if word in _WHOLE:
        return _WHOLE[word].split()
    for suffix, full in _SUFFIXES:
        if word.endswith(suffix) and len(word) > len(suffix):
            return [word[: -len(suffix)], full]
    if word.endswith("'s"):
        stem = word[:-2]
        return [stem, "is"] if stem in _IS_AFTER else [stem]
    return [word.replace("'", "")]


def _tokens(text: str) -> tuple[list[str], list[tuple[int, int]]]:
    """The normalised words of ``text`` and, for each, the span of the written word it came from."""
    words: list[str] = []
    spans: list[tuple[int, int]] = []
    for match in _TOKEN.finditer(text):
        for word in _expand(match.group()):
            if word:
                words.append(word)
                spans.append(match.span())
    return words, spans


def normalise_text(text: str) -> str:
    """Lower case, contractions expanded, punctuation dropped (commas kept as their own word).

    >>> normalise_text("Robot, when I’m attaching the seat's screws, I'd like you to… help!")
    'robot , when i am attaching the seat screws , i would like you to help'
    """
    return " ".join(_tokens(text)[0])


# ----- reading the tree -----------------------------------------------------------------------------------


def _words(tree: Tree[Token]) -> list[str]:
    return [str(token) for token in tree.scan_values(lambda v: isinstance(v, Token)) if token != ","]


def _subtrees(tree: Tree[Token], name: str) -> Iterator[Tree[Token]]:
    for child in tree.children:
        if isinstance(child, Tree) and child.data == name:
            yield child


def _child(tree: Tree[Token], names: tuple[str, ...]) -> Tree[Token]:
    return next(c for c in tree.children if isinstance(c, Tree) and c.data in names)


def _conjuncts(clause: Tree[Token]) -> list[str]:
    """The subtask phrases of a ``sub_clause``."""
    phrases: list[list[str]] = []
    for node in _child(clause, ("subtasks",)).children:
        if not isinstance(node, Tree):
            continue
        if node.data == "subtask":
            phrases.append(_words(_child(node, ("phrase", "verb_phrase", "ing_phrase"))))
        elif node.data == "gapped":
            # "attaching the front rail or the back rail": the words before the first determiner of the
            # conjunct before (or its first word) are carried over
            words = _words(node)
            if phrases:
                before = phrases[-1]
                cut = next((i for i, w in enumerate(before) if w in _DETERMINERS), min(1, len(before)))
                words = before[:cut] + words
            phrases.append(words)
    return [" ".join(words) for words in phrases]


def _preference(tree: Tree[Token]) -> Preference:
    negative = next(tree.find_data("neg"), None) is not None
    subtasks: list[str] = []
    behaviors: list[str] = []
    start = stop = None
    for node in tree.children:
        if not isinstance(node, Tree):
            continue
        if node.data == "sub_clause":
            subtasks.extend(_conjuncts(node))
        elif node.data in ("request", "behaviors"):
            group = node if node.data == "behaviors" else _child(node, ("behaviors",))
            for behavior in _subtrees(group, "behavior"):
                behaviors.append(" ".join(_words(_child(behavior, ("phrase", "verb_phrase")))))
        elif node.data == "start_cond":
            start = " ".join(_words(_child(node, ("condition_text",))))
        elif node.data == "stop_cond":
            stop = " ".join(_words(_child(node, ("condition_text",))))
    return Preference(tuple(subtasks), tuple(behaviors), start, stop, negative)


def _utterance(tree: Tree[Token]) -> Utterance:
    body = _child(tree, ("preference", "explain_subtask", "explain_behavior"))
    if body.data == "preference":
        return _preference(body)
    if body.data == "explain_subtask":
        ref = next(body.find_data("subtask_ref"))
        return ExplainSubtask(" ".join(_words(ref)))
    return ExplainBehavior(" ".join(_words(_child(body, ("behavior_ref",)))))


# ----- entry points -------------------------------------------------------------------------------------------


def parse_utterance(text: str) -> Utterance:
    """Read a preference or a question about the robot's help.

    Args:
        text: What the person said or typed.

    Returns:
        A :class:`Preference`, :class:`ExplainSubtask` or :class:`ExplainBehavior` with normalised phrases.

    Raises:
        UnderstandingError: when the utterance fits no form; the message quotes the part that was understood
            and the form to use. :class:`SentenceTooLongError` for one over
            :data:`~supportive.io.limits.MAX_SENTENCE_CHARS` characters.

    >>> parse_utterance("please hold the seat steady while I'm screwing it down, robot")
    Preference(subtask_phrases=('screwing it down',), behavior_phrases=('hold the seat steady',), start=None, stop=None, negative=False)
    >>> parse_utterance("Don't give me screws when I'm fastening the bolts").negative
    True
    >>> parse_utterance("When will you hold the rear frame steady?")
    ExplainBehavior(behavior_phrase='hold the rear frame steady')
    >>> parse_utterance("When I am attaching the seat")
    Traceback (most recent call last):
    ...
    supportive.errors.UnderstandingError: I understood 'When I am attaching the seat' but not what you want me to do; say: When I am …, I want you to …
    """
    if len(text) > MAX_SENTENCE_CHARS:
        raise SentenceTooLongError(text, MAX_SENTENCE_CHARS)
    words, spans = _tokens(text)
    if not words:
        raise UnderstandingError(text, None, "anything", _ANY_FORM)
    try:
        utterance = _utterance(_parser().parse(" ".join(words), start="start"))
    except LarkError:
        raise _diagnose(text, words, spans) from None
    if any(set(phrase.split()) <= _EMPTY for phrase in _phrases(utterance)):
        raise _diagnose(text, words, spans)
    return utterance


def _phrases(utterance: Utterance) -> tuple[str, ...]:
    if isinstance(utterance, Preference):
        return utterance.subtask_phrases + utterance.behavior_phrases
    if isinstance(utterance, ExplainSubtask):
        return (utterance.subtask_phrase,)
    return (utterance.behavior_phrase,)


def _diagnose(text: str, words: list[str], spans: list[tuple[int, int]]) -> UnderstandingError:
    """The error for an utterance that failed: the longest beginning some partial form explains."""
    joined = " ".join(words)
    offsets = [0]
    for word in words[:-1]:
        offsets.append(offsets[-1] + len(word) + 1)
    best: tuple[int, str, str] | None = None
    for start, missing, expected in _PARTIALS:
        try:
            tree = _parser().parse(joined, start=start)
        except LarkError:
            continue
        junk = next(tree.find_data("junk"), None)
        if junk is None:
            count = len(words)
        else:
            first = next(t for t in junk.scan_values(lambda v: isinstance(v, Token)))
            count = offsets.index(first.start_pos) if first.start_pos in offsets else 0
        while count and words[count - 1] == ",":
            count -= 1
        if count and (best is None or count > best[0]):
            best = (count, missing, expected)
    if best is None or (best[1] == _REQUEST_ONLY and len(set(words[: best[0]]) - _EMPTY) < _UNDERSTOOD_WORDS):
        return UnderstandingError(text, None, "anything", _ANY_FORM)  # one verb alone is not a request
    count, missing, expected = best
    understood = text[spans[0][0] : spans[count - 1][1]].strip()
    return UnderstandingError(text, understood, missing, expected)


def parse_condition(text: str) -> list[list[tuple[str, bool]]]:
    """Split a condition phrase into a DNF: a list of conjunctions of ``(phrase, positive)`` literals.

    "or" separates conjunctions and "and" literals; a literal holding "not", "no" or "never" (also from
    "isn't", "hasn't", …) is negative and its phrase is given without the negation. A later conjunct must
    read as a clause (hold "is", "are", "has", "not", …, or a word in "-ed"); otherwise "and"/"or" stay inside
    the literal.

    Args:
        text: A condition, as in :attr:`Preference.start` or :attr:`Preference.stop`.

    Raises:
        UnderstandingError: for an empty condition.

    >>> parse_condition("the front rail is attached to the left and right frames")
    [[('the front rail is attached to the left and right frames', True)]]
    >>> parse_condition("the seat has not been placed or the bolts aren't tight")
    [[('the seat has been placed', False)], [('the bolts are tight', False)]]
    """
    words, _ = _tokens(text)
    words = [w for w in words if w != ","]
    if not words:
        raise UnderstandingError(text, None, "a condition", "… when the seat is not attached")
    try:
        tree = _parser().parse(" ".join(words), start="condition")
    except LarkError:  # pragma: no cover - every word sequence is a condition
        raise UnderstandingError(text, None, "a condition", "… when the seat is not attached") from None
    dnf: list[list[tuple[str, bool]]] = []
    for conjunction in _subtrees(tree, "conjunction"):
        clause: list[tuple[str, bool]] = []
        for literal in _subtrees(conjunction, "literal"):
            literal_words = _words(literal)
            negations = sum(w in _NEGATIONS for w in literal_words)
            kept = [w for w in literal_words if w not in _NEGATIONS and not (negations and w == "yet")]
            clause.append((" ".join(kept), negations % 2 == 0))
        dnf.append(clause)
    return dnf
