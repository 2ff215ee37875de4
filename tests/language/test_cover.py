"""Minimal DNF covers of state regions (§3.3.4.3): ILP, brute force and ESPRESSO, λ, precision, no words."""

from __future__ import annotations

import itertools
from collections.abc import Hashable
from fractions import Fraction
from typing import Any, Required, TypedDict

import numpy as np
import pytest
from hypothesis import given, reject
from hypothesis import strategies as st

from supportive.errors import LanguageError, NoCoverError, SupportiveError
from supportive.language.cover import Cover, CoverMethod, describe_precision, minimal_cover
from supportive.language.dnf import DNF, Conjunction, Literal, TruthTable


def neg(atom: str) -> Literal:
    return Literal(atom, False)


def full_table(atoms: list[str]) -> TruthTable:
    """One state per valuation, named by its bits (``"101"``: first and third atoms hold)."""
    rows = list(itertools.product([True, False], repeat=len(atoms)))
    names = ["".join("1" if v else "0" for v in row) for row in rows]
    return TruthTable(names, atoms, np.array(rows, dtype=bool).reshape(len(rows), len(atoms)))


def one_atom_table() -> TruthTable:
    """Three target-like states and two irrelevant ones where p holds, one more irrelevant one where not."""
    states = ["t1", "t2", "t3", "i1", "i2", "i3"]
    return TruthTable.from_sets(states, {"p": ["t1", "t2", "t3", "i1", "i2"]})


# ----- hand-built tables with a known answer -------------------------------------------------------------


@pytest.mark.parametrize("method", ["ilp", "brute-force", "espresso"])
def test_p_and_not_q_or_r(method: CoverMethod) -> None:
    table = full_table(["p", "q", "r"])
    region = DNF.of(["p", neg("q")], ["r"])
    target = table.states_of(region)
    cover = minimal_cover(table, target, method=method)
    assert cover.covered == target
    assert cover.exact and cover.precision == 1.0 and cover.recall == 1.0
    assert set(cover.formula.clauses) == set(region.clauses)
    assert cover.method == method


def test_ilp_formula_is_sorted_and_printable() -> None:
    table = full_table(["p", "q", "r"])
    cover = minimal_cover(table, table.states_of(DNF.of(["p", neg("q")], ["r"])))
    assert str(cover.formula) == "r or p and not q"
    assert cover.objective == pytest.approx(-0.5 * 5)


def test_thesis_example_two_clauses_sharing_a_literal() -> None:
    """ "front frame is present and not attached to left support or … not attached to right support"."""
    atoms = ["present(front)", "attached(front, left)", "attached(front, right)"]
    table = full_table(atoms)
    region = DNF.of([atoms[0], neg(atoms[1])], [atoms[0], neg(atoms[2])])
    cover = minimal_cover(table, table.states_of(region))
    assert cover.exact
    assert set(cover.formula.clauses) == set(region.clauses)


def test_the_whole_counted_region_is_true_and_the_empty_one_false() -> None:
    table = full_table(["p", "q"])
    everything = minimal_cover(table, table.states)
    assert everything.formula == DNF.of(Conjunction.of())
    assert str(everything.formula) == "true"
    nothing = minimal_cover(table, [])
    assert nothing.formula == DNF(())
    assert nothing.exact and nothing.precision == 1.0 and nothing.recall == 1.0 and nothing.objective == 0.0
    assert describe_precision(nothing) == "has no relevant states to cover and covers no irrelevant ones"


def test_dont_care_states_are_free() -> None:
    table = full_table(["p", "q"])
    # Only 11 must be covered and only 00 left out: p (or q) alone will do, covering 10 (don't care).
    cover = minimal_cover(table, ["11"], irrelevant=["00"])
    assert cover.formula.size == 1
    assert cover.exact and cover.precision == 1.0
    assert "11" in cover.covered and "00" not in cover.covered
    assert cover.irrelevant_included == frozenset()


def test_longer_conjunctions_are_needed_for_a_single_valuation() -> None:
    table = full_table(["p", "q", "r"])
    with pytest.raises(NoCoverError) as info:
        minimal_cover(table, ["111"], max_literals=2)
    assert info.value.uncoverable == frozenset({"111"})
    assert "'111'" in str(info.value) and "at most 2 literals" in str(info.value)
    assert minimal_cover(table, ["111"], max_literals=3).formula == DNF.of(["p", "q", "r"])


# ----- no words: NoCoverError --------------------------------------------------------------------------


def twin_table() -> TruthTable:
    """a and b look the same (p, not q); c is p and q; d is neither."""
    return TruthTable.from_sets(["a", "b", "c", "d"], {"p": ["a", "b", "c"], "q": ["c"]})


@pytest.mark.parametrize("method", ["ilp", "brute-force", "espresso"])
def test_full_coverage_of_inseparable_states_raises(method: CoverMethod) -> None:
    with pytest.raises(NoCoverError) as info:
        minimal_cover(twin_table(), ["a", "c"], method=method)
    assert info.value.uncoverable == frozenset({"a"})
    assert isinstance(info.value, SupportiveError)
    assert "'a'" in str(info.value)


def test_allowing_irrelevant_states_covers_them_at_a_price() -> None:
    for method in ("ilp", "brute-force", "espresso"):
        cover = minimal_cover(twin_table(), ["a", "c"], allow_irrelevant=True, method=method)
        assert cover.formula == DNF.of(["p"]), method
        assert cover.irrelevant_included == frozenset({"b"})
        assert cover.relevant_omitted == frozenset()
        assert not cover.exact
        assert cover.precision == pytest.approx(2 / 3) and cover.recall == 1.0
        assert describe_precision(cover) == "covers all 2 relevant states and 1 irrelevant one"


def test_partial_coverage_leaves_inseparable_states_out() -> None:
    for method in ("ilp", "espresso"):
        cover = minimal_cover(twin_table(), ["a", "c"], full_coverage=False, lam=0.9, method=method)
        assert cover.covered & {"a", "b", "c", "d"} == {"c"}, method
        assert cover.relevant_omitted == frozenset({"a"})
        assert cover.precision == 1.0 and cover.recall == 0.5
        assert describe_precision(cover) == "misses 1 relevant state of 2 and covers no irrelevant ones"


def test_target_and_irrelevant_must_not_overlap() -> None:
    with pytest.raises(ValueError, match="both target and irrelevant"):
        minimal_cover(twin_table(), ["a"], irrelevant=["a", "b"])


def test_a_short_term_may_reuse_an_irrelevant_state_another_term_pays_for() -> None:
    """p∧q covers the target 111 without irrelevant states, but p is shorter and its only irrelevant state
    (100) is included anyway by ¬q∧¬r, the cheapest way to cover the target 000."""
    states = {"t000": "000", "t111": "111", "i100": "100"}
    states |= {f"i{bits}_{k}": bits for bits in ("001", "010", "011") for k in range(3)}
    values = np.array([[c == "1" for c in bits] for bits in states.values()], dtype=bool)
    table = TruthTable(list(states), ["p", "q", "r"], values)
    for method in ("ilp", "brute-force"):
        cover = minimal_cover(table, ["t000", "t111"], allow_irrelevant=True, max_literals=2, method=method)
        assert cover.formula == DNF.of(["p"], [neg("q"), neg("r")]), method
        assert cover.irrelevant_included == frozenset({"i100"})


# ----- λ -------------------------------------------------------------------------------------------------


def test_large_lambda_omits_relevant_states_small_lambda_includes_irrelevant_ones() -> None:
    table = one_atom_table()
    target = ["t1", "t2", "t3"]
    # Saying p gains 3·(1−λ) and costs 2·λ: worth it below λ = 0.6.
    cautious = minimal_cover(table, target, lam=0.9, full_coverage=False)
    assert cautious.formula == DNF(())
    assert cautious.relevant_omitted == frozenset(target) and cautious.irrelevant_included == frozenset()
    assert cautious.precision == 1.0 and cautious.recall == 0.0
    assert cautious.objective == 0.0
    assert describe_precision(cautious) == "misses 3 relevant states of 3 and covers no irrelevant ones"
    bold = minimal_cover(table, target, lam=0.1, full_coverage=False)
    assert bold.formula == DNF.of(["p"])
    assert bold.irrelevant_included == frozenset({"i1", "i2"}) and bold.relevant_omitted == frozenset()
    assert bold.precision == pytest.approx(3 / 5) and bold.recall == 1.0
    assert bold.objective == pytest.approx(0.1 * 2 - 0.9 * 3)
    assert describe_precision(bold) == "covers all 3 relevant states and 2 irrelevant ones"


def test_a_tie_between_states_goes_to_the_shorter_formula() -> None:
    # At λ = 0.6 saying p is worth exactly nothing: the empty formula is shorter.
    cover = minimal_cover(one_atom_table(), ["t1", "t2", "t3"], lam=0.6, full_coverage=False)
    assert cover.formula == DNF(())


def test_full_coverage_with_irrelevant_states_allowed_ignores_lambda_for_the_target() -> None:
    for lam in (0.1, 0.9):
        cover = minimal_cover(one_atom_table(), ["t1", "t2", "t3"], lam=lam, allow_irrelevant=True)
        assert cover.formula == DNF.of(["p"]) and cover.recall == 1.0


def test_precision_counts_only_target_and_irrelevant_states() -> None:
    table = one_atom_table()
    cover = minimal_cover(table, ["t1", "t2", "t3"], irrelevant=["i3"])  # i1, i2: don't care
    assert cover.formula == DNF.of(["p"])
    assert cover.covered == frozenset({"t1", "t2", "t3", "i1", "i2"})
    assert cover.exact and cover.precision == 1.0


# ----- argument checks -----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"lam": 1.5}, "lam"),
        ({"max_literals": 0}, "max_literals"),
        ({"method": "greedy"}, "unknown method"),
    ],
)
def test_bad_arguments(options: dict[str, Any], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        minimal_cover(twin_table(), ["c"], **options)


def test_espresso_refuses_wide_tables() -> None:
    atoms = [f"a{j}" for j in range(17)]
    table = TruthTable(["s"], atoms, np.zeros((1, 17), dtype=bool))
    with pytest.raises(ValueError, match="2\\^17"):
        minimal_cover(table, ["s"], method="espresso")


def test_brute_force_refuses_many_candidates() -> None:
    table = full_table(["p", "q", "r", "s", "t"])
    target = [name for name in table.states if str(name).count("1") % 2]  # parity: nothing short fits
    with pytest.raises(ValueError, match="brute force"):
        minimal_cover(table, target, method="brute-force", full_coverage=False, max_literals=5)


def test_unknown_state() -> None:
    with pytest.raises(KeyError):
        minimal_cover(twin_table(), ["z"])


def test_time_limited_ilp_reports_optimality() -> None:
    cover = minimal_cover(twin_table(), ["c"], time_limit=10.0)
    assert cover.optimal and cover.formula == DNF.of(["q"])
    assert not minimal_cover(twin_table(), ["c"], method="espresso").optimal


# ----- random tables -------------------------------------------------------------------------------------


class Problem(TypedDict, total=False):
    """A random cover problem: minimal_cover's arguments but the method (the defaults where left out)."""

    table: Required[TruthTable]
    target: Required[list[Hashable]]
    irrelevant: list[Hashable]
    lam: float
    full_coverage: bool
    allow_irrelevant: bool | None
    max_literals: int


@st.composite
def problems(draw: st.DrawFn, max_atoms: int = 4, max_states: int = 12) -> Problem:
    n_atoms = draw(st.integers(1, max_atoms))
    n_states = draw(st.integers(1, max_states))
    values = draw(
        st.lists(
            st.lists(st.booleans(), min_size=n_atoms, max_size=n_atoms), min_size=n_states, max_size=n_states
        )
    )
    roles = draw(st.lists(st.sampled_from("tti-"), min_size=n_states, max_size=n_states))
    states = [f"s{i}" for i in range(n_states)]
    table = TruthTable(states, [f"a{j}" for j in range(n_atoms)], np.array(values, dtype=bool))
    dont_care = draw(st.booleans())
    return {
        "table": table,
        "target": [s for s, r in zip(states, roles, strict=True) if r == "t"],
        "irrelevant": [
            s for s, r in zip(states, roles, strict=True) if r == "i" or (r == "-" and not dont_care)
        ],
        "lam": draw(st.sampled_from([0.0, 0.1, 0.3, 0.5, 0.6, 0.75, 0.9, 1.0])),
        "full_coverage": draw(st.booleans()),
        "allow_irrelevant": draw(st.sampled_from([None, True, False])),
        "max_literals": draw(st.integers(1, n_atoms)),
    }


def outcome(problem: Problem, method: CoverMethod) -> Cover | frozenset[Hashable]:
    try:
        return minimal_cover(**problem, method=method)
    except NoCoverError as error:
        return error.uncoverable
    except LanguageError as error:  # beyond the brute-force oracle's reach (more than 20 candidate terms)
        if method == "brute-force" and "brute force is for at most" in str(error):
            reject()
        raise


def cost(cover: Cover) -> int:
    return sum(1 + len(clause) for clause in cover.formula.clauses)


@given(problems())
def test_ilp_matches_brute_force(problem: Problem) -> None:
    ilp = outcome(problem, "ilp")
    brute = outcome(problem, "brute-force")
    if isinstance(ilp, frozenset) or isinstance(brute, frozenset):
        assert ilp == brute
        return
    assert ilp.objective == pytest.approx(brute.objective, abs=1e-9)
    assert cost(ilp) == cost(brute)
    assert ilp.optimal and brute.optimal


def reference(problem: Problem) -> tuple[Fraction, int] | None:
    """The optimum by the definition: every set of every consistent conjunction, no pruning."""
    table = problem["table"]
    assert isinstance(table, TruthTable)
    target = table.mask_of(problem["target"])
    irrelevant = table.mask_of(problem["irrelevant"])
    full = bool(problem["full_coverage"])
    allow = problem["allow_irrelevant"]
    allow = not full if allow is None else allow
    lam = Fraction(problem["lam"]).limit_denominator(1000)
    max_literals = int(problem["max_literals"])
    terms: list[tuple[np.ndarray, int]] = []
    for k in range(max_literals + 1):
        for atoms in itertools.combinations(table.atoms, k):
            for signs in itertools.product([True, False], repeat=k):
                clause = Conjunction.of(*(Literal(a, s) for a, s in zip(atoms, signs, strict=True)))
                mask = table.conjunction_mask(clause)
                if (mask & target).any() and (allow or not (mask & irrelevant).any()):
                    terms.append((mask, 1 + k))
    best: tuple[Fraction, int] | None = None
    for size in range(int(target.sum()) + 1):
        for chosen in itertools.combinations(terms, size):
            covered = np.zeros(len(table.states), dtype=bool)
            for mask, _ in chosen:
                covered |= mask
            if full and (target & ~covered).any():
                continue
            key = (
                lam * int((covered & irrelevant).sum()) - (1 - lam) * int((covered & target).sum()),
                sum(c for _, c in chosen),
            )
            best = key if best is None or key < best else best
    return best


@given(problems(max_atoms=3, max_states=7))
def test_ilp_matches_the_definition_without_pruning(problem: Problem) -> None:
    target = problem["target"]
    assert isinstance(target, list)
    problem = {**problem, "target": target[:4]}  # keep the reference's search small
    expected = reference(problem)
    got = outcome(problem, "ilp")
    if expected is None:
        assert isinstance(got, frozenset) and got
        return
    assert isinstance(got, Cover)
    assert got.objective == pytest.approx(float(expected[0]), abs=1e-9)
    assert cost(got) == expected[1]


@given(problems())
def test_espresso_is_exact_whenever_the_ilp_is(problem: Problem) -> None:
    table = problem["table"]
    assert isinstance(table, TruthTable)
    exact = Problem(table=table, target=problem["target"], irrelevant=problem["irrelevant"])
    ilp = outcome(Problem(**exact, max_literals=len(table.atoms)), "ilp")
    espresso = outcome(exact, "espresso")
    if isinstance(ilp, frozenset):
        assert espresso == ilp  # both: the target states that share a valuation with an irrelevant one
        return
    assert isinstance(espresso, Cover)
    assert ilp.exact and espresso.exact
    counted = frozenset(problem["target"]) | frozenset(problem["irrelevant"])
    assert ilp.covered & counted == espresso.covered & counted == frozenset(problem["target"])


@given(problems())
def test_cover_fields_agree(problem: Problem) -> None:
    cover = outcome(problem, "ilp")
    if isinstance(cover, frozenset):
        return
    table = problem["table"]
    assert isinstance(table, TruthTable)
    target = frozenset(problem["target"])
    irrelevant = frozenset(problem["irrelevant"])
    assert cover.covered == table.states_of(cover.formula)
    assert cover.irrelevant_included == cover.covered & irrelevant
    assert cover.relevant_omitted == target - cover.covered
    assert cover.exact == (not cover.irrelevant_included and not cover.relevant_omitted)
    hits = len(cover.covered & target)
    lam = float(problem["lam"])
    assert cover.objective == pytest.approx(lam * len(cover.irrelevant_included) - (1 - lam) * hits)
    if problem["full_coverage"]:
        assert cover.recall == 1.0
    allow = problem["allow_irrelevant"]
    if allow is False or (allow is None and problem["full_coverage"]):
        assert not cover.irrelevant_included
    assert all(1 <= len(c) <= int(problem["max_literals"]) or len(c) == 0 for c in cover.formula.clauses)
