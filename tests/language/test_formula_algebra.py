"""DNF algebra and simplification agree with the regions they denote (random tables, hypothesis)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from supportive.language.dnf import DNF, Conjunction, Literal, TruthTable, simplify

ATOMS = ("p", "q", "r", "s")
LITERALS = st.builds(Literal, st.sampled_from(ATOMS), st.booleans())
FORMULAS = st.lists(st.frozensets(LITERALS, max_size=3).map(Conjunction), max_size=4).map(
    lambda clauses: DNF(tuple(clauses))
)


def _table(seed: int) -> TruthTable:
    rng = np.random.default_rng(seed)
    return TruthTable([f"s{i}" for i in range(10)], list(ATOMS), rng.random((10, len(ATOMS))) < 0.5)


@given(FORMULAS, FORMULAS, st.integers(0, 2**16))
def test_and_or_not_are_intersection_union_complement(a: DNF, b: DNF, seed: int) -> None:
    table = _table(seed)
    assert np.array_equal(table.mask(a & b), table.mask(a) & table.mask(b))
    assert np.array_equal(table.mask(a | b), table.mask(a) | table.mask(b))
    assert np.array_equal(table.mask(~a), ~table.mask(a))


@given(FORMULAS, st.lists(st.integers(0, 9), unique=True), st.integers(0, 2**16), st.data())
def test_simplify_keeps_the_region_within_the_states_that_count(
    formula: DNF, within: list[int], seed: int, data: st.DataObject
) -> None:
    table = _table(seed)
    states = [table.states[i] for i in within]
    fixed = data.draw(st.frozensets(st.sampled_from(sorted(formula.literals())))) if formula.literals() else frozenset()
    short = simplify(formula, table, states, fixed=fixed)
    inside = table.mask_of(states)
    assert np.array_equal(table.mask(short) & inside, table.mask(formula) & inside)
    assert short.size <= formula.size
    for clause in short.clauses:  # each clause is an original one less literals that were not fixed
        assert any(clause.literals <= c.literals and c.literals & fixed <= clause.literals for c in formula.clauses)
