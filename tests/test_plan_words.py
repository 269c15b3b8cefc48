"""The plans' construction steps are typed values, their sentences written in the render layer
(planmethod.render.plan_words) from message templates; the plans layer holds no English
sentence; how a plan keeps its steps is a recorder it is given."""

from __future__ import annotations

import ast
import re
import typing
from pathlib import Path

import numpy as np
import pytest

from planmethod.plans import DropSteps, draw_plans
from planmethod.plans import steps as typed
from planmethod.plans.steps import (
    Across,
    BothEquations,
    BothSides,
    Coincide,
    CoriolisComponent,
    CrankNormal,
    CrankTangential,
    CrankVelocity,
    FixedPivot,
    FrameImage,
    Guide,
    Intersect,
    LayOff,
    Line,
    NormalComponent,
    NormalOfSegment,
    Pole,
    Project,
    Read,
    ReadRadius,
    Similarity,
    SpecialAcceleration,
    SpecialGuide,
    SpecialPoint,
    SpecialSide,
    VectorName,
    VelocityEquation,
)
from planmethod.render import plan_words
from planmethod.render.plan_words import REASON_MESSAGES, STEP_MESSAGES, step_message
from planmethod.spec import load_exercise
from planmethod.words import render
from planmethod.words.catalogue import package_templates

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = sorted((ROOT / "exercises").glob("*.toml"))

#: the shaper's links' numbers (crank 1, block 2, lever 3, rod 4, ram 5), the slotted crank's
#: (crank 1, block 2, crosshead 3) and the conveyor's (tray 3, rocker EF 4)
NUMBERS = {"frame": 0, "crank": 1, "block": 2, "lever": 3, "rod": 4, "ram": 5, "tray": 3,
           "rocker_EF": 4, "crosshead": 3}


def v(symbol: str, point: str, base: str = "") -> VectorName:
    return VectorName(symbol, point, base)


#: (step, plan, sentence): a step of every type, with every reason, and its sentence as the
#: course reads it (the shaper's, the slotted crank's and the conveyor's, as the JSON report
#: gives them)
SENTENCES = [
    (Pole(number=1, end="p"), "velocity", "pole p"),
    (Coincide(number=2, start="p", end="o1", known=FixedPivot("O1")), "velocity",
     "o₁ at the pole: O₁ is fixed"),
    (Coincide(number=13, start="p", end="d@frame", known=FrameImage()), "velocity",
     "d₀ at the pole: the frame does not move"),
    (LayOff(number=5, start="p", end="b", direction_deg=150.0, length_mm=32.0,
            component="absolute", vector=v("v", "B"),
            known=CrankVelocity("crank", "O1", "B", 0.8)), "velocity",
     "v_B = ω₁·l_O₁B = 0.8 m/s, ⟂ O₁B in the sense of ω₁"),
    (LayOff(number=5, start="π", end="b", direction_deg=-120.0, length_mm=32.0,
            component="normal", vector=v("a", "B"),
            known=CrankNormal("crank", "O1", "B", 6.4, True)), "acceleration",
     "a_B = aⁿ = ω₁²·l = 6.4 m/s², from B towards O₁"),
    (LayOff(number=4, start="π", end="n_BO", direction_deg=-150.0, length_mm=25.0,
            component="normal", vector=v("aⁿ", "B", "O"),
            known=CrankNormal("crank", "O", "B", 10.0, False)), "acceleration",
     "aⁿ = ω₁²·l = 10 m/s², from B towards O"),
    (LayOff(number=5, start="n_BO", end="b", direction_deg=120.0, length_mm=0.5,
            component="tangential", vector=v("aᵗ", "B", "O"),
            known=CrankTangential("crank", "O", "B", 0.2)), "acceleration",
     "aᵗ = ε₁·l = 0.2 m/s², ⟂ OB in the sense of ε₁"),
    (LayOff(number=8, start="o2", end="n_B@lever", direction_deg=-97.4, length_mm=6.99,
            component="normal", vector=v("aⁿ", "B@lever", "O2"), group=0,
            known=NormalComponent("B", "O2")), "acceleration",
     "aⁿ_B₃O₂ from o₂: (o₂n_B₃) = (v-plan segment)²·μv²/((BO₂)·μl·μa), from B towards O₂"),
    (LayOff(number=6, start="a", end="n_BA", direction_deg=45.0, length_mm=1.69,
            component="normal", vector=v("aⁿ", "B", "A"), group=0,
            known=NormalOfSegment("a", "b")), "acceleration",
     "aⁿ_BA from a: (ab)²·μv²/(length·μl·μa), towards the centre"),
    (LayOff(number=6, start="b", end="k_B@lever", direction_deg=-7.4, length_mm=5.83,
            component="coriolis", vector=v("aᵏ", "B@lever", "B"), group=0,
            known=CoriolisComponent("block", True)), "acceleration",
     "aᵏ = 2·ω₂·v_rel from b, v_rel turned 90° in the sense of ω₂"),
    (Coincide(number=17, start="d@frame", end="k_D", component="coriolis",
              vector=v("aᵏ", "D", "D@frame"), group=1,
              known=CoriolisComponent("frame", False)), "acceleration",
     "aᵏ = 0: frame does not turn; k_D coincides with d₀"),
    (Line(number=7, start="o2", direction_deg=172.6, component="relative",
          vector=v("v", "B@lever", "O2"), group=0, along=Across("B@lever", "O2")), "velocity",
     "through o₂: v_B₃O₂ ⟂ B₃O₂"),
    (Line(number=6, start="b", direction_deg=82.6, component="relative",
          vector=v("v", "B@lever", "B"), group=0, along=Guide("block", "lever")), "velocity",
     "through b: v_B₃B along the guide of pair 2–3"),
    (Line(number=12, start="k2_Q", direction_deg=10.0, component="relative",
          vector=v("aʳ", "Q", "Q@frame"), group=0, along=Guide("crosshead", "frame")),
     "acceleration", "through k′_Q: aʳ_QQ₀ (relative) along the guide of pair 3–0"),
    (Line(number=6, start="a", direction_deg=135.0, component="relative",
          vector=v("v", "S*", "A"), group=0, along=SpecialSide("A", "B")), "velocity",
     "through a: v_S* − v_A ⟂ AB (S* lies on the line AB)"),
    (Line(number=8, start="n_S*B", direction_deg=135.0, component="tangential",
          vector=v("aᵗ", "S*", "A"), group=0, along=SpecialSide("A", "B")), "acceleration",
     "through n_S*B: aᵗ_BA + aᵗ_S*B ⟂ AB"),
    (Line(number=7, start="d@frame", direction_deg=30.0, component="relative",
          vector=v("v", "S*", "D@frame"), group=0, along=SpecialGuide("block", "frame", "D")),
     "velocity", "through d₀: v_S*D₀ along the guide of pair 2–0 (S* lies on the normal to "
     "the guide through D)"),
    (Line(number=9, start="n_S*D", direction_deg=30.0, component="relative",
          vector=v("aʳ", "S*", "D@frame"), group=0, along=SpecialGuide("block", "frame", "D")),
     "acceleration", "through n_S*D: aʳ + aᵗ_S*D along the guide of pair 2–0"),
    (Intersect(number=8, end="b@lever", lines=(6, 7), angle_deg=90.0, group=0,
               solves=VelocityEquation("B@lever", ("B", "O2"))), "velocity",
     "b₃: v_B₃ = v_B + v_B₃B = v_O₂ + v_B₃O₂"),
    (Intersect(number=10, end="b@lever", lines=(7, 9), angle_deg=90.0, group=0,
               solves=BothEquations("B@lever")), "acceleration",
     "b₃: a_B₃ from both vector equations"),
    (Intersect(number=8, end="s*", lines=(6, 7), angle_deg=63.3, group=0,
               solves=SpecialPoint(-0.430719, -0.345509, "tray", "rod", "rocker_EF")),
     "velocity", "s*: Assur's special point S* = (-0.430719, -0.345509) m of tray, where the "
                 "lines of rod and rocker EF meet"),
    (Intersect(number=12, end="s*", lines=(8, 11), angle_deg=63.3, group=0,
               solves=SpecialAcceleration()), "acceleration",
     "s*: a_S* from the two sides through the special point"),
    (Intersect(number=17, end="d", lines=(14, 16), angle_deg=25.2, group=0,
               solves=BothSides("D")), "acceleration", "d: a_D from both sides"),
    (Similarity(number=11, start="o2", end="c", length_mm=45.5, direction_deg=172.6,
                link="lever", references=("o2",)), "velocity",
     "c by similarity on link 3 from o₂"),
    (Project(number=30, start="d", end="n_D", direction_deg=12.0, point="D", speed="d"),
     "acceleration", "project πd on the normal to the path of D (⟂ pd): n_D"),
    (Read(number=10, start="o2", end="b@lever", length_mm=29.536, quantity="omega_lever",
          value=1.8942038), "velocity", "(o₂b₃) = 29.54 mm → ω₃ = 1.8942"),
    (Read(number=9, start="b", end="b@lever", length_mm=12.313, quantity="v_B@leverB",
          value=-0.3078324689, relative=v("v", "B@lever", "B")), "velocity",
     "(bb₃) = 12.31 mm → v_B₃B = -0.307832"),
    (Read(number=14, start="k1_Q", end="q", length_mm=121.777, quantity="a_rel_QQ@crank",
          value=48.710774, relative=v("aʳ", "Q", "Q@crank")), "acceleration",
     "(k_Qq) = 121.8 mm → aʳ_QQ₁ = 48.7108"),
    (Read(number=21, start="b@lever", end="b", length_mm=12.313, quantity="ds_block/lever",
          value=0.3078324689), "velocity", "(b₃b) = 12.31 mm → ds/dt₂₃ = 0.307832"),
    (ReadRadius(number=31, start="π", end="n_D", length_mm=12.5, quantity="rho_D",
                value=0.1234567, point="D", speed="d"), "acceleration",
     "ρ_D = (pd)²·μv²/((πn_D)·μa) = 0.123457 m"),
]


def _case(step) -> str:
    """A case's name: the step's type and its reason's."""
    reasons = [type(getattr(step, name)).__name__ for name in ("known", "along", "solves")
               if hasattr(step, name)]
    return "-".join([type(step).__name__, *reasons])


@pytest.mark.parametrize(("step", "plan", "sentence"), SENTENCES,
                         ids=[_case(step) for step, _, _ in SENTENCES])
def test_each_step_renders_its_sentence_from_its_template(step, plan, sentence):
    """Every kind of step, with every reason it gives, has its sentence: a template of
    plan_words (read into the catalogue), its fields in the course's notation."""
    said = step_message(step, plan, NUMBERS)
    assert render(said) == sentence
    templates = {found.template for found in package_templates()
                 if found.file == "planmethod/render/plan_words.py"}
    assert said.template in templates


def test_every_step_type_and_reason_has_a_template_and_a_case():
    """The message table covers every step type and every reason, and the table of cases
    above tries each of them."""
    steps = set(typing.get_args(typed.Step))
    reasons = {*typing.get_args(typed.Known), *typing.get_args(typed.Direction),
               *typing.get_args(typed.Solves)}
    assert set(STEP_MESSAGES) == steps and set(REASON_MESSAGES) == reasons
    tried = {type(step) for step, _, _ in SENTENCES} | {
        type(getattr(step, name)) for step, _, _ in SENTENCES
        for name in ("known", "along", "solves") if hasattr(step, name)}
    assert tried >= steps | reasons


@pytest.mark.parametrize("path", EXERCISES, ids=lambda path: path.stem)
def test_a_step_holds_names_and_numbers_never_a_sentence(path):
    """Every field of every step of the shipped exercises' plans is a name, a number or a
    typed value of names and numbers: no text with a space in it (a sentence)."""
    plans = draw_plans(load_exercise(path))

    def texts(value):
        if isinstance(value, str):
            yield value
        elif isinstance(value, tuple):
            for item in value:
                yield from texts(item)

    for plan in (plans.velocity, plans.acceleration):
        for step in plan.steps:
            for text in texts(step):
                assert not re.search(r"\s", text), (step, text)


# -- the plans layer holds no English sentence ------------------------------------------------
#: what the plans layer may still say in English: the developer's registry check (a
#: TypeError at load)
ALLOWED = {("planmethod/plans/groups/__init__.py", "describe")}
#: words in a row: what a sentence reads like (a name, a key, a unit or a formula does not)
SENTENCE = re.compile(r"[A-Za-z]{2,}[,;:]? [a-z]{2,}[,;:]? [a-z]{2,}")
MAKERS = {"message", "plural", "template"}


def _literals(tree: ast.AST) -> list[tuple[int, str, str]]:
    """The string literals of a module (each f-string's text parts joined) outside docstrings
    and raise statements, with their line and enclosing function, and the calls of a
    message maker outside a raise statement (as ``"message("``)."""
    found: list[tuple[int, str, str]] = []

    def walk(node: ast.AST, function: str) -> None:
        if isinstance(node, ast.Raise):
            return                      # an error's message: the one place for words here
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value,
                                                                     ast.Constant):
                body = body[1:]         # its docstring
            name = node.name if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef) \
                else function
            for child in body:
                walk(child, name)
            return
        if isinstance(node, ast.Call):
            called = node.func.id if isinstance(node.func, ast.Name) else getattr(
                node.func, "attr", "")
            if called in MAKERS:
                found.append((node.lineno, function, f"{called}("))
        if isinstance(node, ast.JoinedStr):
            text = "".join(part.value for part in node.values if isinstance(part, ast.Constant))
            found.append((node.lineno, function, text))
            return
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            found.append((node.lineno, function, node.value))
        for child in ast.iter_child_nodes(node):
            walk(child, function)

    module = tree.body[1:] if tree.body and isinstance(tree.body[0], ast.Expr) else tree.body
    for node in module:
        walk(node, "")
    return found


def test_the_plans_layer_holds_no_english_sentence():
    """No module of planmethod/plans makes a message (but an error's, in its raise
    statement) or holds a literal that reads as a sentence outside docstrings and raise
    statements: the steps, the flags and the titles are data, their words the render
    layer's."""
    problems = []
    for path in sorted((ROOT / "planmethod" / "plans").rglob("*.py")):
        relative = str(path.relative_to(ROOT))
        for line, function, text in _literals(ast.parse(path.read_text(encoding="utf-8"))):
            if (relative, function) in ALLOWED:
                continue
            if text in {f"{maker}(" for maker in MAKERS} or SENTENCE.search(text):
                problems.append(f"{relative}:{line} ({function}): {text!r}")
    assert problems == []


def test_the_sentence_check_finds_a_sentence_and_a_message():
    """The check can fail: a sentence in an f-string, a message made outside a raise."""
    source = ('def f(x):\n    """Doc string of many words."""\n'
              '    text = f"{x} by similarity on link"\n'
              '    made = message("pole {pole}", pole=x)\n'
              '    raise ValueError(message("this is allowed here"))\n')
    found = [text for _, _, text in _literals(ast.parse(source))]
    assert "message(" in found and any(SENTENCE.search(text) for text in found)
    assert not any("allowed" in text or "Doc string" in text for text in found)


# -- recorders --------------------------------------------------------------------------------
def test_a_recorder_keeps_or_drops_the_steps_and_the_drawing_is_the_same():
    """draw_plans is given how to keep each plan's steps: KeepSteps keeps every step,
    numbered 1, 2, … in order; DropSteps keeps none; the points and the readings are the
    same either way; a recorder of one's own sees every step, in order, as the function
    that makes it."""
    exercise = load_exercise(ROOT / "exercises" / "shaper_sixbar.toml")
    kept = draw_plans(exercise)
    dropped = draw_plans(exercise, recorder=DropSteps)
    seen: list[tuple[str, int]] = []

    class Reads:
        """Keeps the readings only."""

        def __init__(self) -> None:
            self.kept = []

        def record(self, make) -> None:
            step = make()
            seen.append((step.action, step.number))
            if step.action == "read":
                self.kept.append(step)

        @property
        def steps(self):
            return tuple(self.kept)

    own = draw_plans(exercise, recorder=Reads)
    for name in ("velocity", "acceleration"):
        steps = getattr(kept, name).steps
        assert [step.number for step in steps] == list(range(1, len(steps) + 1))
        assert getattr(dropped, name).steps == ()
        assert getattr(own, name).steps == tuple(s for s in steps if s.action == "read")
        for other in (dropped, own):
            assert getattr(other, name).points_mm == getattr(kept, name).points_mm
    assert kept.readings == dropped.readings == own.readings
    assert [number for action, number in seen if action == "pole"] == [1, 1]
    assert len(seen) == len(kept.velocity.steps) + len(kept.acceleration.steps)


def test_dropped_steps_are_never_made_so_copies_of_a_drawing_draw():
    """Copies of a drawing (a length per copy, as a tolerance analysis draws them) make no
    step — there is no one sentence for many lengths: with DropSteps they draw, their
    readings one per copy. Leaving out the position plan is a choice of its own: the steps
    are kept without it."""
    exercise = load_exercise(ROOT / "exercises" / "compressor_slider_crank.toml")
    copies = np.array([0.0, 0.5, -0.5])

    def perturb(length, segment):
        return length + copies

    drawn = draw_plans(exercise, perturb=perturb, position=False, recorder=DropSteps)
    assert drawn.velocity.steps == () and np.shape(drawn.readings["v_C"]) == (3,)
    assert not np.allclose(drawn.readings["v_C"][1], drawn.readings["v_C"][2])
    without = draw_plans(exercise, position=False)
    assert without.position is None
    assert without.velocity.steps == draw_plans(exercise).velocity.steps


def test_the_json_steps_keep_their_schema_and_carry_their_sentence():
    """A step's JSON is its as_dict() with its sentence as ``text`` after ``action``."""
    plans = draw_plans(load_exercise(ROOT / "exercises" / "slotted_crank_crosshead.toml"))
    written = plan_words.plan_dict(plans.acceleration)
    steps = plans.acceleration.steps
    assert [list(entry) for entry in written["steps"]] == [
        ["number", "action", "text", *list(step.as_dict())[2:]] for step in steps]
    coriolis = next(entry for entry in written["steps"] if entry["end"] == "k1_Q")
    assert coriolis["vector"] == "aᵏ_QQ@crank" and coriolis["component"] == "coriolis"
    assert coriolis["text"] == "aᵏ = 2·ω₁·v_rel from q₁, v_rel turned 90° in the sense of ω₁"
