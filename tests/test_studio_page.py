"""The studio's page without a browser: its markup filled with words in the studio's language,
its scripts served as files under a policy that allows no inline script, and the exercise the
page sends as data written as TOML by Python (planmethod/studio/page.py, exercise_data.py).
The page in Chromium: tests/test_studio_browser.py."""

from __future__ import annotations

import json
import re
import tomllib
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_studio import COMPRESSOR, post_json, request

from planmethod.errors import SpecError
from planmethod.studio.exercise_data import exercise_toml, with_toml
from planmethod.studio.page import PAGE_FILES, SCRIPT_WORDS, page_file, studio_page

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    from planmethod.studio.server import StudioServer

    folder = tmp_path_factory.mktemp("studio-page")
    (folder / "compressor.toml").write_bytes(COMPRESSOR.read_bytes())
    server = StudioServer(folder, 0)
    server.start()
    yield server
    server.stop()


def test_the_page_holds_no_script_of_its_own_and_every_word_filled():
    text = studio_page("en").decode("utf-8")
    assert "⟪" not in text and "{words}" not in text and '<html lang="en">' in text
    scripts = re.findall(r"<script([^>]*)>(.*?)</script>", text, re.S)
    assert [attributes for attributes, _ in scripts] == [
        ' type="application/json" id="studio-words"', ' src="/page_words.js"',
        ' src="/studio.js"', ' src="/studio_runs.js"']
    assert all(not body.strip() for attributes, body in scripts if "src=" in attributes)
    words = json.loads(scripts[0][1])
    assert set(words["templates"]) == set(SCRIPT_WORDS) and words["decimal"] == "."
    assert words["templates"]["job_previewed"] == "Preview: {count} variants drawn"
    assert '<span data-drive-symbol="phi">φ₁</span>' in text   # a symbol set in its words


def test_the_page_and_its_scripts_are_served_under_a_policy_of_scripts_from_the_studio(server):
    status, _, headers = request(server, "GET", "/")
    policy = headers["Content-Security-Policy"]
    assert status == 200 and "script-src 'self'" in policy and "unsafe-inline'; img" in policy
    assert "script-src 'unsafe-inline'" not in policy and "unsafe-eval" not in policy
    for path, (_, name) in PAGE_FILES.items():
        status, _, headers = request(server, "GET", path)
        assert status == 200 and headers["Content-Type"].startswith("text/javascript")
        assert page_file(path).content.startswith(b'"use strict";'), name
        assert request(server, "GET", path, token=False)[0] == 403      # the token, as ever
    assert request(server, "GET", "/studio.html")[0] == 404
    assert request(server, "GET", "/../studio.js")[0] == 404
    assert request(server, "POST", "/studio.js", "x")[0] == 404


def test_the_server_solves_and_saves_the_exercise_the_page_sends_as_data(server):
    tables = post_json(server, "/api/open", {"path": "compressor.toml"})[1]["tables"]
    status, solved, _ = request(server, "POST", "/api/solve", json.dumps({"exercise": tables}),
                                headers={"Content-Type": "application/json"})
    from planmethod.grading.templates import to_toml

    status_toml, by_toml, _ = request(server, "POST", "/api/solve", to_toml(tables))
    assert status == status_toml == 200
    assert solved["report"]["checks"] == by_toml["report"]["checks"]
    hostile = {**tables, "title": 'say "hi" \\ \x7f\nnext line\u2028'}
    status, payload, _ = post_json(server, "/api/save", {"path": "data.toml",
                                                         "exercise": hostile})
    assert status == 200, payload
    saved = (Path(server.workspace.root) / "data.toml").read_text(encoding="utf-8")
    assert tomllib.loads(saved)["title"] == hostile["title"]
    assert "\x7f" not in saved
    status, payload, _ = post_json(server, "/api/turn", {"exercise": tables, "angle": 90})
    assert status == 200 and payload["tables"]["drive"]["angle"] == pytest.approx(90)
    status, payload, _ = post_json(server, "/api/turn", {"exercise": tables, "toml": "x",
                                                         "angle": 90})
    assert status == 400 and payload["error"].startswith("exercise: give the exercise once")
    status, payload, _ = post_json(server, "/api/turn", {"exercise": {**tables, "points": {
        "A": [0, None]}}, "angle": 90})
    assert status == 400 and payload["error"].startswith("exercise.points.A[1]: null")


@settings(max_examples=150, deadline=None)
@given(st.recursive(st.none() | st.booleans() | st.integers(-2**70, 2**70)
                    | st.floats(allow_nan=False, allow_infinity=False) | st.text(max_size=8),
                    lambda inner: st.lists(inner, max_size=3)
                    | st.dictionaries(st.text(max_size=5), inner, max_size=3), max_leaves=12))
def test_any_json_exercise_is_written_as_toml_that_reads_back_equal_or_refused(value):
    """Whatever JSON a page sends as a table of the exercise, Python writes TOML that reads
    back as the same data, or refuses it in one line naming the key — never a TOML file that
    reads otherwise."""
    data = {"title": "T", "table": {"value": value}}
    try:
        text = exercise_toml(data)
    except SpecError as error:
        assert str(error).startswith("exercise.table.value") and "\n" not in str(error)
        return
    assert tomllib.loads(text) == data


def test_a_request_gives_its_exercise_once():
    assert with_toml({"angle": 3}) == {"angle": 3}
    assert with_toml({"exercise": {"title": ""}})["toml"] == 'title = "Mechanism"\n'
    with pytest.raises(SpecError, match=r"as data \(exercise\) or as text \(toml\)"):
        with_toml({"exercise": {}, "toml": "x"})
    with pytest.raises(SpecError, match=r"^exercise: must be a table"):
        exercise_toml([1, 2])
