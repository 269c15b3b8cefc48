"""Values cross the modules of the kinematics, the plans and the forces as typed fields, never
by string keys: a key formatted in one module is never formatted again in another to read the
value back.

A *formatted key* is an f-string used as a key: the index of a subscript
(``values[f"axes:{link}"]``), the first argument of ``get``, ``pop`` or ``setdefault``
(``readings.get(f"omega_{link}")``), a key of a dict display, or the name of a named output
(``tracer.output(f"p:{point}", …)``, ``outputs.scalar(f"sine:{index}", …)``). Its *template* is
the f-string with each field replaced by ``{}`` (``omega_{}``). A template formatted as a key in
two modules is a hand-over by string keys: the writer's names are the reader's interface, and a
renamed key breaks it silently. The typed way is the writer's own accessor or field — the
program's schema (``result.schema.points["C"].velocity``), ``Plans.omega(link)``.
"""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: the packages whose modules hand values to each other (issue 36: the kinematics, the plans
#: and the forces)
PACKAGES = ("kinematics", "plans", "forces")
#: methods whose first argument is a key, or the name of a named output
KEYED = frozenset({"get", "pop", "setdefault", "output", "output_vector", "scalar", "vector"})


def _template(node: ast.AST) -> str | None:
    """An f-string's template (each field as ``{}``), or None for anything else."""
    if not isinstance(node, ast.JoinedStr):
        return None
    return "".join(str(part.value) if isinstance(part, ast.Constant) else "{}"
                   for part in node.values)


def formatted_keys(source: str) -> list[tuple[str, int]]:
    """(template, line) of each formatted key in ``source``.

    >>> formatted_keys('x = values[f"axes:{link}"]\\ny = d.get(f"omega_{l}", 0) + f"v_{p}"')
    [('axes:{}', 1), ('omega_{}', 2)]
    """
    found = []
    for node in ast.walk(ast.parse(source)):
        keys: list[ast.AST] = []
        if isinstance(node, ast.Subscript):
            keys.append(node.slice)
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr in KEYED and node.args):
            keys.append(node.args[0])
        elif isinstance(node, ast.Dict):
            keys.extend(key for key in node.keys if key is not None)
        for key in keys:
            template = _template(key)
            if template is not None:
                found.append((template, key.lineno))
    return sorted(found, key=lambda item: item[1])


def hand_overs(sources: dict[str, str]) -> list[str]:
    """Each template formatted as a key in more than one of ``sources`` (path → text), with
    where."""
    places: dict[str, dict[str, int]] = defaultdict(dict)
    for path, text in sources.items():
        for template, line in formatted_keys(text):
            places[template].setdefault(path, line)
    return [f"{template!r} is a key formatted in "
            + ", ".join(f"{path}:{line}" for path, line in sorted(where.items()))
            for template, where in sorted(places.items()) if len(where) > 1]


def test_no_module_reads_another_modules_values_by_string_keys():
    sources = {str(path.relative_to(ROOT)): path.read_text(encoding="utf-8")
               for package in PACKAGES
               for path in sorted((ROOT / "planmethod" / package).rglob("*.py"))}
    assert len(sources) > 20
    assert hand_overs(sources) == []


def test_a_hand_over_by_string_keys_is_found():
    """What the kinematics did before its schema: the program named its outputs, a higher
    group's module read them back by the same names (and the plans' readings, read by the
    forces)."""
    program = ('def build(link, outputs, body):\n'
               '    outputs.vector(f"axes:{link}", body.axes)\n'
               '    outputs.scalar(f"omega:{link}", body.omega)\n')
    higher = ('def body(values, link):\n'
              '    return values[f"axes:{link}"], values[f"omega:{link}"]\n')
    forces = 'def omega(plans, link):\n    return plans.readings.get(f"omega_{link}")\n'
    plans = 'def read(self, link, omega):\n    self.readings[f"omega_{link}"] = omega\n'
    assert hand_overs({"program.py": program, "higher.py": higher}) == [
        "'axes:{}' is a key formatted in higher.py:2, program.py:2",
        "'omega:{}' is a key formatted in higher.py:2, program.py:3"]
    assert hand_overs({"plans.py": plans, "forces.py": forces}) == [
        "'omega_{}' is a key formatted in forces.py:2, plans.py:2"]
    assert hand_overs({"program.py": program, "plans.py": plans}) == []
