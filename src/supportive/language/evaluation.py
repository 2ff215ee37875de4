"""Measuring subtask matchers on a set of utterances with known answers (the held-out set of the chair in
``tests/data/chair-utterances.yaml`` is one; write your own in the same format).

The format: a YAML mapping with ``utterances``, a list of ``{text, subtasks}``: what a person said and, for
each subtask phrase the grammar finds in it, the subtask meant (a named node of the task's structure).
Utterances without ``subtasks`` are skipped.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from supportive.errors import FileFormatError
from supportive.io.safe_load import load_yaml, read_text
from supportive.language.grammar import ExplainSubtask, Preference, parse_utterance
from supportive.language.grounding import Matcher

__all__ = ["Accuracy", "matcher_accuracy", "read_utterance_set"]


@dataclass(frozen=True)
class Accuracy:
    """Top-1 and top-3 accuracy of a matcher over ``n`` subtask phrases."""

    top1: float
    top3: float
    n: int


def read_utterance_set(path: str | Path) -> list[tuple[str, str]]:
    """The (subtask phrase, gold subtask) pairs of an utterance set, phrases as the grammar returns them.

    Raises:
        FileFormatError: for a missing file, bad YAML, or an utterance whose subtask phrases and answers do
            not pair up.
    """
    file = Path(path)
    data = load_yaml(read_text(file, FileFormatError), file, FileFormatError)
    pairs: list[tuple[str, str]] = []
    for i, item in enumerate((data or {}).get("utterances", [])):
        if "subtasks" not in item:
            continue
        said = parse_utterance(item["text"])
        if isinstance(said, Preference):
            phrases: tuple[str, ...] = said.subtask_phrases
        elif isinstance(said, ExplainSubtask):
            phrases = (said.subtask_phrase,)
        else:
            phrases = ()
        if len(phrases) != len(item["subtasks"]):
            raise FileFormatError(
                f"{len(phrases)} subtask phrases but {len(item['subtasks'])} answers", path=file,
                place=f"utterances[{i}]",
            )
        pairs.extend(zip(phrases, item["subtasks"], strict=True))
    return pairs


def matcher_accuracy(matcher: Matcher, pairs: list[tuple[str, str]]) -> Accuracy:
    """How often the gold subtask is the matcher's first candidate, and among its first three."""
    if not pairs:
        return Accuracy(0.0, 0.0, 0)
    top1 = top3 = 0
    for phrase, gold in pairs:
        keys = [c.key for c in matcher.candidates(phrase, alpha=3)]
        top1 += keys[0] == gold
        top3 += gold in keys
    return Accuracy(top1 / len(pairs), top3 / len(pairs), len(pairs))
