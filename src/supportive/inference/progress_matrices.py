"""The progress model's enumerated states as sparse matrices, for the exact tracker's vector updates.

Index ``i < n - 1`` is ``states[i]``; the last index is "finished". ``step`` moves probability one step on
(row-stochastic, finished absorbing or restarting); ``to_leaf`` and ``to_action`` spread each state's next
step over the leaves and over the action ids plus the end; ``done`` says which leaves each state has done.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy import sparse

from supportive.learning.distribution import END, ProgressModel
from supportive.tasks.executions import Progress

__all__ = ["ProgressMatrices"]


class ProgressMatrices:
    """Sparse matrices over ``states`` and "finished" (see the module docstring).

    Args:
        model: The progress model.
        states: Its reachable states (``ProgressModel.states``).
        actions: The action ids, in the order of the ``to_action`` columns (then ``<end>``).
        restart: Finished starts the task again instead of staying finished.
    """

    def __init__(
        self, model: ProgressModel, states: Sequence[Progress], actions: Sequence[str], *, restart: bool
    ) -> None:
        self.states = list(states)
        self.index = {s: i for i, s in enumerate(self.states)}
        n = len(self.states) + 1
        self.size = n
        self.finished = n - 1
        leaves = model.leaves
        action_index = {a: i for i, a in enumerate(actions)}
        self.last = np.array([s.last for s in self.states] + [-1], dtype=np.intp)
        self.performing = self.last >= 0
        self.last_or_zero = np.maximum(self.last, 0)
        self.last_plus_one = self.last + 1
        rows, cols, values = [], [], []
        leaf_rows, leaf_cols, leaf_values = [], [], []
        act_rows, act_cols, act_values = [], [], []
        for i, state in enumerate(self.states):
            for leaf, (p, nxt) in model.outcomes(state).items():
                rows.append(i)
                cols.append(self.finished if nxt is None else self.index[nxt])
                values.append(p)
                act_rows.append(i)
                act_cols.append(len(actions) if leaf == END else action_index[leaves[leaf][0]])
                act_values.append(p)
                if leaf != END:
                    leaf_rows.append(i)
                    leaf_cols.append(leaf)
                    leaf_values.append(p)
        initial = [self.index[s] for s in model.executions.initial()]
        if restart:
            for j in initial:  # finished: what the start would do next
                for k in range(len(rows)):
                    if rows[k] == j:
                        rows.append(self.finished)
                        cols.append(cols[k])
                        values.append(values[k] / len(initial))
            restart_actions = [(c, v) for r, c, v in zip(act_rows, act_cols, act_values, strict=True) if r in initial]
            for c, v in restart_actions:
                act_rows.append(self.finished)
                act_cols.append(c)
                act_values.append(v / len(initial))
        else:
            rows.append(self.finished)
            cols.append(self.finished)
            values.append(1.0)
            act_rows.append(self.finished)
            act_cols.append(len(actions))
            act_values.append(1.0)
        self.step = sparse.csr_matrix((values, (rows, cols)), shape=(n, n))
        self.to_leaf = sparse.csr_matrix((leaf_values, (leaf_rows, leaf_cols)), shape=(n, len(leaves)))
        self.to_action = sparse.csr_matrix((act_values, (act_rows, act_cols)), shape=(n, len(actions) + 1))
        done_rows, done_cols = [], []
        for i, state in enumerate(self.states):
            mask, bit = state.done, 0
            while mask:
                if mask & 1:
                    done_rows.append(i)
                    done_cols.append(bit)
                mask >>= 1
                bit += 1
        self.done = sparse.csr_matrix(
            (np.ones(len(done_rows)), (done_rows, done_cols)), shape=(n, len(leaves))
        )
        self.step_t = self.step.T.tocsr()  # column products as row products: vector @ step
        self.done_t = self.done.T.tocsr()
        self.to_leaf_t = self.to_leaf.T.tocsr()
        self.to_action_t = self.to_action.T.tocsr()
        self.initial = np.zeros(n)
        self.initial[initial] = 1.0 / len(initial)

    def advance(self, vector: np.ndarray) -> np.ndarray:
        """``vector @ step``: where probability goes in one step."""
        out: np.ndarray = self.step_t @ vector
        return out
