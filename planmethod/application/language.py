"""The language a run speaks: the command line's ``--lang`` (or an API call's
``language=``), else the ``[course] language`` of the exercise or template it reads, else
``PLANMETHOD_LANG``, else English (:func:`planmethod.words.language.choose`).

A language that cannot be spoken — a code that is no language's, a language without a
catalogue — is refused in one line naming where it came from (the option, the file and its
key, the environment variable), before any text is made.

The file's language is read in one place, :func:`course_language`, from the tables of an
exercise or template file.

Examples
--------
>>> course_language({"course": {"language": "ru"}}), course_language({"title": "x"})
('ru', None)
>>> run_language("en", environment={"PLANMETHOD_LANG": "ru"})
'en'
>>> run_language(None, environment={"PLANMETHOD_LANG": "x y"})
Traceback (most recent call last):
...
planmethod.errors.SpecError: PLANMETHOD_LANG: 'x y' is no language code (such as en or ru)
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..errors import PlanmethodError, SpecError
from ..words.language import ENVIRONMENT, choose, problem

__all__ = ["COURSE_KEY", "chosen_language", "course_language", "file_language", "keys_language",
           "run_language", "text_language"]

#: the key of an exercise or template file that names its course's language
COURSE_KEY = "course.language"

#: the option that chooses a language on the command line (named in its errors)
OPTION = "option --lang"


def course_language(tables: Mapping[str, Any]) -> Any:
    """The ``[course] language`` the tables of an exercise or template file name, or None
    (a value that is no text is returned as it is, for :func:`run_language` to refuse)."""
    course = tables.get("course") if isinstance(tables, Mapping) else None
    return course.get("language") if isinstance(course, Mapping) else None


def text_language(text: str) -> Any:
    """The ``[course] language`` of an exercise's TOML text, or None (also for text that
    is not TOML: whatever reads it says why)."""
    from ..spec import parse_toml

    try:
        return course_language(parse_toml(text))
    except (PlanmethodError, RecursionError, MemoryError):
        return None


def file_language(path: str | Path | None) -> Any:
    """The ``[course] language`` of an exercise or template file (``.toml``), or the one its
    keys record (:func:`keys_language`: a ``.json`` key or bundle, or a variants folder), or
    None: for another file, or one that cannot be read (the command that reads it says why)."""
    if path is None:
        return None
    if Path(path).suffix.lower() == ".json" or Path(path).is_dir():
        return keys_language(path)
    if Path(path).suffix.lower() != ".toml":
        return None
    from ..spec import read_text

    try:
        text = read_text(path)
    except (PlanmethodError, OSError):
        return None
    return text_language(text)


def keys_language(path: str | Path) -> Any:
    """The ``[course] language`` a key, a bundle of keys (``keys.json``) or the folder
    ``planmethod variants`` wrote records: that of the template its keys were drawn from (a
    key keeps its exercise), or None — also for a file that is no key or cannot be read (the
    command that reads it says why).

    >>> keys_language("no such folder") is None
    True
    """
    from ..grading.keys import load_keys

    try:
        keys = load_keys(path)
    except (PlanmethodError, OSError, RecursionError, MemoryError):
        return None
    exercises = [key.get("exercise") for key in keys.values()]
    return next((course_language(exercise) for exercise in exercises
                 if isinstance(exercise, Mapping)), None)


def run_language(option: str | None, file: str | Path | None = None, *,
                 text: str | None = None,
                 environment: Mapping[str, str] = os.environ) -> str:
    """The language of a run: ``option``, else the ``[course] language`` of ``file`` (or of
    the exercise ``text``), else ``PLANMETHOD_LANG`` of ``environment``, else English.

    Raises
    ------
    SpecError
        If the chosen language cannot be spoken, naming where it came from.
    """
    course = None
    if not option:
        course = text_language(text) if text is not None else file_language(file)
    return chosen_language(option, course, file=file, environment=environment)


def chosen_language(option: str | None, course: Any, *, file: str | Path | None = None,
                    option_key: str = OPTION,
                    environment: Mapping[str, str] = os.environ) -> str:
    """The language of a run whose file's ``[course] language`` is ``course`` (as read:
    :func:`course_language`): ``option``, else ``course``, else ``PLANMETHOD_LANG``, else
    English (:func:`planmethod.words.language.choose`).

    Raises
    ------
    SpecError
        If the chosen language cannot be spoken, naming where it came from: the option
        (``option_key``), the file's key, the environment variable.

    Examples
    --------
    >>> chosen_language(None, "en", environment={"PLANMETHOD_LANG": "x y"})
    'en'
    """
    if not option and course is not None:   # checked as the exercise's reader checks it
        from ..spec import course_from_dict

        return course_from_dict({"course": {"language": course}},
                                file=None if file is None else str(file)).language
    language = choose(option, None, environment)
    why = problem(language)
    if why is not None:
        raise SpecError(why, key=option_key if option else ENVIRONMENT)
    return language
