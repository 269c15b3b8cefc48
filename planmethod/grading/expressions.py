"""A small, safe expression language for exercise templates (no ``eval`` of file text).

A template value written as a string starting with ``=`` is an expression::

    "= l_AB + l_BC"              arithmetic: + - * / ^ (power), unary minus, parentheses
    "= 0.5 * links.BC.C[0]"      references: a name from [vars] or a dotted key of the file
    "= round(3 * l_AB, 3)"       functions: min max abs round sqrt sin cos tan asin acos atan2
                                 hypot (angles of sin/cos/tan/asin/acos/atan2 in degrees)
    "= pi / 4"                   constant: pi

The grammar (precedence low → high)::

    expression := term (("+" | "-") term)*
    term       := unary (("*" | "/") unary)*
    unary      := ("-" | "+") unary | power
    power      := atom ("^" unary)?
    atom       := NUMBER | REFERENCE | NAME "(" [expression ("," expression)*] ")"
                | "(" expression ")"

Parsing builds a tree of tuples; evaluation walks it with a resolver for references, so
nothing from the file is ever executed. Every problem is an :class:`ExpressionError` (a
``ValueError``) saying where in the text it is; the template loader turns it into a
:class:`~planmethod.errors.SpecError` naming the file and key.

Examples
--------
>>> evaluate(parse("2 * (l + 1) ^ 2"), {"l": 0.5}.__getitem__)
4.5
>>> evaluate(parse("round(cos(60) * 10, 3)"), lambda name: 0.0)
5.0
>>> sorted(references(parse("a.b[1] + max(c, 2)")))
['a.b[1]', 'c']
>>> parse("2 +* 3")
Traceback (most recent call last):
...
planmethod.grading.expressions.ExpressionError: at character 4: expected a number, ...
"""

from __future__ import annotations

import math
import operator
import re
from collections.abc import Callable
from enum import StrEnum
from functools import partial

from ..errors import value_text
from ..words import Message, message, plural, render

__all__ = ["FUNCTIONS", "ExpressionError", "evaluate", "parse", "references"]

#: The longest expression accepted (characters) and the deepest nesting.
MAX_LENGTH = 500
MAX_DEPTH = 40


class ExpressionError(ValueError):
    """A template expression is malformed or cannot be evaluated: ``message`` says why (and
    where in the text), in the language spoken when it is shown."""

    def __init__(self, message: Message) -> None:
        self.message = message
        super().__init__(message)

    def __str__(self) -> str:
        return render(self.message)


class Token(StrEnum):
    """What a token of the text is (the group of ``_TOKEN`` that matched it)."""

    NUMBER = "number"
    NAME = "name"
    OP = "op"
    END = "end"


class Node(StrEnum):
    """A node of the tree that is not a binary operation (those are keyed by their operator,
    see ``_BINARY``)."""

    NUM = "num"
    REF = "ref"
    NEG = "neg"
    CALL = "call"


def _divide(left: float, right: float) -> float:
    if right == 0:
        raise ExpressionError(message("division by zero"))
    return left / right


def _power(left: float, right: float) -> float:
    if abs(right) > 64:
        raise ExpressionError(message("exponent {exponent:g} is out of range (|x| ≤ 64)",
                                      exponent=right))
    return left ** right


#: operator → its function, for the binary nodes ``(operator, left, right)``
_BINARY: dict[str, Callable[[float, float], float]] = {
    "+": operator.add, "-": operator.sub, "*": operator.mul, "/": _divide, "^": _power}


# the functions below that take a function or a name first are bound to it with
# functools.partial in FUNCTIONS (not built as closures when the module loads)
def _degrees(function: Callable[[float], float], x: float) -> float:
    """``function`` of an angle given in degrees."""
    return function(math.radians(x))


def _round(x: float, digits: float = 0) -> float:
    if digits != int(digits) or not -12 <= digits <= 12:
        raise ExpressionError(message("round(x, digits) needs a whole number of digits in "
                                      "-12…12, got {digits:g}", digits=digits))
    return float(round(x, int(digits)))


def _checked(name: str, function: Callable[[float], float], low: float | None,
             high: float | None, x: float) -> float:
    """``function(x)``, or an :class:`ExpressionError` naming ``name`` where ``x`` lies outside
    [``low``, ``high``] (None: no bound)."""
    if (low is not None and x < low) or (high is not None and x > high):
        raise ExpressionError(message("{function}({x:g}) is undefined", function=name, x=x))
    return function(x)


#: name → (function, least and most arguments)
FUNCTIONS: dict[str, tuple[Callable[..., float], int, int]] = {
    "min": (min, 1, 64),
    "max": (max, 1, 64),
    "abs": (abs, 1, 1),
    "round": (_round, 1, 2),
    "sqrt": (partial(_checked, "sqrt", math.sqrt, 0.0, None), 1, 1),
    "sin": (partial(_degrees, math.sin), 1, 1),
    "cos": (partial(_degrees, math.cos), 1, 1),
    "tan": (partial(_degrees, math.tan), 1, 1),
    "asin": (partial(_checked, "asin", lambda x: math.degrees(math.asin(x)), -1.0, 1.0), 1, 1),
    "acos": (partial(_checked, "acos", lambda x: math.degrees(math.acos(x)), -1.0, 1.0), 1, 1),
    "atan2": (lambda y, x: math.degrees(math.atan2(y, x)), 2, 2),
    "hypot": (math.hypot, 2, 2),
}
CONSTANTS = {"pi": math.pi}

_TOKEN = re.compile(r"""
    (?P<space>\s+)
  | (?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z_][A-Za-z0-9_]*|\[\d+\])*)
  | (?P<op>[-+*/^(),])
""", re.VERBOSE)


def _tokens(text: str) -> list[tuple[str, str, int]]:
    if len(text) > MAX_LENGTH:
        raise ExpressionError(plural("longer than {count} character",
                                     "longer than {count} characters", count=MAX_LENGTH))
    out, position = [], 0
    while position < len(text):
        match = _TOKEN.match(text, position)
        if not match:
            raise ExpressionError(message("at character {position}: unexpected {given!r}",
                                          position=position + 1, given=text[position]))
        if match.lastgroup != "space":
            out.append((Token(match.lastgroup), match.group(), position))
        position = match.end()
    out.append((Token.END, "", len(text)))
    return out


class _Parser:
    def __init__(self, text: str) -> None:
        self.tokens = _tokens(text)
        self.index = 0
        self.depth = 0

    def peek(self) -> tuple[str, str, int]:
        return self.tokens[self.index]

    def take(self) -> tuple[str, str, int]:
        token = self.tokens[self.index]
        self.index += 1
        return token

    def expect(self, value: str) -> None:
        kind, text, position = self.take()
        if text != value or kind is not Token.OP:
            raise ExpressionError(
                message("at character {position}: expected {expected!r}, got {given!r}",
                        position=position + 1, expected=value, given=text) if text else
                message("at character {position}: expected {expected!r}, got the end",
                        position=position + 1, expected=value))

    def deeper(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise ExpressionError(plural("nested deeper than {count} level",
                                         "nested deeper than {count} levels", count=MAX_DEPTH))

    def expression(self):
        self.deeper()
        node = self.term()
        while self.peek()[1] in ("+", "-") and self.peek()[0] is Token.OP:
            sign = self.take()[1]
            node = (sign, node, self.term())
        self.depth -= 1
        return node

    def term(self):
        node = self.unary()
        while self.peek()[1] in ("*", "/") and self.peek()[0] is Token.OP:
            factor = self.take()[1]
            node = (factor, node, self.unary())
        return node

    def unary(self):
        if self.peek()[0] is Token.OP and self.peek()[1] in ("-", "+"):
            sign = self.take()[1]
            self.deeper()
            operand = self.unary()
            self.depth -= 1
            return (Node.NEG, operand) if sign == "-" else operand
        return self.power()

    def power(self):
        node = self.atom()
        if self.peek()[0] is Token.OP and self.peek()[1] == "^":
            self.take()
            self.deeper()
            node = ("^", node, self.unary())
            self.depth -= 1
        return node

    def atom(self):
        kind, text, position = self.take()
        if kind is Token.NUMBER:
            return (Node.NUM, float(text))
        if kind is Token.NAME:
            if self.peek()[1] == "(" and self.peek()[0] is Token.OP:
                if text not in FUNCTIONS:
                    raise ExpressionError(message("at character {position}: unknown "
                                                  "function {name!r}; known: {known}",
                                                  position=position + 1, name=text,
                                                  known=list(FUNCTIONS)))
                self.take()
                arguments = []
                if self.peek()[1] != ")":
                    arguments.append(self.expression())
                    while self.peek()[1] == "," and self.peek()[0] is Token.OP:
                        self.take()
                        arguments.append(self.expression())
                self.expect(")")
                _, least, most = FUNCTIONS[text]
                if not least <= len(arguments) <= most:
                    wanted = str(least) if least == most else f"{least}…{most}"
                    raise ExpressionError(message("at character {position}: {function}() "
                                                  "takes {wanted} argument(s), got {count}",
                                                  position=position + 1, function=text,
                                                  wanted=wanted, count=len(arguments)))
                return (Node.CALL, text, tuple(arguments))
            if text in CONSTANTS:
                return (Node.NUM, CONSTANTS[text])
            return (Node.REF, text)
        if kind is Token.OP and text == "(":
            node = self.expression()
            self.expect(")")
            return node
        raise ExpressionError(
            message("at character {position}: expected a number, a name or '(', got {given!r}",
                    position=position + 1, given=text) if text else
            message("at character {position}: expected a number, a name or '(', got the end",
                    position=position + 1))


def parse(text: str):
    """Parse an expression (without its leading ``=``) into a tree of tuples.

    Raises
    ------
    ExpressionError
        If the text is not an expression of the grammar above.
    """
    parser = _Parser(text)
    if parser.peek()[0] is Token.END:
        raise ExpressionError(message("empty expression"))
    node = parser.expression()
    kind, token, position = parser.peek()
    if kind is not Token.END:
        raise ExpressionError(message("at character {position}: unexpected {given!r}",
                                      position=position + 1, given=token))
    return node


def references(node) -> set[str]:
    """The names an expression tree refers to."""
    kind = node[0]
    if kind is Node.REF:
        return {node[1]}
    children = node[2] if kind is Node.CALL else node[1:]
    if kind is Node.NUM or not children:
        return set()
    return set().union(*(references(child) for child in children))


def evaluate(node, resolve: Callable[[str], float]) -> float:
    """Evaluate an expression tree; ``resolve(name)`` gives the value of a reference.

    Raises
    ------
    ExpressionError
        On division by zero, a result that is not a finite number, or a function outside
        its domain.
    """
    kind = node[0]
    if kind is Node.NUM:
        return node[1]
    if kind is Node.REF:
        value = resolve(node[1])
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ExpressionError(message("{name} is not a number ({given})", name=node[1],
                                          given=value_text(value)))
        return float(value)
    if kind is Node.NEG:
        return -evaluate(node[1], resolve)
    try:
        if kind is Node.CALL:
            function, arguments = FUNCTIONS[node[1]][0], node[2]
            try:
                result = float(function(*(evaluate(a, resolve) for a in arguments)))
            except ValueError as error:
                if isinstance(error, ExpressionError):
                    raise
                raise ExpressionError(message("{function}() failed: {problem}",
                                              function=node[1], problem=str(error))) from None
        else:
            result = _BINARY[kind](evaluate(node[1], resolve), evaluate(node[2], resolve))
    except OverflowError:
        raise ExpressionError(message("the result overflows")) from None
    if isinstance(result, complex) or not math.isfinite(result):
        raise ExpressionError(message("the result is not a finite number ({result})",
                                      result=str(result)))
    return float(result)
