"""What the demonstrations show about order and contiguity, and when that is evidence enough.

Two claims a hierarchy makes need evidence from a few demonstrations:

* **x before y.** Demonstrations that perform both always do x first (never the other way round). Real people
  keep habits, so a pair done in the same order by everyone may still commute; the claim is *established*
  when it is seen consistently and either (a) some other step is consistently between the two (it belongs to
  a longer consistently ordered run: ``witnessed``) or (b) at least ``order_support`` demonstrations show
  both (two steps of free relative order come in one order every time with chance ``2^(1-m)``). With an
  ``order_penalty``, the top level's orders face a sharper test instead (:func:`weighed_precedences`): a free
  pair in a partial order is no coin (``a1`` comes before ``b3`` in 19 of the 20 orders of two interleaved
  chains ``a1 < a2 < a3``, ``b1 < b2 < b3``), so an order is weighed by how much more probable it makes the
  demonstrations than the orders around it already do.
* **S is one subtask** (its steps are never interleaved with others). Steps outside S that are seen both
  before and after it (*free* steps) could have been performed in the middle of it; that none ever was is
  the evidence. Were S no subtask, its steps and the free ones would be siblings, done in any order: in a
  demonstration with ``s`` steps of S and ``u`` free steps, the places S's steps take among the ``s + u``
  would be any of the ``C(s + u, s)`` sets alike, ``u + 1`` of which are one run, so S would be contiguous with
  chance ``(u + 1) / C(s + u, s)``; the claim is accepted when the product over the demonstrations is below
  ``evidence`` (or when no step is free: then the order alone keeps S together). (Until issue #23's review
  the chance was ``(2 / (s + 1)) ** u``, each free step in one of S's gaps independently: not what any order
  of siblings gives, never larger and smaller once ``s`` and ``u`` are both 2 or more — for ``s = 2, u = 5``
  0.13 against 0.29 — so subtasks were kept on too little evidence.)
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from supportive.learning.linear_extensions import count_linear_extensions, count_without, covering_pairs

__all__ = [
    "as_matrix",
    "contiguity_chance",
    "established_precedences",
    "establishes_any",
    "matrix_contiguity_chance",
    "padded",
    "pair_counts",
    "position_pair_counts",
    "position_pair_counts_listed",
    "positions_of",
    "supported",
    "weighed_precedences",
]

BoolMatrix = npt.NDArray[np.bool_]
IntMatrix = npt.NDArray[np.int64]


def pair_counts(sequences: Sequence[Sequence[int]], members: Sequence[int]) -> tuple[IntMatrix, IntMatrix]:
    """``(before, together)``: ``before[i, j]`` counts the sequences doing ``members[i]`` before
    ``members[j]``, ``together[i, j]`` those doing both."""
    index = {m: i for i, m in enumerate(members)}
    ranks = np.full((len(sequences), len(members)), -1, dtype=np.int64)
    for row, sequence in zip(ranks, sequences, strict=True):
        order = [index[x] for x in sequence if x in index]
        row[order] = np.arange(len(order))
    return position_pair_counts(ranks)


def position_pair_counts(positions: IntMatrix) -> tuple[IntMatrix, IntMatrix]:
    """:func:`pair_counts` of sequences given as ``positions[s, i]``, where sequence ``s`` does member ``i``
    (-1: not at all; only the order of the positions in a row matters). Sequences doing fewer than two
    members count in neither matrix."""
    present = positions >= 0
    shown = present[present.sum(axis=1) >= 2].astype(np.int64)
    together: IntMatrix = shown.T @ shown
    first = np.where(present, positions, positions.max(initial=0) + 1)  # absent: never before another
    size = positions.shape[1]
    before = np.zeros((size, size), dtype=np.int64)
    step = max(1, len(positions) // max(size, 1))  # a chunk of sequences holds about as many cells as the input
    for start in range(0, len(positions), step):
        before += (first[start : start + step, :, None] < positions[start : start + step, None, :]).sum(axis=0)
    return before, together


def established_precedences(before: IntMatrix, together: IntMatrix, order_support: int) -> BoolMatrix:
    """``E[i, j]``: "i before j" is established (see the module docstring)."""
    consistent: BoolMatrix = (before > 0) & (before.T == 0)
    if not consistent.any():
        return consistent
    as_float = consistent.astype(np.float32)
    witnessed: BoolMatrix = consistent & ((as_float @ as_float) > 0)
    established: BoolMatrix = witnessed | (consistent & (together >= order_support))
    return established


def weighed_precedences(established: BoolMatrix, together: IntMatrix, penalty: float) -> BoolMatrix:
    """The orders of ``established`` (an acyclic relation, ``E[i, j]``: i before j) that the demonstrations
    weigh in for by more than ``penalty`` nats (``together[i, j]``: demonstrations doing both i and j).

    Read every demonstration's order of these steps as drawn uniformly among the orders the relation admits
    (its linear extensions). Dropping an order ``i < j`` that no other order implies (a covering pair)
    multiplies the admitted orders by ``1 / q``, where ``q`` is the share of the looser relation's orders
    that keep ``i`` before ``j``; each of the ``m`` demonstrations doing both was ``1 / q`` times as probable
    with the order, so they weigh ``m · ln(1 / q)`` nats for it: nothing for an order the others already
    imply, ``m · ln 2`` for a pair that would be free, and little for an order the others nearly imply
    (``a1 < b3`` beside two interleaved chains, ``q = 0.95``). The cheapest order below ``penalty`` is
    dropped and the others below it weighed again against what is left (with the orders the drop left
    uncovered), until every order left is worth more (a greedy search for the relation of highest likelihood
    when each order must pay ``penalty``, a likelihood-ratio test at the threshold ``e^penalty``). An order
    once found worth its penalty is not weighed again: dropping others loosens the relation around it, which
    seldom makes it less telling, and weighing every order after every drop made learning a recipe ten times
    slower. ``penalty`` 0 keeps every order; an order whose weight cannot be counted
    (:func:`~supportive.learning.linear_extensions.count_linear_extensions` gives up on a part too large) is
    kept, as the demonstrations show it.

    Every order kept is one the demonstrations keep, so each demonstration keeping ``established`` keeps the
    result.

    >>> first = np.array([[False, True], [False, False]])  # 0 before 1
    >>> six = np.full((2, 2), 6)  # six demonstrations doing both
    >>> bool(weighed_precedences(first, six, penalty=4.0)[0, 1])  # worth 6 ln 2 = 4.16 nats: kept
    True
    >>> bool(weighed_precedences(first, six, penalty=4.5)[0, 1])
    False
    """
    size = len(established)
    if penalty <= 0 or size < 2:
        return established.copy()
    pairs = tuple(sorted((int(u), int(v)) for u, v in zip(*np.nonzero(established), strict=True)))
    weights = tuple(int(together[u, v]) for u, v in pairs)
    kept = np.zeros_like(established)
    for u, v in _weighed(size, pairs, weights, penalty):
        kept[u, v] = True
    return kept


@functools.lru_cache(maxsize=256)  # the slip search weighs the same top levels again and again
def _weighed(size: int, pairs: tuple[tuple[int, int], ...], weights: tuple[int, ...], penalty: float) -> frozenset[tuple[int, int]]:
    """:func:`weighed_precedences` over steps ``0 … size-1`` of ``pairs``, ``weights`` the demonstrations
    doing each pair's two steps."""
    shown = dict(zip(pairs, weights, strict=True))
    kept = set(pairs)
    worth: set[tuple[int, int]] = set()  # orders found worth the penalty (or not countable): kept as they are
    while True:
        total = count_linear_extensions(size, kept)
        if not total:
            break
        cheapest: tuple[float, tuple[int, int]] | None = None
        for pair in covering_pairs(size, kept):
            if pair in worth:
                continue
            looser = count_without(size, kept, pair)
            weight = math.inf if looser is None else shown[pair] * math.log(looser / total)
            if weight >= penalty:
                worth.add(pair)
            elif cheapest is None or weight < cheapest[0]:
                cheapest = (weight, pair)
        if cheapest is None:
            break
        kept.discard(cheapest[1])
    return frozenset(kept)


def position_pair_counts_listed(rows: Sequence[Sequence[int]], size: int) -> tuple[list[list[int]], list[list[int]]]:
    """:func:`position_pair_counts` of the rows of ``positions`` given as lists of ``size`` entries, as nested
    lists: faster than the matrices on a few dozen entries, where numpy's cost per call outweighs its speed
    per entry."""
    before = [[0] * size for _ in range(size)]
    together = [[0] * size for _ in range(size)]
    for row in rows:
        done = [i for i, p in enumerate(row) if p >= 0]
        if len(done) < 2:
            continue
        for i in done:
            before_i, together_i = before[i], together[i]
            for j in done:
                together_i[j] += 1
                before_i[j] += row[i] < row[j]
    return before, together


def establishes_any(before: Sequence[Sequence[int]], together: Sequence[Sequence[int]], order_support: int) -> bool:
    """Whether :func:`established_precedences` of these counts (as nested lists, from
    :func:`position_pair_counts_listed`) holds anywhere; stops at the first pair established."""
    size = len(before)
    consistent = [[before[i][j] > 0 and before[j][i] == 0 for j in range(size)] for i in range(size)]
    for i in range(size):
        for j in range(size):
            if consistent[i][j] and (
                together[i][j] >= order_support or any(consistent[i][m] and consistent[m][j] for m in range(size))
            ):
                return True
    return False


def contiguity_chance(arrays: Sequence[npt.NDArray[np.int64]], members: frozenset[int], size: int) -> float:
    """The chance that ``members`` would be contiguous in every sequence were they and the free steps done in
    any order (1.0 when no step is free); see the module docstring.

    Args:
        arrays: The sequences, as integer arrays of node ids.
        members: The nodes of the would-be subtask.
        size: One more than the largest node id.
    """
    return matrix_contiguity_chance(as_matrix(arrays), list(members), size)


def as_matrix(sequences: Sequence[Sequence[int]] | Sequence[npt.NDArray[np.int64]]) -> IntMatrix:
    """Sequences of node ids as the rows of one matrix, each row padded with -1 after its sequence ends."""
    lengths = list(map(len, sequences))
    return padded(np.fromiter(itertools.chain.from_iterable(sequences), dtype=np.int64, count=sum(lengths)), lengths)


def padded(values: npt.NDArray[np.int64], lengths: Sequence[int]) -> IntMatrix:
    """:func:`as_matrix` of the sequences that ``values`` holds one after the other, of ``lengths``."""
    sizes = np.array(lengths, dtype=np.int64)
    matrix = np.full((len(sizes), int(sizes.max(initial=0))), -1, dtype=np.int64)
    matrix[np.arange(matrix.shape[1]) < sizes[:, None]] = values
    return matrix


def positions_of(nodes: IntMatrix, size: int, absent: int = -1) -> IntMatrix:
    """``at[d, n]``: where row ``d`` of ``nodes`` (:func:`as_matrix`) holds node ``n`` (``absent`` when it does
    not), for the nodes ``0 … size-1``; a node is at most once in a row."""
    at = np.full((len(nodes), size), absent, dtype=np.int64)
    rows, columns = np.nonzero(nodes >= 0)
    at[rows, nodes[rows, columns]] = columns
    return at


def matrix_contiguity_chance(nodes: IntMatrix, members: Sequence[int], size: int) -> float:
    """:func:`contiguity_chance` of sequences given as the rows of ``nodes`` (:func:`as_matrix`)."""
    member = np.zeros(size + 1, dtype=bool)  # the last entry stands for the padding
    member[list(members)] = True
    inside = member[nodes]
    spans = inside.any(axis=1)
    nodes, inside = nodes[spans], inside[spans]
    columns = np.arange(nodes.shape[1])
    first = inside.argmax(axis=1)
    last = nodes.shape[1] - 1 - inside[:, ::-1].argmax(axis=1)
    before = np.zeros(size + 1, dtype=bool)
    after = np.zeros(size + 1, dtype=bool)
    before[nodes[columns < first[:, None]]] = True
    after[nodes[columns > last[:, None]]] = True
    free = before & after & ~member  # the padding is never before a member: never free
    if not free.any():
        return 1.0
    log_chance = 0.0
    for loose, count in zip(free[nodes].sum(axis=1).tolist(), inside.sum(axis=1).tolist(), strict=True):
        # in integers, so that a row with one step of S or no free step adds exactly 0
        log_chance += math.log(loose + 1) - math.log(math.comb(count + loose, count))
    return math.exp(log_chance)


def supported(chance: float, evidence: float) -> bool:
    """True when a contiguity whose chance (:func:`contiguity_chance`) is ``chance`` is evidence enough of one
    subtask: no step was free around it (the order alone keeps it together), or it would have been unlikely
    (below ``evidence``) were it not one."""
    return chance == 1.0 or chance < evidence
