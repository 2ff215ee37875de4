"""Formulas over grounded predicates, as written in task files and spoken back: DNF of literals (§3.3.4.3).

Syntax (a lark grammar)::

    present(front_rail) and not attached(seat, left_frame) or done(Attach seat)

``or`` binds weaker than ``and``; ``not`` negates one atom; parentheses group only an atom's arguments (the
formula is always in disjunctive normal form, which is what the robot reasons and speaks in). An argument is
any text without commas or parentheses (subtask names may hold spaces); ``true`` is the empty conjunction
(always), ``false`` the empty disjunction (never).
Atoms are kept in a canonical spelling: ``name(arg1, arg2)``.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from functools import cache

from lark import Lark, Token, Transformer, UnexpectedInput

from supportive.errors import FormulaError

__all__ = ["DNF", "Conjunction", "Literal", "atom", "parse_formula", "split_atom"]


@dataclass(frozen=True, order=True)
class Literal:
    """A grounded atom (``attached(seat, frame)``) or its negation."""

    atom: str
    positive: bool = True

    def negated(self) -> Literal:
        """The opposite literal."""
        return Literal(self.atom, not self.positive)

    def __str__(self) -> str:
        return self.atom if self.positive else f"not {self.atom}"


@dataclass(frozen=True)
class Conjunction:
    """Literals that must all hold (the empty conjunction holds everywhere)."""

    literals: frozenset[Literal]

    @classmethod
    def of(cls, *literals: Literal | str) -> Conjunction:
        """A conjunction of literals; a plain string is a positive literal."""
        return cls(frozenset(Literal(x) if isinstance(x, str) else x for x in literals))

    @property
    def consistent(self) -> bool:
        """False when it holds an atom both ways (it then denotes no state)."""
        return not any(lit.negated() in self.literals for lit in self.literals)

    def __len__(self) -> int:
        return len(self.literals)

    def __str__(self) -> str:
        return " and ".join(str(lit) for lit in sorted(self.literals)) or "true"


@dataclass(frozen=True)
class DNF:
    """A disjunction of conjunctions (no clause: denotes no state)."""

    clauses: tuple[Conjunction, ...]

    @classmethod
    def of(cls, *clauses: Conjunction | Iterable[Literal | str]) -> DNF:
        """A DNF from conjunctions or iterables of literals."""
        return cls(tuple(c if isinstance(c, Conjunction) else Conjunction.of(*c) for c in clauses))

    @classmethod
    def true(cls) -> DNF:
        """The formula that holds everywhere (one empty clause)."""
        return cls((Conjunction(frozenset()),))

    def __and__(self, other: DNF) -> DNF:
        """Both formulas, distributed back into DNF; inconsistent and repeated clauses are dropped.

        >>> str(parse_formula("p or q") & parse_formula("not p"))
        'not p and q'
        """
        clauses: dict[Conjunction, None] = {}
        for mine in self.clauses:
            for theirs in other.clauses:
                clause = Conjunction(mine.literals | theirs.literals)
                if clause.consistent:
                    clauses[clause] = None
        return DNF(tuple(clauses))

    def __or__(self, other: DNF) -> DNF:
        """Either formula: the clauses of both (repeats dropped)."""
        return DNF(tuple(dict.fromkeys((*self.clauses, *other.clauses))))

    def __invert__(self) -> DNF:
        """The negation, in DNF: the conjunction, over the clauses, of their negated literals (De Morgan).
        The result can be exponentially longer; conditions people say have a few literals.

        >>> str(~parse_formula("p and q or r"))
        'not p and not r or not q and not r'
        """
        negation = DNF.true()
        for clause in self.clauses:
            negation &= DNF(tuple(Conjunction(frozenset({literal.negated()})) for literal in sorted(clause.literals)))
        return negation

    def literals(self) -> frozenset[Literal]:
        """Every literal the formula mentions."""
        return frozenset(lit for clause in self.clauses for lit in clause.literals)

    @property
    def size(self) -> int:
        """Total number of literals: how long it takes to say."""
        return sum(len(c) for c in self.clauses)

    def atoms(self) -> frozenset[str]:
        """Every atom the formula mentions."""
        return frozenset(lit.atom for clause in self.clauses for lit in clause.literals)

    def __str__(self) -> str:
        """The formula in the task-file syntax (it parses back to an equal formula)."""
        return " or ".join(str(c) for c in self.clauses) or "false"


def atom(name: str, *args: str) -> str:
    """The canonical spelling of an atom.

    >>> atom("attached", " seat", "left_frame "), atom("holding_anything")
    ('attached(seat, left_frame)', 'holding_anything')
    """
    cleaned = [" ".join(a.split()) for a in args]
    return f"{name.strip()}({', '.join(cleaned)})" if cleaned else name.strip()


def split_atom(text: str) -> tuple[str, tuple[str, ...]]:
    """An atom's predicate name and arguments.

    >>> split_atom("attached(seat, left_frame)"), split_atom("raining")
    (('attached', ('seat', 'left_frame')), ('raining', ()))
    """
    literal = _parse(text).clauses[0].literals
    (only,) = literal
    name, _, rest = only.atom.partition("(")
    return name, tuple(a.strip() for a in rest.rstrip(")").split(",")) if rest else ()


_GRAMMAR = r"""
    ?start: disjunction
          | FALSE -> never
    disjunction: conjunction (OR conjunction)*
    conjunction: TRUE -> empty
               | literal (AND literal)*
    literal: NOT? atom
    atom: NAME ["(" [arg ("," arg)*] ")"]
    arg: ARG
    NOT: /not\b/
    AND: /and\b/
    OR: /or\b/
    TRUE: /true\b/
    FALSE: /false\b/
    NAME: /(?!(and|or|not|true|false)\b)[A-Za-z_][A-Za-z0-9_\-]*/
    ARG: /[^,()]+/
    %import common.WS
    %ignore WS
"""


class _ToDNF(Transformer[Token, DNF]):
    """The parse tree as a :class:`DNF`: lark calls each method by the name of its rule (or alias) in
    ``_GRAMMAR``, so none of them is called by name in Python."""

    def never(self, _: list[object]) -> DNF:
        return DNF(())

    def disjunction(self, parts: list[object]) -> DNF:
        return DNF(tuple(p for p in parts if isinstance(p, Conjunction)))

    def empty(self, _: list[object]) -> Conjunction:
        return Conjunction(frozenset())

    def conjunction(self, parts: list[object]) -> Conjunction:
        return Conjunction(frozenset(p for p in parts if isinstance(p, Literal)))

    def literal(self, parts: list[object]) -> Literal:
        return Literal(str(parts[-1]), positive=len(parts) == 1)

    def atom(self, parts: list[object]) -> str:
        name, *args = parts
        return atom(str(name), *(str(a) for a in args if a is not None))

    def arg(self, parts: list[Token]) -> str:
        return str(parts[0])


@cache
def _parser() -> Lark:
    return Lark(_GRAMMAR, parser="earley")


@cache
def _parse(text: str) -> DNF:
    try:
        tree = _parser().parse(text)
    except UnexpectedInput as exc:
        column = getattr(exc, "column", None)
        where = f" at column {column}" if isinstance(column, int) and column > 0 else ""
        raise FormulaError(
            f"cannot read the formula {text!r}{where} (expected atoms like present(x) joined by and / or, "
            "each optionally preceded by not)"
        ) from None
    result = _ToDNF().transform(tree)
    return result if isinstance(result, DNF) else DNF((result,))


def parse_formula(text: str) -> DNF:
    """Parse a formula (see the module docstring).

    Raises:
        FormulaError: when it does not parse, naming the column.

    >>> f = parse_formula("placed(seat) and not attached(seat,left_frame) or done(Attach seat)")
    >>> str(f)
    'not attached(seat, left_frame) and placed(seat) or done(Attach seat)'
    >>> parse_formula(str(f)) == f
    True
    """
    if not text.strip():
        raise FormulaError("the formula is empty (write 'true' for always, 'false' for never)")
    return _parse(" ".join(text.split()))
