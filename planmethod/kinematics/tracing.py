"""Formulas traced into one straight-line numpy function, evaluated in a reused workspace.

A :class:`Tracer` runs the group kinds' formulas (:mod:`planmethod.kinematics.groups`) on
:class:`Traced` values: each arithmetic operation is recorded instead of done. Constants of the
model fold away as the operations are recorded (a frame point does not move, a zero coordinate
adds nothing, a factor 1 is no multiplication), a negation is carried as a sign until a value
needs it, and an operation already recorded with the same arguments is not recorded again.
:meth:`Tracer.compile` then writes the recorded operations as Python source — one numpy ufunc
call per operation, each writing into a row of a preallocated workspace (``out=``), rows reused
as soon as a value is dead — and compiles it. What the function computes goes straight into the
rows of the result buffer (:class:`Layout` says which row holds what).

Checks are recorded as *guards*: a cheap bound over all angles (``values.min() > bound``); only
where the bound fails is the exact check (a function of the group kind, run on the arrays)
called, which raises the error with its angle, link and message or lets the evaluation go on.

Examples
--------
>>> import math
>>> import numpy as np
>>> tracer = Tracer()
>>> phi = tracer.angles()
>>> c = tracer.apply("cos", phi * (math.pi / 180.0))
>>> tracer.output("x", 0.5 * c + 0.0)
>>> tracer.output("y", 2.0)
>>> compiled = tracer.compile()
>>> rows = compiled.evaluate(np.array([0.0, 120.0]))
>>> compiled.read(rows, "x").round(6).tolist(), compiled.read(rows, "y").tolist()
([0.5, -0.25], [2.0, 2.0])
"""

from __future__ import annotations

import builtins
import math
import threading
import types
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

__all__ = ["CHUNK", "Compiled", "Layout", "Redo", "Traced", "Tracer"]

#: angles evaluated at once: a long sweep is evaluated chunk by chunk into the result rows. A
#: workspace row of this many angles (64 KiB) stays in a core's cache, and numpy's cost per call
#: (about 0.4 µs an operation) is paid once per chunk: a tenth of the arithmetic at this length
#: (measured: 4,096 costs the conveyor 15 % and the slider-crank 8 % more at 36,000 angles,
#: 16,384 gains nothing more)
CHUNK = 8192

#: the numpy ufunc of each recorded operation
_UFUNCS = {"add": "add", "sub": "subtract", "mul": "multiply", "div": "divide",
           "neg": "negative", "sqrt": "sqrt", "cos": "cos", "sin": "sin", "abs": "absolute",
           "arctan2": "arctan2", "maximum": "maximum", "minimum": "minimum"}
_PYTHON = {"add": lambda a, b: a + b, "sub": lambda a, b: a - b, "mul": lambda a, b: a * b,
           "div": lambda a, b: a / b, "neg": lambda a: -a, "sqrt": math.sqrt, "cos": math.cos,
           "sin": math.sin, "abs": abs, "arctan2": math.atan2, "maximum": max, "minimum": min}
_COMMUTATIVE = {"add", "mul", "maximum", "minimum"}
#: ufuncs whose output is passed by keyword
_KEYWORD_OUT = {"maximum", "minimum"}


#: compiled sources, shared by every program whose source is the same (mechanisms that differ
#: only in their numbers), the most recently used kept
CODE_CACHE = 256
_CODE: dict[str, types.CodeType] = {}
_CODE_LOCK = threading.Lock()


def _placeholder(slot: int) -> float:
    """The number written into a program's source for its number ``slot``: a float no model
    uses (beyond 1e300, one per slot), replaced by the model's own number in the compiled
    code's constants."""
    return 1.0e300 * (1.0 + slot * 2.0 ** -40)


class Redo(Exception):  # noqa: N818 (a signal, not an error)
    """Raised by a guard's check where the straight-line evaluation does not apply to a chunk
    (a Newton step that did not converge, an assembly far from its path): the chunk is then
    evaluated again by the ``redo`` given to :meth:`Compiled.run` (the direct evaluation, which
    iterates and raises the errors)."""


def _key(value) -> object:
    """A CSE key of an argument: an id, or a float's exact bits."""
    return value if isinstance(value, int) else ("c", float(value).hex())


class Traced:
    """A recorded value: operation ``id`` of its tracer, possibly negated (a negation is carried
    as a sign until an operation needs the value itself)."""

    __slots__ = ("id", "negated", "tracer")

    def __init__(self, tracer: Tracer, id: int, negated: bool = False) -> None:
        self.tracer, self.id, self.negated = tracer, id, negated

    def __neg__(self) -> Traced:
        return Traced(self.tracer, self.id, not self.negated)

    def __add__(self, other):
        return self.tracer.add(self, other)

    def __radd__(self, other):
        return self.tracer.add(other, self)

    def __sub__(self, other):
        return self.tracer.add(self, _negate(other))

    def __rsub__(self, other):
        return self.tracer.add(other, -self)

    def __mul__(self, other):
        return self.tracer.mul(self, other)

    def __rmul__(self, other):
        return self.tracer.mul(other, self)

    def __truediv__(self, other):
        return self.tracer.div(self, other)

    def __rtruediv__(self, other):
        return self.tracer.div(other, self)

    def __repr__(self) -> str:
        return f"{'-' if self.negated else ''}t{self.id}"


def _negate(value):
    return -value


def _float(value) -> bool:
    return isinstance(value, float | int) and not isinstance(value, bool)


@dataclass
class _Op:
    name: str
    out: tuple[int, ...]
    args: tuple
    extra: object = None  # a guard's (bound, check index); a call's function index


@dataclass(frozen=True, slots=True)
class Layout:
    """Where each output is: ``rows[name]`` = a row index, or a pair (x row, y row) of
    consecutive rows, or ``constants[name]`` a float or a pair of floats."""

    rows: dict = field(default_factory=dict)
    constants: dict = field(default_factory=dict)
    count: int = 0


class Tracer:
    """Records operations on :class:`Traced` values (see the module docstring)."""

    def __init__(self) -> None:
        self.ops: list[_Op] = []
        self._count = 1  # id 0: the crank angles (deg)
        self._seen: dict[tuple, int] = {}
        self._producers: dict[int, _Op] = {}
        self.checks: list[Callable] = []
        self.calls: list[Callable] = []
        self._outputs: list[tuple[str, tuple]] = []

    # -- recording ---------------------------------------------------------------------------
    def angles(self) -> Traced:
        """The crank angles in degrees (the function's input)."""
        return Traced(self, 0)

    def _record(self, name: str, *args) -> Traced:
        key = (name, *(_key(a) for a in args))
        if name in _COMMUTATIVE:
            key = (name, *sorted((_key(a) for a in args), key=repr))
        found = self._seen.get(key)
        if found is None:
            found = self._seen[key] = self._count
            self._count += 1
            self.ops.append(_Op(name, (found,), args))
            self._producers[found] = self.ops[-1]
        return Traced(self, found)

    def plain(self, value) -> object:
        """A float, or the id of a traced value with its sign applied (a negation recorded)."""
        if not isinstance(value, Traced):
            return float(value)
        if value.negated:
            return self._negation(value.id)
        return value.id

    def _negation(self, ident: int) -> int:
        """The id of −value: a product or quotient with a constant rewritten with the constant
        negated (−(a·c) = a·(−c), −(a/c) = a/(−c), −(c/b) = (−c)/b: exact in IEEE arithmetic,
        signed zeros included), so no extra pass is made; else a negation. (−(a − b) is not
        rewritten as b − a: the two differ in the sign of a zero, which arctan2 sees.)"""
        op = self._producers.get(ident)
        if op is not None and op.name in ("mul", "div"):
            first, second = op.args
            if isinstance(second, float):
                return self._record(op.name, first, -second).id
            if op.name == "div" and isinstance(first, float):
                return self._record("div", -first, second).id
        return self._record("neg", ident).id

    def apply(self, name: str, *args):
        """Record (or fold) the operation ``name`` of ``args``."""
        if all(_float(a) for a in args):
            return _PYTHON[name](*(float(a) for a in args))
        if name in ("cos", "abs"):
            (value,) = args
            return self._record(name, value.id)
        if name == "sin":
            (value,) = args
            found = self._record(name, value.id)
            return -found if value.negated else found
        return self._record(name, *(self.plain(a) for a in args))

    def add(self, a, b):
        if _float(a) and _float(b):
            return float(a) + float(b)
        if _float(a) and a == 0:
            return b
        if _float(b) and b == 0:
            return a
        if _float(a):
            a, b = b, a
        if _float(b):  # ±A + c
            if a.negated:
                return self._record("sub", float(b), a.id)
            return self._record("add", a.id, float(b))
        if a.id == b.id:
            if a.negated != b.negated:
                return 0.0
            found = self._record("add", a.id, a.id)
            return -found if a.negated else found
        if not a.negated and not b.negated:
            return self._record("add", a.id, b.id)
        if not a.negated:
            return self._record("sub", a.id, b.id)
        if not b.negated:
            return self._record("sub", b.id, a.id)
        return -self._record("add", a.id, b.id)

    def mul(self, a, b):
        if _float(a) and _float(b):
            return float(a) * float(b)
        if _float(a):
            a, b = b, a
        if _float(b):
            factor = float(b)
            if factor == 0:
                return 0.0
            if factor == 1:
                return a
            if factor == -1:
                return -a
            return self._record("mul", a.id, -factor if a.negated else factor)
        found = self._record("mul", a.id, b.id)
        return -found if a.negated != b.negated else found

    def div(self, a, b):
        if _float(a) and _float(b):
            return float(a) / float(b)
        if _float(b):
            divisor = float(b)
            if divisor == 1:
                return a
            if divisor == -1:
                return -a
            return self._record("div", a.id, -divisor if a.negated else divisor)
        if _float(a):
            if a == 0:
                return 0.0
            return self._record("div", -float(a) if b.negated else float(a), b.id)
        found = self._record("div", a.id, b.id)
        return -found if a.negated != b.negated else found

    def guard(self, value, bound: float, check: Callable, *args,
              magnitude: bool = False) -> None:
        """At run time: where ``value.min() > bound`` fails (NaN included), call
        ``check(angles_deg, *args)`` (arrays), which raises or returns.

        With ``magnitude``, the bound is on ``|value|`` (``bound`` ≥ 0), tested without a pass
        of its own over the angles: ``value.min() > bound`` where the first value is positive,
        else ``value.max() < -bound`` (a value that changes sign fails either way)."""
        if _float(value) and (abs(float(value)) if magnitude else float(value)) > bound:
            return  # holds at every angle
        self.checks.append(check)
        plain = tuple(self.plain(a) if isinstance(a, Traced) else float(a) for a in args)
        # a constant that fails the bound: the exact check is called at every evaluation
        self.ops.append(_Op("guard", (), (self.plain(value), *plain),
                            (float(bound), len(self.checks) - 1, magnitude)))

    def call(self, function: Callable, args: Sequence, count: int) -> list[Traced]:
        """Record ``function(angles_deg, arrays, out_rows)`` that writes ``count`` results
        into the rows it is given."""
        self.calls.append(function)
        out = tuple(range(self._count, self._count + count))
        self._count += count
        plain = tuple(self.plain(a) if isinstance(a, Traced) else float(a) for a in args)
        self.ops.append(_Op("call", out, plain, len(self.calls) - 1))
        return [Traced(self, i) for i in out]

    def output(self, name: str, value) -> None:
        """Name a scalar result."""
        self._outputs.append((name, (value,)))

    def output_vector(self, name: str, x, y) -> None:
        """Name a vector result (its x and y in consecutive rows, read as an (N, 2) view)."""
        self._outputs.append((name, (x, y)))

    # -- compiling -----------------------------------------------------------------------------
    def compile(self, name: str = "evaluate") -> Compiled:
        """The recorded operations as one compiled function (see :class:`Compiled`): the
        outputs given rows (:meth:`_rows`), the operations they need kept (:meth:`_needed`),
        written as numpy calls into reused workspace rows (:class:`_SourceWriter`) and compiled
        once per source (:func:`_load`)."""
        layout, primary, fills, copies = self._rows()
        writer = _SourceWriter(self._needed(primary, copies), primary, copies)
        template = writer.source(name, layout, fills, copies)
        numbers = {_placeholder(slot): float.fromhex(bits)
                   for bits, slot in writer.constants.items()}
        function = _load(template, name, numbers)
        source = template
        for placeholder, value in numbers.items():
            source = source.replace(repr(placeholder), repr(value))
        return Compiled(function, source, layout, writer.work, tuple(self.checks),
                        tuple(self.calls))

    def _rows(self) -> tuple[Layout, dict[int, int], list[tuple[int, float]],
                             list[tuple[int, int]]]:
        """Where each output goes: the :class:`Layout`; the values computed straight into an
        output row (``primary``: id → row); rows filled with a constant (``fills``); rows
        copied from a value computed elsewhere (``copies``: row, id)."""
        primary: dict[int, int] = {}    # id → its output row (written there directly)
        fills: list[tuple[int, float]] = []
        copies: list[tuple[int, int]] = []
        layout = Layout()
        rows = 0
        written: dict[tuple, object] = {}   # the values of an output → its rows
        for out_name, values in self._outputs:
            values = tuple(self.plain(v) if isinstance(v, Traced) else float(v) for v in values)
            if all(isinstance(v, float) for v in values):
                layout.constants[out_name] = values[0] if len(values) == 1 else values
                continue
            if values in written:   # the same values under another name: the same rows
                layout.rows[out_name] = written[values]
                continue
            ids = [v for v in values if isinstance(v, int)]
            existing = [primary.get(i) for i in ids]
            if (len(values) == 2 and len(ids) == 2 and None not in existing
                    and existing[1] == existing[0] + 1):
                layout.rows[out_name] = tuple(existing)
                continue
            if len(values) == 1 and existing[0] is not None:
                layout.rows[out_name] = existing[0]
                continue
            mine = list(range(rows, rows + len(values)))
            rows += len(values)
            for row, value in zip(mine, values, strict=True):
                if isinstance(value, float):
                    fills.append((row, value))
                elif value == 0 or value in primary:
                    copies.append((row, value))
                else:
                    primary[value] = row
            layout.rows[out_name] = mine[0] if len(mine) == 1 else tuple(mine)
            written[values] = layout.rows[out_name]
        return Layout(layout.rows, layout.constants, rows), primary, fills, copies

    def _needed(self, primary: dict[int, int], copies: list[tuple[int, int]]) -> list[_Op]:
        """The recorded operations the outputs, guards and calls need, in order (one of each
        pair of products x·c, x·(−c) shared: :func:`_share_negated_products`)."""
        needed = set(primary) | {value for _, value in copies}
        recorded = _share_negated_products(self.ops, needed)
        for op in reversed(recorded):
            if op.name in ("guard", "call") or op.out[0] in needed:
                needed.update(arg for arg in op.args if isinstance(arg, int))
        return [op for op in recorded if op.name in ("guard", "call") or op.out[0] in needed]


class _SourceWriter:
    """Writes operations as Python source, one numpy call a line: a value computed into its
    output row where it has one, else into a workspace row ``w<k>`` taken from the rows freed
    after their last use. The model's numbers are written as placeholders, one per number
    (:func:`_placeholder`): mechanisms that differ only in their numbers (a template's
    variants) share the source, compiled once; each program's code then takes its own numbers
    in place of the placeholders (as constants: no slower than numbers written in)."""

    def __init__(self, ops: list[_Op], primary: dict[int, int],
                 copies: list[tuple[int, int]]) -> None:
        self.ops, self.primary = ops, primary
        #: each value's last use (an operation's index; copied outputs: past the end)
        self.last: dict[int, int] = {}
        for index, op in enumerate(ops):
            for arg in op.args:
                if isinstance(arg, int):
                    self.last[arg] = index
        for _, value in copies:
            self.last[value] = len(ops)
        self.where: dict[int, str] = {0: "angles"}
        for ident, row in primary.items():
            self.where[ident] = f"o{row}"
        self.free: list[int] = []
        #: workspace rows used
        self.work = 0
        #: a float's exact bits → its placeholder's slot
        self.constants: dict[str, int] = {}

    def constant(self, value: float) -> str:
        bits = float(value).hex()
        if bits not in self.constants:
            self.constants[bits] = len(self.constants)
        return repr(_placeholder(self.constants[bits]))

    def text(self, arg) -> str:
        return self.constant(arg) if isinstance(arg, float) else self.where[arg]

    def release(self, index: int, op: _Op) -> None:
        """Free the workspace rows of the arguments whose last use is operation ``index``."""
        for arg in set(op.args):
            if (isinstance(arg, int) and self.last.get(arg) == index
                    and arg not in self.primary and arg != 0
                    and self.where.get(arg, "").startswith("w")):
                self.free.append(int(self.where[arg][1:]))

    def take(self) -> str:
        if self.free:
            return f"w{self.free.pop()}"
        self.work += 1
        return f"w{self.work - 1}"

    def guard(self, op: _Op) -> str:
        bound, check, magnitude = op.extra
        value, *args = (self.text(a) for a in op.args)
        call = f"checks[{check}](angles{''.join(', ' + a for a in args)})"
        if isinstance(op.args[0], float):  # a constant that fails its bound
            return call
        if magnitude:
            return (f"if not ({value}.min() > {self.constant(bound)} if {value}[0] > 0.0 "
                    f"else {value}.max() < {self.constant(-bound)}): {call}")
        return f"if not ({value}.min() > {self.constant(bound)}): {call}"

    def call(self, op: _Op) -> str:
        for out in op.out:
            if out not in self.primary:
                self.where[out] = self.take()
        inputs = ", ".join(self.text(a) for a in op.args)
        outputs = ", ".join(self.where[o] for o in op.out)
        return (f"calls[{op.extra}](angles, ({inputs}{',' if op.args else ''}), "
                f"({outputs},))")

    def ufunc(self, index: int, op: _Op) -> str:
        (out,) = op.out
        args = [self.text(a) for a in op.args]
        self.release(index, op)   # an argument's row may take the result
        if out not in self.primary:
            self.where[out] = self.take()
        target = self.where[out]
        if op.name in _KEYWORD_OUT:  # (a positional out is deprecated for these)
            target = f"out={target}"
        return f"{_UFUNCS[op.name]}({', '.join(args)}, {target})"

    def source(self, name: str, layout: Layout, fills: list[tuple[int, float]],
               copies: list[tuple[int, int]]) -> str:
        """The function's source: constant rows filled, the operations, copied rows."""
        lines = [f"o{row}.fill({self.constant(value)})" for row, value in fills]
        for index, op in enumerate(self.ops):
            if op.name in ("guard", "call"):
                lines.append(self.guard(op) if op.name == "guard" else self.call(op))
                self.release(index, op)
            else:
                lines.append(self.ufunc(index, op))
        lines += [f"copyto(o{row}, {self.where[value]})" for row, value in copies]
        header = [f"def {name}(angles, out, work, checks, calls):"]
        if layout.count:
            header.append(f"    {', '.join(f'o{i}' for i in range(layout.count))}, = out")
        if self.work:
            header.append(f"    {', '.join(f'w{i}' for i in range(self.work))}, = work")
        return "\n".join(header + [f"    {line}" for line in lines] + ["    return None"])


def _load(template: str, name: str, numbers: dict[float, float]) -> types.FunctionType:
    """The function of ``template`` with its placeholders replaced by ``numbers``: compiled once
    per template (the most recently used :data:`CODE_CACHE` kept)."""
    with _CODE_LOCK:
        code = _CODE.pop(template, None)
        if code is None:
            module = compile(template, f"<planmethod {name}>", "exec")
            code = next(c for c in module.co_consts if isinstance(c, types.CodeType))
        _CODE[template] = code                 # most recently used last
        while len(_CODE) > CODE_CACHE:
            _CODE.pop(next(iter(_CODE)))
    code = code.replace(co_consts=tuple(numbers.get(c, c) if type(c) is float else c
                                        for c in code.co_consts))
    namespace = {ufunc: getattr(np, ufunc) for ufunc in set(_UFUNCS.values())}
    namespace["copyto"] = np.copyto
    namespace["__builtins__"] = builtins
    return types.FunctionType(code, namespace, name)


def _share_negated_products(ops: list[_Op], pinned: set[int]) -> list[_Op]:
    """The operations with one of each pair x·c, x·(−c) left out where the other serves: when
    both are recorded (one a result's negation, say) and every use of one is a sum or a
    difference that takes the other instead — a + P = a − N, a − P = a + N, exact in IEEE
    arithmetic (N = −P to the bit, signed zeros included) — that one is not computed; the other
    is computed where the first was (it needs only x).

    The pairs are taken in order, each checked against the operations as rewritten so far
    (a rewrite may let a pair passed over before share), until a pass shares none.

    >>> ops = [_Op("mul", (2,), (1, 3.0)), _Op("mul", (3,), (1, -3.0)),
    ...        _Op("add", (4,), (0, 2)), _Op("sub", (5,), (0, 3))]
    >>> [(op.name, op.out, op.args) for op in _share_negated_products(ops, {4, 5})]
    [('mul', (3,), (1, -3.0)), ('sub', (4,), (0, 3)), ('sub', (5,), (0, 3))]
    """
    sharing = _Sharing(ops, pinned)
    shared = True
    while shared:
        shared = False
        for key in list(sharing.products):
            shared |= sharing.share(key)
    return [op for op in sharing.work if op is not None]


class _Sharing:
    """The operations being rewritten by :func:`_share_negated_products`: where each product
    x·c is recorded, and where each value is read."""

    def __init__(self, ops: list[_Op], pinned: set[int]) -> None:
        self.work: list[_Op | None] = list(ops)
        self.pinned = pinned
        self.products: dict[tuple[int, float], int] = {}   # (x, c) → where x·c is (the last)
        self.uses: dict[int, set[tuple[int, int]]] = {}    # a value → (op, argument) reading it
        for position, op in enumerate(self.work):
            if op.name == "mul" and isinstance(op.args[0], int) and isinstance(op.args[1], float):
                self.products[(op.args[0], op.args[1])] = position
            self.read(position, op)

    def unread(self, position: int, op: _Op) -> None:
        for place, arg in enumerate(op.args):
            if isinstance(arg, int):
                self.uses[arg].discard((position, place))

    def read(self, position: int, op: _Op) -> None:
        for place, arg in enumerate(op.args):
            if isinstance(arg, int):
                self.uses.setdefault(arg, set()).add((position, place))

    def share(self, key: tuple[int, float]) -> bool:
        """Leave out x·c (``key``) where x·(−c) serves every reader of it; whether it did."""
        work, products = self.work, self.products
        gone = products.get(key)
        kept = products.get((key[0], -key[1]))
        if gone is None or kept is None or kept == gone:
            return False
        dropped = work[gone].out[0]
        readers = sorted(self.uses.get(dropped, ()))
        if dropped in self.pinned or not all(_takes_negation(work[position], place)
                                             for position, place in readers):
            return False
        other = work[kept].out[0]
        for position, place in readers:
            op = work[position]
            turned = _Op("sub" if op.name == "add" else "add", op.out,
                         (op.args[1 - place], other), op.extra)
            self.unread(position, op)
            self.read(position, turned)
            work[position] = turned
        first, last = min(gone, kept), max(gone, kept)
        self.unread(gone, work[gone])
        self.unread(kept, work[kept])
        work[first], work[last] = work[kept], None
        self.read(first, work[first])
        del products[key]
        products[(key[0], -key[1])] = first
        self.uses.pop(dropped, None)
        return True


def _takes_negation(op: _Op, place: int) -> bool:
    """Whether argument ``place`` of ``op`` may be replaced by its negation, the operation
    turned (a sum into a difference, or back)."""
    if op.args.count(op.args[place]) != 1:
        return False
    return op.name == "add" or (op.name == "sub" and place == 1)


class Compiled:
    """A traced function compiled: ``evaluate(angles_deg)`` → the result rows (K, N)."""

    def __init__(self, function, source: str, layout: Layout, work: int, checks, calls) -> None:
        self.function, self.source, self.layout = function, source, layout
        self.work, self.checks, self.calls = work, checks, calls
        self._local = threading.local()   # a workspace per thread
        self._constants: dict[tuple[str, int], np.ndarray] = {}
        self._where: dict[str, tuple] = {}
        for name, where in layout.rows.items():
            self._where[name] = (1, where[0]) if isinstance(where, tuple) else (0, where)
        for name, value in layout.constants.items():
            self._where[name] = (2, value)

    def workspace(self, count: int) -> list[np.ndarray]:
        """Rows of ``count`` angles of this thread's workspace (kept and reused across
        calls)."""
        local = self._local
        views = getattr(local, "views", None)
        if views is None:
            views = local.views = {}
            local.space = np.empty((self.work, CHUNK))
        found = views.get(count)
        if found is None:
            if len(views) > 8:
                views.clear()
            found = views[count] = [row[:count] for row in local.space]
        return found

    def run(self, angles_deg: np.ndarray, rows: list[np.ndarray],
            redo: Callable[[np.ndarray, list[np.ndarray]], None] | None = None) -> None:
        """Evaluate at ``angles_deg`` into ``rows`` (one array of len(angles) per output row),
        chunk by chunk. A check that raises propagates (see :meth:`Tracer.guard`), but
        :class:`Redo`: ``redo(angles_deg, rows)`` then evaluates that chunk again (without a
        ``redo``, :class:`Redo` propagates too)."""
        count = angles_deg.shape[0]
        if count <= CHUNK:
            try:
                self.function(angles_deg, rows, self.workspace(count), self.checks, self.calls)
            except Redo:
                if redo is None:
                    raise
                redo(angles_deg, rows)
            return
        for lo in range(0, count, CHUNK):
            hi = min(lo + CHUNK, count)
            part = [row[lo:hi] for row in rows]
            try:
                self.function(angles_deg[lo:hi], part, self.workspace(hi - lo), self.checks,
                              self.calls)
            except Redo:
                if redo is None:
                    raise
                redo(angles_deg[lo:hi], part)

    def evaluate(self, angles_deg: np.ndarray,
                 redo: Callable[[np.ndarray, list[np.ndarray]], None] | None = None
                 ) -> np.ndarray:
        """The result rows (K, N) at ``angles_deg`` (a new array; ``redo`` as :meth:`run`)."""
        out = np.empty((self.layout.count, angles_deg.shape[0]))
        self.run(np.ascontiguousarray(angles_deg, dtype=float), list(out), redo)
        return out

    def read(self, rows: np.ndarray, name: str) -> np.ndarray:
        """An output from the result rows: a view, or a constant over the angles (read-only,
        made once per number of angles)."""
        kind, where = self._where[name]
        if kind == 0:
            return rows[where]
        if kind == 1:
            return rows[where:where + 2].T
        count = rows.shape[1]
        found = self._constants.get((name, count))
        if found is None:
            shape = (count, 2) if isinstance(where, tuple) else (count,)
            found = np.empty(shape)
            found[...] = where
            found.flags.writeable = False
            if len(self._constants) > 256:
                self._constants.clear()
            self._constants[(name, count)] = found
        return found
