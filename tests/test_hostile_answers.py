"""Hostile input that was read without a word (issue 24): numbers a reader cannot take
(subnormal coordinates, 5,000-digit whole numbers, a drawn label at ``x="NaN"``), answers files
that lose or merge students, study options beyond the limits, spreadsheet formulas in the CSV
files planmethod writes, and text that adds sub-questions to a Moodle Cloze quiz.

Every refused case gives one line on stderr (``planmethod…: error: …`` naming the file and the
line or key), exit 2, no traceback and nothing written. Each test was seen to fail without the
change it covers.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from planmethod.cli import main

ROOT = Path(__file__).resolve().parent.parent
GOOD = ROOT / "exercises" / "compressor_slider_crank.toml"
BASE = GOOD.read_text(encoding="utf-8")
TEMPLATE = ROOT / "exercises" / "templates" / "slider_crank.toml"
STUDY = ROOT / "exercises" / "fourbar_study.toml"
HUGE = "9" * 5000


def refused(capsys, argv, folder: Path) -> str:
    """Run ``argv`` in-process; return its one error line after checking the contract: exit
    2, one line, no traceback or warning, nothing written in ``folder``."""
    before = set(folder.rglob("*"))
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert code == 2, (argv, code, out[-300:], err[-300:])
    assert "Traceback" not in err + out and "Warning" not in err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("planmethod") and ": error: " in lines[0], err
    assert set(folder.rglob("*")) == before, "a file was written"
    return lines[0]


# -- numbers at reading ----------------------------------------------------------------------
EXERCISE_COMMANDS = {
    "solve": lambda f, out: ["solve", f],
    "workbook": lambda f, out: ["workbook", f, "-o", out / "page.html", "--step", "90"],
    "variants": lambda f, out: ["variants", f, "--out", out / "run", "--no-sheets"],
    "grade": lambda f, out: ["grade", f, out / "answers.csv"],
}

SUBNORMAL = {
    # a crank of 5e-324 m divided by zero (or gave +inf %) in solve, workbook and variants
    "a subnormal crank": ("B = [0.06, 0] }", "B = [5e-324, 0] }", "links.AB.B"),
    "a crank of 1e-300 m": ("B = [0.06, 0] }", "B = [1e-300, 0] }", "links.AB.B"),
    "a crank of 1e-9 m": ("B = [0.06, 0] }", "B = [1e-9, 0] }", "links.AB.B"),
    # two joints of one moving link 1e-10 m apart
    "joints 1e-10 m apart": ("C = [0.18, 0], D = [0.09, 0] }",
                             "C = [0.18, 0], D = [1e-10, 0] }\nCD = { D = [0, 0] }",
                             "links.BC.D"),
    "a 5,000-digit angle": ("angle = 45", f"angle = {HUGE}", "line "),
    "a hexadecimal number beyond 64 bits": ("angle = 45", "angle = 0x" + "f" * 5000,
                                            "drive.angle"),
}


@pytest.mark.parametrize("command", list(EXERCISE_COMMANDS))
@pytest.mark.parametrize("case", list(SUBNORMAL))
def test_numbers_out_of_range_are_refused_at_reading(capsys, tmp_path, command, case):
    old, new, where = SUBNORMAL[case]
    assert old in BASE
    path = tmp_path / "bad.toml"
    path.write_text(BASE.replace(old, new, 1), encoding="utf-8")
    (tmp_path / "answers.csv").write_text("student,v_C\ns1,5\n")
    line = refused(capsys, EXERCISE_COMMANDS[command](path, tmp_path), tmp_path)
    assert "bad.toml" in line and where in line, line
    assert ("at least 1e-08 m" in line) or ("64-bit" in line), line


@pytest.mark.parametrize(("old", "new"), [
    ("B = [0.06, 0] }", "B = [1e-8, 0] }"),             # the shortest crank in range
    ("B = [0.06, 0] }", "B = [0.06, 5e-324] }"),        # a subnormal coordinate: harmless
    ("A = [0, 0] }", "A = [0, 0], G = [0, -1e-309] }"),  # frame points: no length counts
    ("D = [0.09, 0] }", "D = [1e-300, 0] }"),           # a coupler point beside a joint
])
def test_what_lies_in_range_still_solves(capsys, tmp_path, old, new):
    """The new bound refuses only a moving link's length below 1e-8 m."""
    path = tmp_path / "ok.toml"
    path.write_text(BASE.replace(old, new, 1), encoding="utf-8")
    assert new in path.read_text()
    assert main(["solve", str(path)]) == 0
    capsys.readouterr()


def _key_files(tmp_path: Path) -> Path:
    assert main(["variants", str(GOOD), "--out", str(tmp_path / "run"), "--no-sheets"]) == 0
    return tmp_path / "run" / "keys.json"


def test_a_5000_digit_number_in_json_is_one_line_naming_its_key(capsys, tmp_path):
    keys = _key_files(tmp_path)
    capsys.readouterr()
    answers = tmp_path / "answers.json"
    answers.write_text('{"s1": {"v_C": 5}}')
    drawing = tmp_path / "plan.json"
    drawing.write_text('{"plan": "velocity", "points": {"p": [0, 0], "b": [' + HUGE + ", 1]}}")
    line = refused(capsys, ["grade", GOOD, "--drawing", drawing], tmp_path)
    assert "plan.json: points.b[0]: a whole number of 5000 digits" in line
    text = keys.read_text()
    keys.write_text(text.replace('"version": 1', '"version": ' + HUGE, 1))
    line = refused(capsys, ["grade", keys, answers], tmp_path)
    assert "keys.json: version: a whole number of 5000 digits" in line


@pytest.mark.parametrize("seed", ["1" + "0" * 23, HUGE])
def test_a_seed_beyond_64_bits_is_refused(capsys, tmp_path, seed):
    """keys.json is read back with 64-bit whole numbers: a longer seed would make a run whose
    keys cannot be graded."""
    line = refused(capsys, ["variants", GOOD, "--seed", seed, "--out", tmp_path / "run"],
                   tmp_path)
    assert "argument --seed: expected a whole number within ±9223372036854775807" in line


@pytest.mark.parametrize("value", ["NaN", "inf", "-Infinity", "1e999"])
def test_a_drawn_label_at_a_coordinate_that_is_not_finite_is_refused(capsys, tmp_path, value):
    """A label at x="NaN" counted as a point at the pole."""
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
           'viewBox="0 0 100 100"><line x1="0" y1="0" x2="30" y2="10"/>'
           f'<text x="0" y="0">p</text><text x="{value}" y="0">b</text></svg>')
    path = tmp_path / "plan.svg"
    path.write_text(svg)
    line = refused(capsys, ["grade", GOOD, "--drawing", path, "--plan", "velocity"], tmp_path)
    assert f"plan.svg: <text> 'b': x='{value}' is not a finite number" in line


def test_a_polyline_with_a_point_that_is_not_a_number_is_refused(capsys, tmp_path):
    """``NaN`` among a polyline's points shifted every pair after it."""
    path = tmp_path / "plan.svg"
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
                    'viewBox="0 0 100 100"><polyline id="v" points="0 0 NaN 10 30 10"/>'
                    '<text x="0" y="0">p</text><text x="30" y="10">b</text></svg>')
    line = refused(capsys, ["grade", GOOD, "--drawing", path, "--plan", "velocity"], tmp_path)
    assert 'plan.svg: <polyline id="v">: points=' in line


# -- answers that were lost or merged --------------------------------------------------------
LOST_OR_MERGED = {
    # an unterminated quote merged the rest of the file into one student
    "a quote left open": ("student,v_C,omega_BC\ns1,5.27,-24.25\ns2,\"4\ns3,5.27,-24\n"
                          "s4,1,2\n", "answers.csv: line 3: "),
    "a quote closed on a later line": ("student,v_C\ns1,5\ns2,\"4\ns3,5\ns4,\"6\"\n",
                                       "answers.csv: line 3: "),
    "text after a closing quote": ("student,v_C\ns1,5\ns2,\"4\"x\n", "answers.csv: line 3: "),
    "a quote left open in the header": ("student,\"v_C\ns1,5\n", "answers.csv: line 1: "),
    # a repeated column kept the last one silently
    "a column twice": ("student,v_C,v_C\ns1,1,5.27\n", "answers.csv: line 1: column 'v_C' "
                                                      "is given twice (columns 2 and 3)"),
    "a column twice in another case": ("student,v_C,V_c \ns1,1,5.27\n",
                                       "answers.csv: line 1: column 'v_C' and column 'V_c' "
                                       "are one column, compared ignoring case (columns 2 "
                                       "and 3)"),
    "an answer twice in another case": ('{"s1": {"v_C": 1, " V_c": 2}}',
                                        "answers.json: s1: answer 'v_C' and answer ' V_c' are "
                                        "one answer, question ids compared ignoring case"),
    # a header and no student graded an empty class
    "a header and no student": ("student,v_C,omega_BC\n", "answers.csv: a header (line 1) and "
                                                         "no student's answers"),
    "a header and blank lines": ("student,v_C\n\n , \n", "no student's answers"),
    # a JSON object with one stray value collapsed the class into one row for '*'
    "a stray value in a class": ('{"s1": {"v_C": 5.27}, "s2": {"v_C": 4}, "s3": 6}',
                                 "answers.json: s3: is a number, not an object of one "
                                 "student's answers"),
    "an object among one student's answers": ('{"v_C": 5.27, "a_C": 4, "x": {"a": 1}}',
                                              "answers.json: x: is an object, not an answer"),
    "a list as an answer": ('{"s1": {"v_C": [5.27]}}', "answers.json: s1.v_C: is a list"),
    "a key twice": ('{"s1": {"v_C": 1}, "s1": {"v_C": 2}}', "answers.json: s1: the key is "
                                                            "given twice"),
    "an answer twice": ('[{"student": "s1", "v_C": 1, "v_C": 2}]', "answers.json: v_C: the key "
                                                                  "is given twice"),
    "an empty object": ("{}", "answers.json: no student's answers"),
    "an empty list": ("[]", "answers.json: no student's answers"),
    "a student id that is an object": ('[{"student": {"a": 1}, "v_C": 1}]',
                                       "answers.json: [0].student: no student id"),
    "a 5,000-digit answer": ('{"s1": {"v_C": ' + HUGE + "}}",
                             "answers.json: s1.v_C: a whole number of 5000 digits"),
    # the keys of grade's own output, whatever their values, are no class of students
    "grade's keys alone": ('{"answers": {}, "drawings": {}}',
                           "answers.json: this is planmethod grade's --json output"),
}


@pytest.mark.parametrize("case", list(LOST_OR_MERGED))
def test_answers_that_would_be_lost_or_merged_are_refused(capsys, tmp_path, case):
    text, expected = LOST_OR_MERGED[case]
    path = tmp_path / ("answers.json" if text.startswith(("{", "[")) else "answers.csv")
    path.write_text(text, encoding="utf-8")
    line = refused(capsys, ["grade", GOOD, path, "--csv", tmp_path / "book.csv",
                            "--json", tmp_path / "out.json"], tmp_path)
    assert expected in line, line


def test_grades_own_results_given_back_as_answers_are_refused(capsys, tmp_path):
    """grade --json output fed to grade gave a gradebook of one student '*' with no answer."""
    answers = tmp_path / "answers.csv"
    answers.write_text("student,v_C,omega_BC\ns1,5.27,-24.25\ns2,4,20\n")
    results = tmp_path / "results.json"
    assert main(["grade", str(GOOD), str(answers), "--json", str(results), "--quiet"]) == 0
    capsys.readouterr()
    line = refused(capsys, ["grade", GOOD, results, "--csv", tmp_path / "book.csv"], tmp_path)
    assert "results.json: this is planmethod grade's --json output" in line
    # its list of graded students, too
    listed = tmp_path / "listed.json"
    listed.write_text(json.dumps(json.loads(results.read_text())["answers"]))
    line = refused(capsys, ["grade", GOOD, listed], tmp_path)
    assert "listed.json: [0]: this is planmethod grade's --json output" in line


VALID_ANSWERS = {
    "a plain class": "student,v_C,omega_BC\ns1,5.27,-24.25\ns2,4,20\n",
    "quoted cells with commas": 'student,v_C,omega_BC\n"s1, Ann","5,27","-24,25"\ns2,4,20\n',
    "doubled quotes": 'student,v_C\n"Ann ""the"" Lee",5.27\ns2,4\n',
    "semicolons": "student;v_C;omega_BC\ns1;5,27;-24,25\ns2;4;20\n",
    "tabs and a blank line": "student\tv_C\ns1\t5.27\n\ns2\t4\n",
    "CRLF line ends": "student,v_C\r\ns1,5.27\r\ns2,4\r\n",
    "JSON by student": '{"s1": {"v_C": 5.27}, "s2": {"v_C": null}}',
    "a JSON list": '[{"student": "s1", "v_C": 5.27}, {"student": 2, "answers": {"v_C": 4}}]',
}


@pytest.mark.parametrize("case", list(VALID_ANSWERS))
def test_every_student_of_a_valid_file_is_in_the_gradebook(capsys, tmp_path, case):
    """The post-condition: a file that is read has every one of its students graded."""
    import csv

    text = VALID_ANSWERS[case]
    path = tmp_path / ("answers.json" if text.startswith(("{", "[")) else "answers.csv")
    path.write_bytes(text.encode("utf-8"))
    book = tmp_path / "book.csv"
    assert main(["grade", str(GOOD), str(path), "--csv", str(book), "--quiet"]) == 0
    capsys.readouterr()
    graded = [row["student"] for row in csv.DictReader(book.open(encoding="utf-8"))]
    expected = {"a plain class": ["s1", "s2"], "quoted cells with commas": ["s1, Ann", "s2"],
                "doubled quotes": ['Ann "the" Lee', "s2"]}.get(case, ["s1", "s2" if "list"
                                                                    not in case else "2"])
    assert graded == expected


def test_a_roster_with_a_quote_left_open_is_refused(capsys, tmp_path):
    """variants --students reads a roster the way grade reads answers: nobody is merged."""
    roster = tmp_path / "roster.csv"
    roster.write_text('student,email\nann,"ann@x.org\nbob,bob@x.org\n')
    line = refused(capsys, ["variants", TEMPLATE, "--students", roster, "--out",
                            tmp_path / "run", "--no-sheets"], tmp_path)
    assert "roster.csv: line 2: " in line


# -- study: the limits of the exercise file --------------------------------------------------
@pytest.mark.parametrize(("option", "value"), [
    ("--omegas", "1e9"), ("--omegas", "10:20010:10000"), ("--base-omega", "1e5"),
    ("--weights", "1e13"), ("--base-weight", "-2e12"), ("--moments", "1e300"),
    ("--moments", "80,1e300"), ("--base-moment", "inf"),
])
def test_study_options_beyond_the_limits_are_refused(capsys, tmp_path, option, value):
    line = refused(capsys, ["study", STUDY, option, value, "--step", "30", "--csv",
                            tmp_path / "s.csv"], tmp_path)
    assert line.startswith(f"planmethod study: error: argument {option}: ")
    assert "at most 10000 rad/s" in line or "at most 1e+12 N" in line, line


# -- Moodle Cloze: text cannot add a sub-question --------------------------------------------
#: Moodle's own expression for a Cloze field (question/type/multianswer/questiontype.php,
#: ANSWER_REGEX), in Python: PCRE's look-behind of three widths as three look-behinds
_CLOZE_TYPES = ("NUMERICAL|NM|MULTICHOICE|MC|MULTICHOICE_V|MCV|MULTICHOICE_H|MCH|SHORTANSWER|"
                "SA|MW|SHORTANSWER_C|SAC|MWC|MULTICHOICE_S|MCS|MULTICHOICE_VS|MCVS|"
                "MULTICHOICE_HS|MCHS|MULTIRESPONSE|MR|MULTIRESPONSE_H|MRH|MULTIRESPONSE_S|MRS|"
                "MULTIRESPONSE_HS|MRHS")
_ALTERNATIVE = (r"(=|%(-?[0-9]+(?:[.,][0-9]*)?)%)?(.+?(?<!\\)(?<!&)(?<!&amp;)(?=[~#}]|$))"
                r"(#(.*?(?<!\\)(?=[~}]|$)))?")
_CLOZE_FIELD = (rf"\{{([0-9]*):({_CLOZE_TYPES}):({_ALTERNATIVE}(~{_ALTERNATIVE})*)\}}")


def cloze_sub_questions(text: str) -> int:
    """How many sub-questions Moodle makes of a Cloze question text: it takes the first field,
    replaces it by ``{#n}`` and goes on, as qtype_multianswer_extract_question does."""
    import re

    count = 0
    while (match := re.search(_CLOZE_FIELD, text, re.S)) is not None:
        count += 1
        text = text.replace(match.group(0), f"{{#{count}}}", 1)
    return count


HOSTILE_TEXT = "Crank {1:MULTICHOICE:=yes~no} {#1} {2:SA:=x} } \\{3:NM:=1:1\\}"


def test_hostile_text_adds_no_cloze_sub_question(capsys, tmp_path):
    """A title, a description and a student id holding Cloze fields (and a {#1} that would
    repeat one) leave every variant with exactly one sub-question per asked value."""
    from defusedxml.ElementTree import fromstring

    exercise = tmp_path / "hostile.toml"
    text = BASE.replace('title = "Compressor slider-crank (Abduvaliev & Abduxoshimov)"',
                        f"title = {json.dumps(HOSTILE_TEXT)}", 1)
    exercise.write_text(text.replace('description = """\n',
                                     f'description = """\n{HOSTILE_TEXT.replace(chr(92), "")}\n',
                                     1), encoding="utf-8")
    roster = tmp_path / "roster.csv"
    roster.write_text('student\ns1\n"{1:NM:=5:1} {#2}"\n', encoding="utf-8")
    run = tmp_path / "run"
    assert main(["variants", str(exercise), "--students", str(roster), "--out", str(run),
                 "--no-sheets"]) == 0
    assert main(["export", str(run / "keys.json"), "--format", "moodle", "--out",
                 str(tmp_path / "quiz.xml")]) == 0
    capsys.readouterr()
    keys = json.loads((run / "keys.json").read_text())["keys"]
    assert len(keys) == 2 and "MULTICHOICE" in keys[0]["title"] + keys[0]["task"]
    quiz = fromstring((tmp_path / "quiz.xml").read_bytes())
    questions = quiz.findall("question[@type='cloze']")
    assert len(questions) == 2
    for question, key in zip(questions, keys, strict=True):
        html = question.find("questiontext/text").text
        assert cloze_sub_questions(html) == len(key["questions"]) == html.count(":NUMERICAL:")
        assert "{#" not in html and "&#123;1:MULTICHOICE:=yes~no&#125;" in html
    category = quiz.find("question[@type='category']/category/text").text
    assert category.count("/") - 2 * category.count("//") == 3   # $course$/top/cat/title


# -- no CSV cell starts a formula ------------------------------------------------------------
FORMULAS = ("=HYPERLINK(\"http://x\",\"y\")", "+cmd|' /C calc'!A0", "-2+3", "@SUM(A1)",
            "\tx", "\rx")


def _cells(path: Path) -> list[str]:
    import csv

    with path.open(encoding="utf-8", newline="") as handle:
        return [cell for row in csv.reader(handle) for cell in row]


def _starts_a_formula(cell: str) -> bool:
    import re

    number = re.fullmatch(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", cell)
    return number is None and cell.lstrip(" ").startswith(("=", "+", "-", "@", "\t", "\r"))


def test_no_csv_cell_written_starts_a_formula(capsys, tmp_path):
    """Hostile student ids, question ids and notes go into every CSV planmethod writes — the
    gradebook of grade and of export, the class report, index.csv, the sweep and study tables —
    and no text cell starts a formula; numbers (negative ones too) stay numbers, and the ids
    read back through io.spreadsheet_text are the ids given."""
    import csv

    from planmethod.io import spreadsheet_text

    roster = tmp_path / "roster.csv"
    with roster.open("w", encoding="utf-8", newline="") as handle:
        csv.writer(handle).writerows([["student", "email"], *[[f, f"{n}@x.org"] for n, f in
                                                              enumerate(FORMULAS[:4])],
                                      ["-7", "m@x.org"], ["'q", "q@x.org"]])
    run = tmp_path / "run"
    assert main(["variants", str(TEMPLATE), "--students", str(roster), "--out", str(run),
                 "--no-sheets", "--seed", "3"]) == 0
    keys = json.loads((run / "keys.json").read_text())["keys"]
    answers = tmp_path / "answers.json"
    answers.write_text(json.dumps({key["student"]: {q["id"]: -q["value"]
                                                    for q in key["questions"]}
                                   for key in keys} | {"=1+1": {"v_C": 1}}))
    book, report = tmp_path / "book.csv", tmp_path / "report"
    assert main(["grade", str(run / "keys.json"), str(answers), "--csv", str(book),
                 "--report", str(report), "--quiet"]) == 0
    exported = tmp_path / "exported.csv"
    assert main(["export", str(run / "keys.json"), "--format", "csv", "--answers",
                 str(answers), "--out", str(exported)]) == 0
    sweep, study = tmp_path / "sweep.csv", tmp_path / "study.csv"
    assert main(["sweep", str(GOOD), "--step", "30", "--csv", str(sweep)]) == 0
    assert main(["study", str(STUDY), "--step", "30", "--csv", str(study), "--omegas",
                 "10,20", "--weights", "20,40", "--moments", "80,100"]) == 0
    capsys.readouterr()
    written = [book, exported, report / "questions.csv", report / "mistakes.csv",
               run / "index.csv", sweep, study]
    for path in written:
        cells = _cells(path)
        assert cells and not [c for c in cells if _starts_a_formula(c)], path
    # the hostile ids are in the gradebooks, neutralised, and read back exactly
    for path in (book, exported, run / "index.csv"):
        students = [spreadsheet_text(row[0]) for row in _rows(path)[1:]]
        assert set(students) >= {*FORMULAS[:4], "-7", "'q"}, (path, students)
    # numbers stay numbers: the sweep's negative values are plain numbers, not quoted text
    assert any(cell.startswith("-") and float(cell) < 0 for cell in _cells(sweep))
    # a second run with --force reads index.csv back: the folders of ids that needed a ' are
    # its own, and are replaced
    assert main(["variants", str(TEMPLATE), "--students", str(roster), "--out", str(run),
                 "--no-sheets", "--seed", "3", "--force"]) == 0
    capsys.readouterr()


def _rows(path: Path) -> list[list[str]]:
    import csv

    with path.open(encoding="utf-8", newline="") as handle:
        return list(csv.reader(handle))


# -- variants: a count that finishes in about a minute ---------------------------------------
def test_more_variants_than_a_minute_draws_are_refused_at_once(capsys, tmp_path):
    """`--count` (and a roster) stop at MAX_VARIANTS, the count benchmarked to take about a
    minute; the refusal comes before any variant is drawn."""
    from planmethod.application.variants import MAX_VARIANTS

    line = refused(capsys, ["variants", TEMPLATE, "--count", MAX_VARIANTS + 1, "--out",
                            tmp_path / "run"], tmp_path)
    assert f"--count must be in 1…{MAX_VARIANTS}" in line
    roster = tmp_path / "roster.csv"
    roster.write_text("student\n" + "\n".join(f"s{i}" for i in range(MAX_VARIANTS + 1)) + "\n")
    line = refused(capsys, ["variants", TEMPLATE, "--students", roster, "--out",
                            tmp_path / "run"], tmp_path)
    assert f"roster.csv: the roster lists {MAX_VARIANTS + 1} students" in line


# -- drawn points that were merged, and errors that named the wrong file (issue 35) ------------
SLOTTED = ROOT / "exercises" / "slotted_crank_crosshead.toml"


@pytest.fixture(scope="module")
def key_points():
    """The velocity plan's points of the compressor's key (mm), as a right drawing gives
    them."""
    from planmethod.grading.keys import build_key
    from planmethod.grading.templates import draw_variant, load_template

    key = build_key(draw_variant(load_template(GOOD)))
    return {label: list(xy) for label, xy in key["plans"]["velocity"]["points_mm"].items()}


def _points_json(points: dict, extra: str = "") -> str:
    """A drawing's JSON with ``extra`` members written after the points (json.dumps cannot
    write a key twice)."""
    members = [f"{json.dumps(label)}: {json.dumps(xy)}" for label, xy in points.items()]
    return '{"plan": "velocity", "points": {' + ", ".join(members) + extra + "}}"


MERGED_POINTS = {
    # the second value of c was kept, the first lost without a word
    "a point twice": (', "c": [1, 2]', "plan.json: c: the key is given twice in one object"),
    "a point with a space": (', " c": [1, 2]', "plan.json: points: point 'c' and point ' c' "
                                               "are one point, labels compared without spaces"),
    "the pole as pi": (', "pi": [1, 2]', None),   # p and pi name two points: both graded
    "p and p′ written p'": (', "p\'": [1, 2]', None),
}


@pytest.mark.parametrize("case", list(MERGED_POINTS))
def test_every_drawn_point_is_graded_or_both_are_named(capsys, tmp_path, key_points, case):
    """The post-condition: a drawing that is read has every one of its points graded (each
    key point's result is the point the file gives for it); one that would lose a point is
    refused, naming both."""
    extra, expected = MERGED_POINTS[case]
    path = tmp_path / "plan.json"
    path.write_text(_points_json(key_points, extra), encoding="utf-8")
    if expected is not None:
        assert expected in refused(capsys, ["grade", GOOD, "--drawing", path], tmp_path)
        return
    graded = tmp_path / "graded.json"
    assert main(["grade", str(GOOD), "--drawing", str(path), "--json", str(graded)]) == 0
    capsys.readouterr()
    (drawing,) = json.loads(graded.read_text())["drawings"]
    assert drawing["score"] == drawing["max_score"] > 0
    assert all(result["distance_mm"] < 1e-9 for result in drawing["points"])


def test_pi_and_its_name_are_one_point(capsys, tmp_path):
    path = tmp_path / "plan.json"
    path.write_text('{"plan": "acceleration", "points": {"π": [0, 0], "pi": [3, 4]}}',
                    encoding="utf-8")
    line = refused(capsys, ["grade", GOOD, "--drawing", path], tmp_path)
    assert "plan.json: points: point 'π' and point 'pi' are one point" in line


def _svg(body: str) -> str:
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="200mm" '
            f'viewBox="0 0 200 200">{body}</svg>')


def _svg_labels(points: dict, extra: str = "") -> str:
    """The drawing of ``points`` as labelled dots (SVG's y down), pole at (100, 100)."""
    return _svg("".join(f'<circle cx="{100 + x:.4f}" cy="{100 - y:.4f}" r="0.3"/>'
                        f'<text x="{100 + x:.4f}" y="{100 - y:.4f}">{label}</text>'
                        for label, (x, y) in points.items() if "@" not in label) + extra)


@pytest.mark.parametrize(("extra", "graded"), [
    ('<text x="150" y="150">c</text>', False),              # c marked at a second place
    ('<text x="150" y="150"> c</text>', False),             # … written with a space
    ('<text x="150" y="150">C</text>', True),    # the mechanism's C: c is matched exactly
    ('<text x="10" y="10">10 mm</text><text x="10" y="20">10 mm</text>', True),   # no point
])
def test_a_graded_point_labelled_at_two_places_is_refused(capsys, tmp_path, key_points, extra,
                                                          graded):
    path = tmp_path / "plan.svg"
    path.write_text(_svg_labels(key_points, extra), encoding="utf-8")
    argv = ["grade", GOOD, "--drawing", path, "--plan", "velocity"]
    if graded:
        assert main([str(a) for a in argv]) == 0
        assert "3/3" in capsys.readouterr().out
        return
    line = refused(capsys, argv, tmp_path)
    assert "plan.svg: <text> 'c' at (" in line and "both mark the point c" in line
    assert line.count("<text>") == 2 and "at (150.0, 150.0) mm" in line


@pytest.mark.parametrize(("drawing", "expected"), [
    # the point at 1e308 named the exercise (an overflow), the angle no file and no key
    ('{"plan": "velocity", "points": {"p": [0, 0], "b": [1e308, 0]}}',
     "plan.json: points.b: is at (1e+308, 0) mm, beyond ±1e+06 mm"),
    ('{"format": "planmethod-drawing", "title": "TITLE", "angle": 1e6, "plan": "velocity", '
     '"points": {"p": [0, 0]}}', "plan.json: angle: must be the crank angle in degrees, "
                                 "within ±36000°, got 1000000.0"),
])
def test_a_drawing_out_of_range_names_the_drawing_and_its_key(capsys, tmp_path, drawing,
                                                              expected):
    from planmethod.spec import load_exercise

    path = tmp_path / "plan.json"
    title = json.dumps(load_exercise(GOOD).mechanism.title)[1:-1]
    path.write_text(drawing.replace("TITLE", title), encoding="utf-8")
    line = refused(capsys, ["grade", GOOD, "--drawing", path], tmp_path)
    assert line.startswith(f"planmethod: error: {path}: {expected.removeprefix('plan.json: ')}")
    assert str(GOOD) not in line


def test_a_drawing_at_an_angle_of_toggle_names_the_drawing(capsys, tmp_path):
    """The key posed at the drawing's angle stands at a toggle: the drawing's angle is what
    is wrong, not the exercise."""
    from planmethod.spec import load_exercise

    path = tmp_path / "plan.json"
    path.write_text(json.dumps({"format": "planmethod-drawing", "angle": 120,
                                "title": load_exercise(SLOTTED).mechanism.title,
                                "plan": "velocity", "points": {"p": [0, 0]}}))
    line = refused(capsys, ["grade", SLOTTED, "--drawing", path], tmp_path)
    assert line.startswith(f"planmethod: error: {path}: angle: link block+crosshead, crank "
                           "angle 120°: the guides")


def test_a_drawing_scaled_beyond_correction_is_graded_as_drawn(capsys, tmp_path, key_points):
    """pb drawn 1e-300 mm long: the rescaling overflowed; it is graded as drawn."""
    points = {label: [x * 1e-301, y * 1e-301] for label, (x, y) in key_points.items()}
    path = tmp_path / "plan.json"
    path.write_text(_points_json(points))
    assert main(["grade", str(GOOD), "--drawing", str(path)]) == 0
    out = capsys.readouterr().out
    assert "0/3" in out and "more than 10000 times off; it was graded as drawn" in out


@pytest.mark.parametrize("bundle", [False, True])
def test_an_error_in_a_keys_exercise_names_the_key_file(capsys, tmp_path, bundle):
    """The key keeps its exercise's tables: an error in them named the template the key was
    built from, not the key file."""
    run = tmp_path / "run"
    assert main(["variants", str(TEMPLATE), "--out", str(run), "--count", "2",
                 "--no-sheets"]) == 0
    data = json.loads((run / "keys.json").read_text())
    data["keys"][1]["exercise"]["drive"]["omega"] = 1e9
    keys = tmp_path / ("keys.json" if bundle else "key.json")
    keys.write_text(json.dumps(data if bundle else data["keys"][1]))
    capsys.readouterr()
    where = "keys[1].exercise" if bundle else "exercise"
    line = refused(capsys, ["export", keys, "--format", "prairielearn", "--out",
                            tmp_path / "pl"], tmp_path)
    assert line.startswith(f"planmethod: error: {keys}: {where}.drive.omega: must be at most "
                           "10000"), line
    assert str(TEMPLATE) not in line


CHECK_TABLE = ROOT / "exercises" / "conveyor_sixbar_table2.csv"


@pytest.mark.parametrize(("cell", "value", "expected"), [
    # an angle of 1e300 was a traceback (an index beyond the path's table)
    (0, "1e300", "line 4, column angle: must be within ±36000°, got 1e300"),
    (1, "1e308", "line 4, column x_A: must be within ±1e+06 m, got 1e308"),
])
def test_a_coordinates_table_out_of_range_names_its_cell(capsys, tmp_path, cell, value,
                                                         expected):
    lines = CHECK_TABLE.read_text(encoding="utf-8").splitlines()
    first = next(index for index, line in enumerate(lines) if line[:1].isdigit())
    cells = lines[first].split(",")
    cells[cell] = value
    lines[first] = ",".join(cells)
    table = tmp_path / "table.csv"
    table.write_text("\n".join(lines) + "\n")
    line = refused(capsys, ["check", ROOT / "exercises" / "conveyor_sixbar.toml", table],
                   tmp_path)
    assert line == f"planmethod: error: {table}: {expected}"


def test_a_coordinates_column_twice_is_refused(capsys, tmp_path):
    """x_A and X_A: one of the two columns was kept without a word."""
    table = tmp_path / "table.csv"
    table.write_text("angle,x_A,y_A,X_A\n135,0.1,0.2,0.3\n")
    line = refused(capsys, ["check", ROOT / "exercises" / "conveyor_sixbar.toml", table],
                   tmp_path)
    assert line == (f"planmethod: error: {table}: line 1: column 'x_A' and column 'X_A' are "
                    "one column, the axis compared ignoring case (columns 2 and 4); keep one")
