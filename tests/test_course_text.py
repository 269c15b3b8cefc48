"""Every text a person reads speaks the course's notation (docs/notation.md): the solve and
sweep reports, the plans' vector equations, the names of Coriolis points and of the drive link,
drawing feedback and task texts — under each ``[notation]`` choice, never a report name
(``omega_BC``, ``v_B@lever``, ``R_A``, ``φ1``). Machine names stay in the JSON report and the
CSV headers."""

from __future__ import annotations

import io
import re
import tomllib
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest
from test_notation import CONVENTIONS, SUB, _compressor

from planmethod.application.solving import report_text
from planmethod.cli import main
from planmethod.grading.drawings import Drawing, grade_drawing
from planmethod.grading.keys import build_key
from planmethod.grading.templates import draw_variant, load_template
from planmethod.plans import draw_plans
from planmethod.render.figures import plan_files
from planmethod.render.labels import label_runs, plain
from planmethod.render.plan_words import label_text, step_text
from planmethod.render.svg import vector_equations
from planmethod.report import analyse
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.testing.figures import CODE_WORD
from planmethod.words import render

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = sorted((ROOT / "exercises").glob("*.toml"))

#: a report's name where a person reads: a point of a link (``B@lever``), a quantity's or a
#: reaction's report name (``omega_BC``, ``dds_``, ``Rx_A``, ``R_A``, ``Rᵗ_B``, ``G_BC``,
#: ``F_u``), a Coriolis point's side index (``k1_``), the crank's symbols with a plain digit
#: (``φ1``, ``μv/ω1``), a pair written from → on (``frame → AB``), a doubled word
#: (``link link``)
CODE_NAME = re.compile(r"@|\b(?:omega|epsilon|theta|rho|coriolis|dds|ds|a_rel|Rx|Ry)_"
                       r"|(?<![\w|])(?:R|Rᵗ|Rⁿ|N|G)_[A-Z]|\b[FM]_u\b|\bk[0-9]_|[φωε][0-9]"
                       r"|→ on|\w+ → \w+\s{2}|\blink link\b")


def code_names(text: str) -> list[str]:
    """The report names in ``text`` (see :data:`CODE_NAME`, and the figure check's snake_case
    ``CODE_WORD``: ``rocker_EF``, ``M_b_system``)."""
    found = [match.group(0) for match in CODE_NAME.finditer(text)]
    return found + CODE_WORD.findall(text)


def test_the_check_finds_the_report_names_it_guards():
    """On the text the reports printed before, every kind of report name is found; in the
    course's notation, none."""
    before = ("Compressor — crank angle φ1 = 45°\n  μφv = μv/ω1 = 0.002 m/mm\n"
              "  omega_BC  -24.25\n  v_B@lever  0.73\n  A   frame → AB   -17.9\n"
              "  Rᵗ_B ⟂ BC from ΣM_C(BC) = 0\n  theta_rocker_EF  12\n  M_b_system  0.6\n"
              "  force polygon 2: drive link link 1 (AB)\n  through k1_Q: aʳ\n  F_u = −m·a_S")
    found = code_names(before)
    for name in ("φ1", "ω1", "omega_", "@", "frame → AB  ", "Rᵗ_B", "theta_", "M_b_system",
                 "link link", "k1_", "F_u"):
        assert any(name in word for word in found), name
    after = ("Compressor — crank angle φ₁ = 45°\n  μφv = μv/ω₁ = 0.002 m/mm\n  ω₂  -24.25\n"
             "  v_B₃  0.73\n  R₀₁       A   -17.9\n  Rᵗ₁₂ ⟂ BC from ΣM_C(2) = 0\n"
             "  θ₄  12\n  M_b (whole system)  0.6  |a_S| l_AB ρ_D aʳ_CC₀ Z_g |ΣP|/Σ|P|\n"
             "  force polygon 2: drive link 1 (AB)\n  through k_Q: aʳ_QQ₁\n  Fᵘ = −m·a_S")
    assert code_names(after) == []


def _cli(*argv: str) -> str:
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        code = main([str(a) for a in argv])
    assert code == 0, err.getvalue()
    return out.getvalue()


@pytest.mark.parametrize("notation", ["", "frame = 1"], ids=["default", "frame1"])
@pytest.mark.parametrize("path", EXERCISES, ids=lambda path: path.stem)
def test_no_report_a_person_reads_names_a_report_name(path, notation, tmp_path):
    """``solve``'s text report and ``sweep``'s printed table (with ``--forces`` where the
    exercise has masses) of every shipped exercise, in its own notation and with the frame
    numbered 1, name every quantity, link and force as the course does."""
    text = path.read_text(encoding="utf-8")
    if notation:
        path = tmp_path / path.name
        path.write_text(text + f"\n[notation]\n{notation}\n", encoding="utf-8")
    printed = _cli("solve", path) + _cli("sweep", path, "--step", "45")
    if "[mass." in text:
        printed += _cli("sweep", path, "--step", "45", "--forces")
    assert code_names(printed) == []
    crank = "₂" if notation else "₁"
    assert f"crank angle φ{crank} = " in printed and f"at φ{crank}" in printed


def _number(word: str) -> bool:
    try:
        float(word)
    except ValueError:
        return False
    return True


def _row(text: str, symbol: str) -> list[str]:
    """The table row (its third word a number) whose first word is ``symbol``."""
    return next(words for words in map(str.split, text.splitlines())
                if words[:1] == [symbol] and len(words) > 2 and _number(words[2]))


@pytest.mark.parametrize("name", CONVENTIONS)
def test_the_solve_report_speaks_each_notation(name):
    """The compressor (with a mass on BC, so that it has reactions) under each
    ``[notation]``: BC's ω and ε, the crank's φ and ω, the links of the structural analysis
    and the reactions carry that convention's numbers."""
    notation, (frame, crank, rod, slider) = CONVENTIONS[name]
    exercise = exercise_from_dict(_compressor(notation), file="compressor.toml")
    analysis = analyse(exercise)
    text = report_text(analysis)
    n = {link: str(number).translate(SUB) for link, number in
         (("frame", frame), ("crank", crank), ("rod", rod), ("slider", slider))}

    def pair(first, second):
        sub = f"{first}{second}" if max(first, second) < 10 else f"{first},{second}"
        return sub.translate(str.maketrans("0123456789,", "₀₁₂₃₄₅₆₇₈₉‚"))

    assert f"crank angle φ{n['crank']} = 45°" in text
    assert f"μφv = μv/ω{n['crank']} = " in text and f"μφa = μa/ω{n['crank']}² = " in text
    assert f"drive link {crank} (AB) with the frame {frame}" in text
    assert f"group 1: links {rod}, {slider} (BC, slider) — RRP" in text
    # BC's ω and ε by its number, with the exact values the JSON report keeps as omega_BC
    assert float(_row(text, f"ω{n['rod']}")[2]) == pytest.approx(
        float(analysis.motion.at(0).omega("BC")), rel=1e-5)
    assert float(_row(text, f"ε{n['rod']}")[2]) == pytest.approx(
        float(analysis.motion.at(0).epsilon("BC")), rel=1e-5)
    # the reactions: of the frame on the crank at A, of the crank on the rod at B, of the
    # frame on the slider along its guide (the pair slider–frame)
    assert _row(text, "R" + pair(frame, crank))[1] == "A"
    assert _row(text, "R" + pair(crank, rod))[1] == "B"
    assert _row(text, "R" + pair(frame, slider))[1] == f"{slider}–{frame}"
    assert f"{rod} (BC)" in text and f"Kinetostatics (d'Alembert) at φ{n['crank']}" in text
    assert code_names(text) == []


def test_the_compressors_rod_is_omega_2_by_default_and_omega_3_with_the_frame_1():
    """The case of issue 20: the papers' ω₂ for BC by default, ω₃ where the frame is 1."""
    analysis = analyse(exercise_from_dict(_compressor({}), file="c.toml"))
    default = report_text(analysis)
    english = report_text(analyse(exercise_from_dict(_compressor({"frame": 1}), file="c.toml")))
    rod = float(analysis.motion.at(0).omega("BC"))          # −24.25 rad/s; the slider's ω is 0
    assert float(_row(default, "ω₂")[2]) == pytest.approx(rod, rel=1e-5)
    assert float(_row(english, "ω₃")[2]) == pytest.approx(rod, rel=1e-5)
    assert float(_row(default, "ω₃")[2]) == 0.0 and float(_row(english, "ω₄")[2]) == 0.0
    assert "crank angle φ₁ = 45°" in default and "crank angle φ₂ = 45°" in english
    assert _row(default, "R₀₁")[1] == "A" and _row(english, "R₁₂")[1] == "A"


def test_a_point_placed_by_similarity_names_its_link_by_number():
    """The compressor's d is placed by the similarity rule on the rod: its step says so by
    the rod's number, as the course does, on both plans — link 2 by default, link 3 where
    the frame is 1."""
    for notation, number in (({}, 2), ({"frame": 1}, 3)):
        plans = draw_plans(exercise_from_dict(_compressor(notation), file="c.toml"))
        for plan in (plans.velocity, plans.acceleration):
            said = [step_text(step, plan) for step in plan.steps if step.action == "similarity"]
            assert said == [f"d by similarity on link {number} from b"], said


@pytest.mark.parametrize("path", EXERCISES, ids=lambda path: path.stem)
def test_each_vector_equation_names_each_relative_motion_once(path):
    """Beside each plan, an equation names two different relative accelerations by two
    symbols (aʳ_B₃B and aʳ_B₃B₀, as the velocity equation's v_B₃B and v_B₃B₀), never one
    symbol twice; digits of point names are subscripts."""
    plans = draw_plans(load_exercise(path))
    for plan in (plans.velocity, plans.acceleration):
        for equation in vector_equations(plan):
            terms = re.split(r" [=+] ", equation)
            assert len(terms) == len(set(terms)), equation
            assert not re.search(r"[A-Za-z][0-9]", equation), equation
            assert code_names(equation) == [], equation


@pytest.mark.parametrize(("path", "expected"), [
    ("scotch_yoke", "a_B₃ = a_B + aʳ_B₃B = a_B₀ + aʳ_B₃B₀"),
    ("slotted_crank_crosshead", "a_Q = a_Q₁ + aᵏ_QQ₁ + aʳ_QQ₁ = a_Q₀ + aʳ_QQ₀"),
    ("shaper_sixbar", "a_B₃ = a_B + aᵏ_B₃B + aʳ_B₃B = a_O₂ + aⁿ_B₃O₂ + aᵗ_B₃O₂"),
    ("compressor_slider_crank", "a_C = a_B + aⁿ_CB + aᵗ_CB = a_C₀ + aʳ_CC₀"),
])
def test_the_acceleration_equations_read_as_the_course_writes_them(path, expected):
    plans = draw_plans(load_exercise(ROOT / "exercises" / f"{path}.toml"))
    assert vector_equations(plans.acceleration)[0] == expected


def test_a_coriolis_point_is_k_without_its_side_index():
    """The slotted crank's Coriolis point (report name ``k1_Q``) is k_Q, in its label and in
    the sentences; the second side's point (``k2_Q``) is k′_Q — never k₁,Q."""
    assert plain(label_runs("k1_Q")) == "kQ" and plain(label_runs("k2_Q")) == "k′Q"
    assert [label_text(label, {"frame": 0}) for label in ("k1_Q", "k2_Q", "q@frame")] == [
        "k_Q", "k′_Q", "q₀"]
    plans = draw_plans(load_exercise(ROOT / "exercises" / "slotted_crank_crosshead.toml"))
    sentences = " ".join(step_text(step, plans.acceleration) for step in plans.acceleration.steps)
    assert "k_Q" in sentences and "k1" not in sentences and "k₁" not in sentences
    svg = plan_files(plans)["acceleration.svg"]
    label = re.search(r'<text class="label" data-points="k1_Q"[^>]*>(.*?)</text>', svg)
    assert re.sub(r"<[^>]+>", "", label.group(1)) == "kQ"     # k, Q set as its subscript


def test_the_drive_link_is_named_once():
    """A force polygon's title and the position plan's ω line name the drive link as a course
    does — drive link 1 (AB) — never "drive link link 1 (AB)" or "(link 1 (AB))"."""
    analysis = analyse(load_exercise(ROOT / "exercises" / "fourbar_forces.toml"))
    files = plan_files(analysis.plans, analysis.forces)
    drive = next(svg for name, svg in files.items() if name.startswith("forces_2"))
    assert "force polygon 2: drive link 1 (AB), φ₁ = 60°" in drive
    assert "ω₁ = 10 rad/s, drive link 1 (AB)" in files["position.svg"]
    everything = " ".join(files.values())
    assert "link link" not in everything and "(link 1 (AB))" not in everything


def test_drawing_feedback_sets_point_digits_as_subscripts():
    """The slotted lever's b₃ placed off both its lines, and c placed off by the similarity
    rule: the feedback names the pivot's image o₂ and the components aᵗ_B₃O₂, aʳ_B₃B."""
    key = build_key(draw_variant(load_template("exercises/slotted_lever.toml")))
    points = {label: tuple(xy) for label, xy
              in key["plans"]["acceleration"]["points_mm"].items()}
    x, y = points["b@lever"]
    points["b@lever"] = (x + 7.0, y - 5.0)
    x, y = points["c"]
    points["c"] = (x + 10.0, y + 10.0)
    result = grade_drawing(key, Drawing(points, "acceleration")).as_dict()
    feedback = {entry["point"]: entry["feedback"] for entry in result["points"]}
    assert "aᵗ_B₃O₂ ⟂ BO₂" in feedback["b@lever"] and "aʳ_B₃B" in feedback["b@lever"]
    assert "from o₂" in feedback["c"]
    for text in list(feedback.values()) + result["feedback"]:
        assert code_names(text) == [] and not re.search(r"[A-Za-z][0-9]", text), text


@pytest.mark.parametrize(("notation", "crank"), [({}, "₁"), ({"frame": 1}, "₂")])
def test_a_templates_task_quotes_the_cranks_symbols_by_its_number(notation, crank, tmp_path):
    """``{symbol.omega}`` in a template's description is the crank's ω by its number: the
    task need never say ω₁ where its "Given:" says ω₂. (The shipped templates keep their
    text: a variant's numbers are drawn from a hash of it.)"""
    source = (ROOT / "exercises" / "templates" / "slider_crank.toml").read_text(encoding="utf-8")
    text = (source.replace("ω₁ = {omega:g}", "{symbol.omega} = {omega:g}")
            .replace("(ε₁ = 0)", "({symbol.epsilon} = 0)")
            .replace("φ₁ = {phi", "{symbol.phi} = {phi")
            .replace("of the connecting rod BC", "{symbol.omega_BC} of the connecting rod BC"))
    assert text.count("{symbol.") == 4
    path = tmp_path / "t.toml"
    path.write_text(text + "".join(f"\n[notation]\nframe = {value}\n"
                                   for value in notation.values()), encoding="utf-8")
    assert tomllib.loads(path.read_text(encoding="utf-8"))["description"]
    described = draw_variant(load_template(path)).description
    rod = "₃" if notation else "₂"
    assert f"at ω{crank} = " in described and f"(ε{crank} = 0)" in described
    assert f"At φ{crank} = " in described and f"ω{rod} of the connecting rod" in described
    assert "{symbol." not in described


def test_flags_name_groups_and_points_as_the_course_does():
    """A plan's flag (construction lines meeting at a small angle; here the Scotch yoke's,
    which meet at 80°, under min_angle_deg = 89.9) names the group by its links' numbers and
    the point as the course does: "group of links 2, 3 (block, yoke) … point b₃", never
    "block+yoke", "b@yoke"."""
    data = tomllib.loads((ROOT / "exercises" / "scotch_yoke.toml").read_text(encoding="utf-8"))
    data.setdefault("plan", {})["min_angle_deg"] = 89.9
    analysis = analyse(exercise_from_dict(data, file="scotch_yoke.toml"))
    flags = " ".join(render(flag) for flag in analysis.flags)
    assert "plan, group of links 2, 3 (block, yoke): the lines meet at 80°" in flags
    assert "point b₃ is poorly defined" in flags
    assert code_names(flags) == [] and "+" not in flags
