from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import FormulaError
from supportive.tasks.behaviors import PredicateSpec
from supportive.tasks.formula import DNF, Conjunction, Literal, atom, parse_formula, split_atom


def test_parse_precedence_negation_and_arguments() -> None:
    formula = parse_formula("placed(seat) and not attached(seat,  left_frame) or done(Attach seat)")
    assert formula == DNF.of(
        [Literal("placed(seat)"), Literal("attached(seat, left_frame)", False)], ["done(Attach seat)"]
    )
    assert parse_formula("true") == DNF((Conjunction(frozenset()),))
    assert parse_formula("false") == DNF(()) and str(DNF(())) == "false"
    assert parse_formula("ornament or order(x)") == DNF.of(["ornament"], ["order(x)"])
    assert parse_formula("raining") == DNF.of(["raining"])
    assert parse_formula("notebook(x) and android") == DNF.of(["notebook(x)", "android"])


@pytest.mark.parametrize("bad", ["", "   ", "and x", "p(a", "p(a,)", "p or", "not", "p(a) q(b)"])
def test_bad_formulas_are_reported(bad: str) -> None:
    with pytest.raises(FormulaError):
        parse_formula(bad)


NAMES = st.sampled_from(["p", "held", "attached", "done"])
ARGS = st.lists(st.sampled_from(["seat", "left_frame", "Attach seat", "x"]), max_size=2)
LITERALS = st.builds(lambda n, a, pos: Literal(atom(n, *a), pos), NAMES, ARGS, st.booleans())


@given(st.lists(st.lists(LITERALS, min_size=1, max_size=3), min_size=1, max_size=3))
def test_formulas_print_and_parse_back(clauses: list[list[Literal]]) -> None:
    formula = DNF.of(*clauses)
    assert parse_formula(str(formula)) == formula


def test_atoms_and_templates() -> None:
    assert split_atom(atom("attached", "seat", "left_frame")) == ("attached", ("seat", "left_frame"))
    spec = PredicateSpec("holding", ("x",), "you are holding the ?x", "your hands are free of the ?x")
    assert spec.say(("front_rail",)) == "you are holding the front rail"
    assert spec.say(("seat",), positive=False) == "your hands are free of the seat"
    assert PredicateSpec("raining", (), "it rains").say((), positive=False) == "it is not the case that it rains"
    with pytest.raises(ValueError, match="takes 1 arguments"):
        spec.say(())
