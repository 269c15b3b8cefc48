"""The ``[course]`` table: the language an exercise is set in, read and checked with the file,
kept on the exercise (never on the mechanism, which stays one solve for every language), and
carried from a template to each of its variants."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from planmethod.cli import main
from planmethod.errors import SpecError
from planmethod.grading.templates import draw_variant, parse_template, to_toml
from planmethod.kinematics.program import model
from planmethod.model import Course
from planmethod.spec import course_from_dict, parse_exercise

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = (ROOT / "exercises" / "compressor_slider_crank.toml").read_text(encoding="utf-8")
TEMPLATE = (ROOT / "exercises" / "templates" / "slider_crank.toml").read_text(encoding="utf-8")


def _with_course(text: str, table: str) -> str:
    return f"{text}\n[course]\n{table}\n"


def test_the_language_is_the_exercises_and_the_mechanism_stays_one():
    plain = parse_exercise(COMPRESSOR, file="c.toml")
    russian = parse_exercise(_with_course(COMPRESSOR, 'language = "ru"'), file="c.toml")
    assert (plain.course, russian.course) == (Course(), Course("ru"))
    assert plain != russian
    # one mechanism: equal, hashed alike, and its compiled model found again
    assert russian.mechanism == plain.mechanism
    assert hash(russian.mechanism) == hash(plain.mechanism)
    assert model(russian.mechanism) is model(plain.mechanism)


@pytest.mark.parametrize(("table", "said"), [
    ('language = "zz"', "course.language: no catalogue for the language zz"),
    ('language = "r u"', "course.language: 'r u' is no language code (such as en or ru)"),
    ("language = 7", "course.language: must be a non-empty string, got 7"),
    ('lang = "ru"', "course.lang: unknown key (did you mean 'language'?); expected one of "
                    "language"),
])
def test_a_language_that_cannot_be_spoken_is_one_line_naming_the_key(tmp_path, capsys, table,
                                                                      said):
    path = tmp_path / "bad.toml"
    path.write_text(_with_course(COMPRESSOR, table), encoding="utf-8")
    code = main(["solve", str(path)])
    out, err = capsys.readouterr()
    assert code == 2 and not out
    assert err.startswith(f"planmethod: error: {path}: {said}") and err.count("\n") == 1


def test_course_must_be_a_table():
    with pytest.raises(SpecError, match=r"^t\.toml: course: must be a table, got 'ru'$"):
        course_from_dict({"course": "ru"}, file="t.toml")


def test_a_templates_course_is_carried_to_its_variants():
    template = parse_template(_with_course(TEMPLATE, 'language = "ru"'), file="t.toml")
    variant = draw_variant(template, student="s01")
    assert variant.exercise.course == Course("ru")
    # the variant's own file says it too, so that its sheets and key speak the language
    assert tomllib.loads(to_toml(variant.data))["course"] == {"language": "ru"}
