"""The translation catalogues' build: the templates read from the code, the catalogue files
written from them.

``python -m planmethod.words.catalogue`` reads every :func:`~planmethod.words.message.message`,
:func:`~planmethod.words.message.plural` and :func:`~planmethod.words.message.template` call
of the package (with :mod:`ast`: a template is a literal string at its call), writes the
catalogue template
``planmethod/locale/planmethod.pot``, brings each language's ``.po`` up to date with it (a
template that changed keeps its old translation marked fuzzy) and compiles every ``.po`` to
the ``.mo`` that :mod:`gettext` reads. A template's place is written as its file without the
line, so that moving code does not change the catalogues. The English ``.mo`` translates each
template to itself: it is the list of templates a language's catalogue is measured against
(:func:`planmethod.words.language.missing`).

Reading the templates needs only the standard library; writing the files uses Babel (the
``languages`` extra; the test extra has it).

Examples
--------
>>> source = 'raise SpecError(message("no link {link}", link=name))'
>>> [(found.template, found.fields) for found in templates_in(source, "x.py")]
[('no link {link}', ('link',))]
"""

from __future__ import annotations

import argparse
import ast
import datetime
import string
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

__all__ = ["PACKAGE", "Template", "build", "compile_folder", "new", "package_templates",
           "templates_in"]

PACKAGE = Path(__file__).resolve().parent.parent
LOCALE = PACKAGE / "locale"
DOMAIN = "planmethod"
#: the date written into the catalogues' headers: fixed, so that a build is repeatable
_DATE = datetime.datetime(2026, 1, 1, tzinfo=datetime.UTC)
#: the functions whose first literal arguments are templates
_MAKERS = {"message": 1, "plural": 2, "template": 1}


@dataclass(frozen=True, slots=True)
class Template:
    """A template found in the code: its English forms, context, the fields its call gives
    (None where the call passes ``**fields``) and where it stands."""

    forms: tuple[str, ...]
    context: str | None
    fields: tuple[str, ...] | None
    file: str
    line: int

    @property
    def template(self) -> str:
        return self.forms[0]

    def names(self) -> set[str]:
        """The field names its forms use."""
        return {name.split(".")[0].split("[")[0]
                for form in self.forms for _, name, _, _ in string.Formatter().parse(form)
                if name}


def _name(call: ast.Call) -> str | None:
    function = call.func
    return function.id if isinstance(function, ast.Name) else (
        function.attr if isinstance(function, ast.Attribute) else None)


def _maker(call: ast.Call) -> int:
    return _MAKERS.get(_name(call), 0)


def templates_in(source: str, file: str) -> Iterator[Template]:
    """The templates of one module's source (a call whose template is not a literal string
    is yielded with the form ``""``, for the tests to refuse)."""
    for node in ast.walk(ast.parse(source, file)):
        if not isinstance(node, ast.Call) or not (count := _maker(node)):
            continue
        arguments = node.args[:count]
        forms = tuple(argument.value if isinstance(argument, ast.Constant)
                      and isinstance(argument.value, str) else "" for argument in arguments)
        if len(forms) < count:
            forms += ("",) * (count - len(forms))
        context = next((keyword.value.value for keyword in node.keywords
                        if keyword.arg == "context" and isinstance(keyword.value, ast.Constant)),
                       None)
        given = [keyword.arg for keyword in node.keywords if keyword.arg != "context"]
        # a template()'s fields come later (Message.replace); a **fields call's are unknown
        fields = None if None in given or _name(node) == "template" else tuple(given)
        yield Template(forms, context, fields, file, node.lineno)


def package_templates(root: Path = PACKAGE) -> list[Template]:
    """Every template of the package, in file and line order."""
    found = []
    for path in sorted(root.rglob("*.py")):
        relative = str(path.relative_to(root.parent))
        found.extend(templates_in(path.read_text(encoding="utf-8"), relative))
    return found


def _babel():
    try:
        from babel.messages import catalog, mofile, pofile
    except ImportError:
        sys.exit("planmethod: error: building catalogues needs Babel: "
                 "pip install 'planmethod[languages]'")
    return catalog, mofile, pofile


def _template_catalogue(found: list[Template]):
    catalog, _, _ = _babel()
    template = catalog.Catalog(project="planmethod", domain=DOMAIN, fuzzy=False,
                               charset="utf-8", creation_date=_DATE, revision_date=_DATE,
                               copyright_holder="the planmethod contributors")
    for item in found:
        key = item.forms if len(item.forms) > 1 else item.template
        template.add(key, locations=[(item.file, item.line)], context=item.context,
                     flags=("python-brace-format",))
    return template


def new(language: str, folder: Path) -> str:
    """Start a catalogue for ``language`` under ``folder`` from the package's template: every
    template untranslated (shown in English until it is)."""
    catalog, _, pofile = _babel()
    with open(LOCALE / f"{DOMAIN}.pot", "rb") as file:
        template = pofile.read_po(file)
    fresh = catalog.Catalog(locale=language, domain=DOMAIN, charset="utf-8", project="planmethod",
                            copyright_holder="the planmethod contributors",
                            creation_date=_DATE, revision_date=_DATE, fuzzy=False)
    fresh.update(template, update_header_comment=False)
    target = folder / language / "LC_MESSAGES" / f"{DOMAIN}.po"
    if target.exists():
        sys.exit(f"planmethod: error: {target} exists already (compile it, or remove it to "
                 "start again)")
    return _write(target, lambda file: pofile.write_po(file, fresh, sort_output=True,
                                                       width=100, include_lineno=False))


def compile_folder(folder: Path) -> list[str]:
    """Compile every ``<language>/LC_MESSAGES/planmethod.po`` under ``folder`` to its
    ``.mo`` (fuzzy translations are left out: they show in English)."""
    _, mofile, pofile = _babel()
    written = []
    for po in sorted(folder.glob(f"*/LC_MESSAGES/{DOMAIN}.po")):
        with open(po, "rb") as file:
            language = pofile.read_po(file)
        _drop_untranslated_plurals(language)
        written.append(_write(po.with_suffix(".mo"), lambda file, language=language:
                              mofile.write_mo(file, language, use_fuzzy=False)))
    return written


def _drop_untranslated_plurals(language) -> None:
    """Leave a plural that has no translation out of a catalogue to compile: Babel would
    write its English forms as its translation (a plural's translation is a tuple, never
    empty), and the catalogue would count it as translated (:func:`~planmethod.words.
    language.missing`)."""
    for entry in list(language):
        if entry.id and entry.pluralizable and not any(entry.string):
            language.delete(entry.id, context=entry.context)


def build(root: Path = PACKAGE) -> list[str]:
    """Write the template, update every language's ``.po`` and compile the ``.mo`` files;
    returns what was written."""
    catalog, mofile, pofile = _babel()
    template = _template_catalogue(package_templates(root))
    locale = root / "locale"
    written = [_write(locale / f"{DOMAIN}.pot", lambda file: pofile.write_po(
        file, template, omit_header=False, sort_output=True, width=100,
        include_lineno=False))]
    english = catalog.Catalog(locale="en", domain=DOMAIN, charset="utf-8",
                              creation_date=_DATE, revision_date=_DATE)
    for entry in template:
        if entry.id:
            english.add(entry.id, entry.id, context=entry.context)
    written.append(_write(locale / "en" / "LC_MESSAGES" / f"{DOMAIN}.mo",
                          lambda file: mofile.write_mo(file, english)))
    for po in sorted(locale.glob(f"*/LC_MESSAGES/{DOMAIN}.po")):
        with open(po, "rb") as file:
            language = pofile.read_po(file)
        language.update(template, update_header_comment=False)
        written.append(_write(po, lambda file, language=language: pofile.write_po(
            file, language, sort_output=True, width=100, ignore_obsolete=True,
            include_lineno=False)))
    return written + compile_folder(locale)


def _write(path: Path, writer) -> str:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "wb") as file:
        writer(file)
    return str(path)


def main(argv: list[str] | None = None) -> int:
    """``python -m planmethod.words.catalogue [build | new LANGUAGE FOLDER | compile FOLDER]``:
    rebuild the package's catalogues from the code (a developer), or start and compile a
    course's own catalogue (docs/languages.md)."""
    parser = argparse.ArgumentParser(prog="python -m planmethod.words.catalogue",
                                     description=__doc__.split("\n\n")[0])
    steps = parser.add_subparsers(dest="step")
    steps.add_parser("build", help="the package's template and catalogues, from the code")
    start = steps.add_parser("new", help="start a course's catalogue for a language")
    start.add_argument("language")
    start.add_argument("folder", type=Path)
    steps.add_parser("compile", help="compile a course's catalogues").add_argument(
        "folder", type=Path)
    args = parser.parse_args(argv)
    if args.step == "new":
        written = [new(args.language, args.folder)]
    elif args.step == "compile":
        written = compile_folder(args.folder)
    else:
        written = build()
    for path in written:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
