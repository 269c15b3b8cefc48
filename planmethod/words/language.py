"""The course's language: which one is spoken now, and its translation catalogue.

A language is chosen per run: the command line's ``--lang`` wins over the exercise file's
``[course] language``, which wins over the environment variable ``PLANMETHOD_LANG``; English
is the default (:func:`choose`). While text is made, :func:`speaking` holds the choice (a
context variable, so a server's threads and a notebook's cells each keep their own).

Catalogues are gettext's: ``<folder>/<language>/LC_MESSAGES/planmethod.mo``, read with the
standard library's :mod:`gettext` the first time a language speaks. The folders searched are
those of ``PLANMETHOD_LOCALE_DIR`` (a course's own catalogues, ``os.pathsep``-separated), then
the catalogues shipped inside the package (English and Russian). A catalogue that lacks some
templates falls back to English for those (:func:`missing` counts them).

Examples
--------
>>> choose(None, "ru", {"PLANMETHOD_LANG": "en"}), choose("en", "ru", {})
('ru', 'en')
>>> with speaking("ru"):
...     current()
'ru'
>>> current()
'en'
>>> problem("x y") is not None, problem("ru")
(True, None)
"""

from __future__ import annotations

import contextlib
import functools
import gettext
import os
import re
from collections.abc import Iterator, Mapping
from contextvars import ContextVar
from pathlib import Path

from .message import Message, message

__all__ = ["DOMAIN", "ENGLISH", "ENVIRONMENT", "LOCALE_ENVIRONMENT", "SHIPPED", "catalogue",
           "choose", "current", "missing", "problem", "speaking"]

#: the catalogues' gettext domain (the file name of a compiled catalogue)
DOMAIN = "planmethod"
#: the language every template is written in, spoken when nothing else is chosen
ENGLISH = "en"
#: the languages whose catalogues come with the package
SHIPPED = ("en", "ru")
#: the environment variable that chooses a language
ENVIRONMENT = "PLANMETHOD_LANG"
#: the environment variable that names a course's own catalogue folders
LOCALE_ENVIRONMENT = "PLANMETHOD_LOCALE_DIR"

#: a language's code as gettext names its folders: ``ru``, ``uz``, ``kk``, ``uz_Latn``, ``pt_BR``
_CODE = re.compile(r"[a-z]{2,3}(_[A-Za-z]{2,4})?")

_spoken: ContextVar[str | None] = ContextVar("planmethod_language", default=None)


def _folders() -> tuple[Path, ...]:
    extra = os.environ.get(LOCALE_ENVIRONMENT, "")
    own = tuple(Path(part) for part in extra.split(os.pathsep) if part)
    return (*own, Path(__file__).resolve().parent.parent / "locale")


def _has_catalogue(language: str) -> bool:
    return any((folder / language / "LC_MESSAGES" / f"{DOMAIN}.mo").is_file()
               for folder in _folders())


def problem(language: str) -> Message | None:
    """Why ``language`` cannot be spoken (a code that is no language's, or no catalogue for
    it), or None if it can. The caller raises it with the file and key it came from."""
    if not isinstance(language, str) or not _CODE.fullmatch(language):
        return message("'{language}' is no language code (such as en or ru)",
                       language=str(language)[:40])
    if language != ENGLISH and not _has_catalogue(language):
        return message("no catalogue for the language {language} (shipped: {shipped}; a "
                       "course adds one as docs/languages.md says)", language=language,
                       shipped=", ".join(SHIPPED))
    return None


def choose(option: str | None, file: str | None,
           environment: Mapping[str, str] = os.environ) -> str:
    """The language of a run: the command line's option, else the exercise file's
    ``[course] language``, else ``PLANMETHOD_LANG``, else English (not checked here:
    :func:`problem`)."""
    return option or file or environment.get(ENVIRONMENT) or ENGLISH


def current() -> str:
    """The language spoken now: the one :func:`speaking` holds, else ``PLANMETHOD_LANG``,
    else English."""
    spoken = _spoken.get()
    return spoken if spoken is not None else _from_environment(os.environ.get(ENVIRONMENT))


@functools.lru_cache(maxsize=8)
def _from_environment(chosen: str | None) -> str:
    """``PLANMETHOD_LANG`` if it can be spoken (a command refuses it in one line before any
    text is made: :func:`problem`), else English."""
    return chosen if chosen and problem(chosen) is None else ENGLISH


@contextlib.contextmanager
def speaking(language: str | None) -> Iterator[str]:
    """Speak ``language`` inside the block (None: leave the language as it is)."""
    if language is None:
        yield current()
        return
    token = _spoken.set(language)
    try:
        yield language
    finally:
        _spoken.reset(token)


@functools.lru_cache(maxsize=16)
def catalogue(language: str) -> gettext.NullTranslations:
    """The translations of ``language`` (English: none, every template is its own text)."""
    if language == ENGLISH:
        return gettext.NullTranslations()
    for folder in _folders():
        try:
            return gettext.translation(DOMAIN, folder, languages=[language])
        except OSError:
            continue
    return gettext.NullTranslations()


def missing(language: str) -> int:
    """How many of the package's templates ``language``'s catalogue does not translate (they
    are shown in English)."""
    if language == ENGLISH:
        return 0
    found = _translated(getattr(catalogue(language), "_catalog", {}))
    return len(_templates() - found)


def _translated(entries: Mapping) -> frozenset:
    """The templates a compiled catalogue translates (a plural's forms count once; gettext
    keys a plural form by ``(template, index)`` and a context as ``context\x04template``)."""
    return frozenset(key[0] if isinstance(key, tuple) else key
                     for key, text in entries.items() if key and text)


@functools.lru_cache(maxsize=1)
def _templates() -> frozenset:
    """Every template of the package: the keys of the English catalogue, which the
    catalogue's build writes from the templates in the code."""
    english = Path(__file__).resolve().parent.parent / "locale" / ENGLISH / "LC_MESSAGES"
    try:
        with open(english / f"{DOMAIN}.mo", "rb") as file:
            translations = gettext.GNUTranslations(file)
    except OSError:
        return frozenset()
    return _translated(translations._catalog)
