"""The studio's server: its safety rules and its JSON API (no browser; see
``tests/test_studio_browser.py`` for the page).

Each test talks to a real server on a free port of 127.0.0.1, started in a thread for the
module and always stopped, serving a temporary folder.
"""

from __future__ import annotations

import contextlib
import http.client
import json
import os
import re
import shutil
import signal
import socket
import stat
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from planmethod.spec import read_text
from planmethod.studio import api
from planmethod.studio.server import HOST, StudioServer

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("studio")
    shutil.copy(COMPRESSOR, folder / "compressor.toml")
    (folder / "sub").mkdir()
    return folder


@pytest.fixture(scope="module")
def server(folder):
    server = StudioServer(folder, 0)
    server.start()
    yield server
    server.stop()


def request(server, method: str, path: str, body: bytes | str | None = None, *,
            token: bool = True, headers: dict | None = None) -> tuple[int, dict, dict]:
    """(status, JSON body or {}, headers) of one request; the token in its header unless
    ``token`` is False."""
    connection = http.client.HTTPConnection(HOST, server.port, timeout=60)
    sent = {"Host": f"{HOST}:{server.port}"}
    if token:
        sent["X-Planmethod-Token"] = server.token
    sent.update(headers or {})
    data = body.encode("utf-8") if isinstance(body, str) else body
    try:
        connection.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
        for name, value in sent.items():
            connection.putheader(name, value)
        if data is not None:
            connection.putheader("Content-Length", str(len(data)))
        connection.endheaders()
        if data:
            connection.send(data)
        response = connection.getresponse()
        raw = response.read()
    finally:
        connection.close()
    try:
        payload = json.loads(raw) if raw and raw[:1] in (b"{", b"[") else {}
    except json.JSONDecodeError:
        payload = {}
    return response.status, payload, dict(response.getheaders())


def post_json(server, path: str, data: dict, **options):
    return request(server, "POST", path, json.dumps(data), **options)


def one_line(payload: dict) -> str:
    message = payload["error"]
    assert isinstance(message, str) and message
    assert "\n" not in message and "Traceback" not in message
    return message


def test_an_answer_is_not_held_back_for_the_clients_acknowledgement(folder, monkeypatch):
    """Each connection the studio serves sends what it writes at once (TCP_NODELAY): an
    answer's headers and body are two writes, and without it a browser's round trip took 40 ms
    more than the server's time (benchmarks/results/studio.md)."""
    from planmethod.studio.server import StudioHandler

    seen: list[int] = []
    setup = StudioHandler.setup

    def watched(handler) -> None:
        setup(handler)
        seen.append(handler.connection.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY))

    monkeypatch.setattr(StudioHandler, "setup", watched)
    studio = StudioServer(folder, 0)
    studio.start()
    try:
        status, _, _ = request(studio, "GET", "/api/files")
    finally:
        studio.stop()
    assert status == 200 and seen and all(seen)


# -- safety ---------------------------------------------------------------------------------------
def test_it_listens_on_loopback_only(server):
    assert server.server_address[0] == "127.0.0.1"
    assert server.socket.getsockname()[0] == "127.0.0.1"
    try:   # another address of this machine, if it has one, is not answered
        outside = socket.gethostbyname(socket.gethostname())
    except OSError:
        outside = "127.0.0.1"
    if not outside.startswith("127."):
        with pytest.raises(OSError), socket.create_connection((outside, server.port), timeout=2):
            pass


@pytest.mark.parametrize(("method", "path"), [("GET", "/"), ("GET", "/api/files"),
                                              ("GET", "/api/state"), ("POST", "/api/solve")])
def test_no_token_is_403(server, method, path):
    body = read_text(COMPRESSOR) if method == "POST" else None
    status, payload, _ = request(server, method, path, body, token=False)
    assert status == 403
    assert "token" in one_line(payload)
    status, _, _ = request(server, method, path, body, token=False,
                           headers={"X-Planmethod-Token": server.token[:-1] + "x"})
    assert status == 403


def test_the_first_load_sets_a_strict_cookie(server):
    status, _, headers = request(server, "GET", f"/?token={server.token}", token=False)
    assert status == 200 and headers["Content-Type"].startswith("text/html")
    cookie = headers["Set-Cookie"]
    assert cookie.startswith(f"{server.cookie_name}={server.token}")
    assert "HttpOnly" in cookie and "SameSite=Strict" in cookie
    assert "frame-ancestors 'none'" in headers["Content-Security-Policy"]
    status, payload, _ = request(server, "GET", "/api/files", token=False,
                                 headers={"Cookie": f"{server.cookie_name}={server.token}"})
    assert status == 200 and "compressor.toml" in payload["files"]


@pytest.mark.parametrize("host", ["evil.example:{port}", "127.0.0.1:1", "localhost",
                                  "127.0.0.1.nip.io:{port}", ""])
def test_another_host_is_refused(server, host):
    status, payload, _ = request(server, "GET", "/api/files",
                                 headers={"Host": host.format(port=server.port)})
    assert status == 403 and "refused" in one_line(payload)


def test_the_loopback_names_are_served(server):
    for host in (f"127.0.0.1:{server.port}", f"localhost:{server.port}"):
        assert request(server, "GET", "/api/files", headers={"Host": host})[0] == 200


@pytest.mark.parametrize("headers", [{"Origin": "http://evil.example"},
                                     {"Origin": "null"},
                                     {"Origin": "http://127.0.0.1:1"},
                                     {"Sec-Fetch-Site": "cross-site"},
                                     {"Sec-Fetch-Site": "same-site"}])
def test_another_origin_is_refused(server, headers):
    status, payload, _ = request(server, "POST", "/api/solve", read_text(COMPRESSOR),
                                 headers=headers)
    assert status == 403 and "another site" in one_line(payload)


def test_the_same_origin_is_served(server):
    status, _, _ = request(server, "POST", "/api/solve", read_text(COMPRESSOR),
                           headers={"Origin": f"http://127.0.0.1:{server.port}",
                                    "Sec-Fetch-Site": "same-origin"})
    assert status == 200


def test_an_8_mb_body_is_413_and_the_server_goes_on(server):
    status, payload, _ = request(server, "POST", "/api/solve", b"x" * 8_000_000)
    assert status == 413 and "at most 1000000" in one_line(payload)
    assert request(server, "POST", "/api/solve", b"y" * (api.MAX_BODY + 1))[0] == 413
    assert request(server, "GET", "/api/files")[0] == 200


def test_a_body_without_its_length_is_refused(server):
    connection = http.client.HTTPConnection(HOST, server.port, timeout=30)
    connection.request("POST", "/api/solve", body=iter([b"title = 'x'\n"]),
                       headers={"X-Planmethod-Token": server.token,
                                "Transfer-Encoding": "chunked"}, encode_chunked=True)
    response = connection.getresponse()
    assert response.status == 411
    connection.close()


HOSTILE = {
    "not TOML": "title = = 1",
    "nested 5000 deep": "x = " + "[" * 5000 + "1" + "]" * 5000 + "\n",
    "nan omega": read_text(COMPRESSOR).replace("omega = 100", "omega = nan"),
    "huge coordinate": read_text(COMPRESSOR).replace("[0.06, 0]", "[1e300, 0]"),
    "huge integer": read_text(COMPRESSOR).replace("omega = 100", "omega = " + "9" * 400),
    "a template": read_text(ROOT / "exercises" / "templates" / "slider_crank.toml"),
    "W = 3": re.sub(r"\[\[slide\]\]\n(.+\n)+?\n", "", read_text(COMPRESSOR)),
    "cannot assemble": read_text(COMPRESSOR).replace("C = [0.18, 0]", "C = [0.01, 0]").replace(
        "D = [0.09, 0]", "D = [0.005, 0]"),
    "unknown key": read_text(COMPRESSOR) + "\n[frobnicate]\nx = 1\n",
    "empty": "",
}


@pytest.mark.parametrize("case", list(HOSTILE))
def test_hostile_toml_is_400_with_one_line(server, case):
    status, payload, _ = request(server, "POST", "/api/solve", HOSTILE[case])
    assert status == 400
    one_line(payload)
    assert payload["kind"] in api.KINDS.values()


def test_the_errors_say_what_went_wrong_in_the_courses_words(server):
    kinds = {case: request(server, "POST", "/api/solve", HOSTILE[case])[1]["kind"]
             for case in ("cannot assemble", "nan omega")}
    assert kinds == {"cannot assemble": "assembly", "nan omega": "input"}
    status, payload, _ = request(server, "POST", "/api/solve", HOSTILE["W = 3"])
    assert status == 400 and payload["kind"] == "structure"
    assert "W = 3n − 2p5 − p4 = 3·3 − 2·3 − 0 = 3, expected 1" in one_line(payload)


@pytest.mark.parametrize("body", [b"\xff\xfe not utf-8", b'{"path": NaN}', b"[1, 2]",
                                  b'{"path": ' + b"[" * 100 + b"]" * 100 + b"}"])
def test_hostile_json_is_400_with_one_line(server, body):
    status, payload, _ = request(server, "POST", "/api/open", body)
    assert status == 400
    one_line(payload)


@pytest.mark.parametrize("path", ["../outside.toml", "/tmp/outside.toml", "sub/../../x.toml",
                                  "sub\\..\\..\\x.toml", "..", "", "./../x.toml",
                                  "link_out/x.toml"])
def test_a_path_outside_the_folder_is_refused(server, folder, path):
    if path.startswith("link_out") and not (folder / "link_out").exists():
        (folder / "link_out").symlink_to(folder.parent, target_is_directory=True)
    before = sorted(folder.parent.rglob("*"))
    status, payload, _ = post_json(server, "/api/save", {"path": path,
                                                        "toml": read_text(COMPRESSOR)})
    assert status == 400
    one_line(payload)
    status, _, _ = post_json(server, "/api/open", {"path": path})
    assert status == 400
    status, _, _ = post_json(server, "/api/export", {"toml": read_text(COMPRESSOR),
                                                     "folder": path, "count": 1})
    assert status == 400
    assert sorted(folder.parent.rglob("*")) == before


@pytest.mark.parametrize(("method", "path", "expected"), [("GET", "/api/nothing", 404),
                                                          ("GET", "/api/solve", 405),
                                                          ("DELETE", "/api/files", 405)])
def test_unknown_addresses_and_methods(server, method, path, expected):
    status, payload, _ = request(server, method, path)
    assert status == expected
    one_line(payload)


def raw_exchange(server, data: bytes, *, timeout: float = 30) -> bytes:
    """Send ``data`` as it is on a new connection; everything the server answers until it
    closes the connection (or ``timeout`` passes with nothing more)."""
    with socket.create_connection((HOST, server.port), timeout=timeout) as connection:
        connection.sendall(data)
        answer = b""
        with contextlib.suppress(TimeoutError, ConnectionResetError):
            while chunk := connection.recv(65536):
                answer += chunk
    return answer


def head(server, method: str = "POST", path: str = "/api/solve") -> bytes:
    return (f"{method} {path} HTTP/1.1\r\nHost: {HOST}:{server.port}\r\n"
            f"X-Planmethod-Token: {server.token}\r\n").encode()


def test_two_content_lengths_are_refused(server):
    body = read_text(COMPRESSOR).encode()
    answer = raw_exchange(server, head(server) + f"Content-Length: {len(body)}\r\n"
                          f"Content-Length: 5\r\n\r\n".encode() + body)
    status_line, _, rest = answer.partition(b"\r\n")
    assert status_line == b"HTTP/1.1 400 Bad Request"
    assert b"Connection: close" in rest   # nothing more is read from that connection
    payload = json.loads(rest.split(b"\r\n\r\n", 1)[1])
    assert one_line(payload) == "2 Content-Length headers: a request has one"
    # the same length twice is two headers too; a GET's body is refused
    answer = raw_exchange(server, head(server) + b"Content-Length: 3\r\nContent-Length: 3\r\n"
                          b"\r\nabc")
    assert answer.startswith(b"HTTP/1.1 400 ")
    answer = raw_exchange(server, head(server, "GET", "/api/files")
                          + b"Content-Length: 4\r\n\r\nGET ")
    assert answer.startswith(b"HTTP/1.1 400 ") and b"has no body" in answer
    assert answer.count(b"HTTP/1.1") == 1   # its body was not read as a second request


@pytest.fixture
def strict_server(tmp_path):
    """A studio with a short deadline per request (1 s) and four places for connections."""
    server = StudioServer(tmp_path, 0, request_seconds=1.0, idle_seconds=5.0, connections=4)
    server.start()
    yield server
    server.stop()


def test_a_slow_client_is_cut_off_at_the_deadline_of_its_whole_request(strict_server):
    """A byte every 0.1 s never leaves a read waiting as long as the deadline (1 s); a
    deadline per read would serve it for ever, the deadline of the whole request cuts it off."""
    server = strict_server
    data = head(server, "GET", "/api/files") + b"X-Pad: " + b"a" * 10_000
    sent, cut = 0, False
    with socket.create_connection((HOST, server.port), timeout=30) as connection:
        started = time.monotonic()
        while time.monotonic() - started < 60:
            try:
                connection.sendall(data[sent:sent + 1])
            except OSError:
                cut = True
                break
            sent += 1
            connection.settimeout(0.1)
            try:
                if connection.recv(1) == b"":
                    cut = True
                    break
            except TimeoutError:
                pass
    assert cut and sent < len(data)
    # a client that sends its request whole is served by the same server
    assert request(server, "GET", "/api/files")[0] == 200


def test_a_slow_body_is_408(strict_server):
    server = strict_server
    with socket.create_connection((HOST, server.port), timeout=30) as connection:
        connection.sendall(head(server) + b"Content-Length: 100\r\n\r\n" + b"x" * 10)
        answer = b""
        with contextlib.suppress(ConnectionResetError):
            while chunk := connection.recv(65536):
                answer += chunk
    assert answer.startswith(b"HTTP/1.1 408 ")
    assert b"did not arrive within 1 s" in answer


def test_connections_are_bounded(strict_server):
    server = strict_server
    idle = [socket.create_connection((HOST, server.port), timeout=30) for _ in range(12)]
    try:
        time.sleep(1.5)   # the first four are being served, the others wait or were refused
        handlers = [thread for thread in threading.enumerate()
                    if "process_request_thread" in thread.name]
        assert len(handlers) <= 4
        answer = raw_exchange(server, head(server, "GET", "/api/files") + b"\r\n")
        assert answer.startswith(b"HTTP/1.1 503 ")
        payload = json.loads(answer.split(b"\r\n\r\n", 1)[1])
        assert payload["kind"] == "busy" and "4 connections" in one_line(payload)
    finally:
        for connection in idle:
            connection.close()
    deadline = time.monotonic() + 30
    while request(server, "GET", "/api/files")[0] != 200 and time.monotonic() < deadline:
        time.sleep(0.2)
    assert request(server, "GET", "/api/files")[0] == 200


def test_a_ctrl_c_while_a_connection_starts_stops_the_studio_and_frees_its_place(
        tmp_path, monkeypatch):
    """A Ctrl-C may land in the server's thread just after a connection's thread started:
    the place is given back once (the thread gives it back too) and the interrupt goes on —
    it once became 'Semaphore released too many times', was shown as an internal error and
    the studio served on."""
    import socketserver

    server = StudioServer(tmp_path, 0, connections=2)
    started = socketserver.ThreadingMixIn.process_request

    def interrupted(self, request, client_address):
        started(self, request, client_address)
        for thread in threading.enumerate():   # the connection's thread has ended
            if "process_request_thread" in thread.name:
                thread.join(30)
        raise KeyboardInterrupt

    monkeypatch.setattr(socketserver.ThreadingMixIn, "process_request", interrupted)
    try:
        client, served = socket.socketpair()
        client.close()
        with pytest.raises(KeyboardInterrupt):
            server.process_request(served, ("127.0.0.1", 0))
        assert [server._places.acquire(blocking=False) for _ in range(3)] == [True, True, False]
    finally:
        monkeypatch.undo()
        server.close()


# -- the API --------------------------------------------------------------------------------------
def test_solve_gives_the_reports_of_solve_json_with_the_plans(server):
    status, payload, _ = request(server, "POST", "/api/solve", read_text(COMPRESSOR))
    assert status == 200
    done = subprocess.run([sys.executable, "-m", "planmethod", "solve", str(COMPRESSOR),
                           "--json"], capture_output=True, text=True, cwd=ROOT, check=True)
    assert payload["report"] == json.loads(done.stdout)
    for plan in ("position", "velocity", "acceleration"):
        assert payload["svg"][plan].startswith("<svg")
    assert payload["server_ms"] > 0
    # the page shows each quantity as the course writes it: the compressor's rod BC is link 2
    assert payload["symbols"]["omega_BC"] == "ω₂" and payload["symbols"]["v_C"] == "v_C"
    assert set(payload["symbols"]) == {check["quantity"] for check in payload["report"]["checks"]}
    assert payload["drive_symbols"] == {"phi": "φ₁", "omega": "ω₁", "epsilon": "ε₁"}


def test_the_live_mechanism_is_drawn_without_the_enlarged_details():
    """Redrawn at every step of a drag, the studio's position plan leaves out the enlarged
    details of crowded points (they would jump about below it); the command line's has them."""
    from planmethod.render.svg import position_svg
    from planmethod.report import analyse
    from planmethod.spec import load_exercise

    conveyor = ROOT / "exercises" / "conveyor_sixbar.toml"
    plans = analyse(load_exercise(conveyor)).plans
    assert 'class="detail frame"' in position_svg(plans.position, plans=plans)
    live = api.solve(read_text(conveyor))["svg"]["position"]
    assert live.startswith("<svg") and 'class="detail' not in live


def test_a_drafts_labels_are_quick_and_the_answer_at_rest_is_the_same_bytes(server):
    """A drag's intermediate step (``"draft": true``) reads the same values off the same
    plans, with its labels placed quickly and no forces; the full answer after it is the
    same bytes as one never preceded by a draft."""
    conveyor = ROOT / "exercises" / "conveyor_sixbar.toml"
    tables = post_json(server, "/api/open", {"path": "compressor.toml"})[1]["tables"]
    as_json = {"Content-Type": "application/json"}
    status, alone, _ = post_json(server, "/api/solve", {"exercise": tables}, headers=as_json)
    assert status == 200
    status, draft, _ = post_json(server, "/api/solve", {"exercise": tables, "draft": True},
                                 headers=as_json)
    assert status == 200
    status, after, _ = post_json(server, "/api/solve", {"exercise": tables}, headers=as_json)
    assert after["svg"] == alone["svg"] and after["report"] == alone["report"]
    assert draft["report"]["checks"] == alone["report"]["checks"]
    assert draft["svg"]["velocity"] != alone["svg"]["velocity"]   # labels placed otherwise
    for plan in ("position", "velocity", "acceleration"):
        assert draft["svg"][plan].count("<text") == alone["svg"][plan].count("<text")
    # everything asked (the conveyor): the draft leaves out the forces the page never shows
    text = read_text(conveyor)
    full, quick = api.solve(text), api.solve(text, draft=True)
    assert full["report"]["forces"] and "forces" not in quick["report"]
    assert quick["report"]["checks"] == full["report"]["checks"]
    assert api.solve(text)["svg"] == full["svg"]


def test_the_drives_symbols_follow_the_cranks_number(server):
    """Where the course numbers the frame 1, the crank is 2: the Drive box says φ₂, ω₂, ε₂."""
    text = read_text(COMPRESSOR) + "\n[notation]\nframe = 1\n"
    status, payload, _ = request(server, "POST", "/api/solve", text)
    assert status == 200
    assert payload["drive_symbols"] == {"phi": "φ₂", "omega": "ω₂", "epsilon": "ε₂"}


def test_open_shows_a_file_in_link_frames_as_drawn(server):
    status, payload, _ = post_json(server, "/api/open", {"path": "compressor.toml"})
    assert status == 200 and payload["converted"] is True
    tables = payload["tables"]
    assert tables["links"]["BC"] == ["B", "C", "D"] and "sketch" not in tables
    assert tables["points"]["C"][1] == 0.0


def test_save_writes_the_drawing_whole_and_asks_before_replacing(server, folder):
    from planmethod.grading.templates import to_toml

    tables = post_json(server, "/api/open", {"path": "compressor.toml"})[1]["tables"]
    text = to_toml(tables)
    status, payload, _ = post_json(server, "/api/save", {"path": "sub/drawn.toml", "toml": text})
    assert status == 200 and payload == {"saved": "sub/drawn.toml"}
    assert (folder / "sub" / "drawn.toml").read_text(encoding="utf-8") == text
    status, payload, _ = post_json(server, "/api/save", {"path": "sub/drawn.toml",
                                                        "toml": text + "\n"})
    assert status == 409 and "exists" in one_line(payload)
    status, _, _ = post_json(server, "/api/save", {"path": "sub/drawn.toml", "toml": text,
                                                   "overwrite": True})
    assert status == 200
    status, payload, _ = post_json(server, "/api/save", {"path": "sub/bad.toml",
                                                        "toml": HOSTILE["nan omega"]})
    assert status == 400 and not (folder / "sub" / "bad.toml").exists()
    status, payload, _ = post_json(server, "/api/save", {"path": "sub/notes.txt", "toml": text})
    assert status == 400 and "must end in .toml" in one_line(payload)
    assert not [p for p in (folder / "sub").iterdir() if p.name.startswith(".")]


def test_turn_keeps_the_drawn_assembly(server):
    from planmethod.grading.templates import to_toml

    tables = post_json(server, "/api/open", {"path": "compressor.toml"})[1]["tables"]
    status, payload, _ = post_json(server, "/api/turn", {"toml": to_toml(tables), "angle": 120})
    assert status == 200
    turned = payload["tables"]
    assert turned["drive"]["angle"] == 120.0
    bx, by = turned["points"]["B"]
    assert (bx, by) == pytest.approx((0.06 * -0.5, 0.06 * 3 ** 0.5 / 2), abs=1e-15)
    assert turned["points"]["C"][0] > 0    # still on the drawn side of A


def wait_for(server, job: dict, *, until=lambda job: job["state"] != "running",
             seconds: float = 600) -> dict:
    """The job (as ``GET /api/job`` gives it) once ``until`` holds (by default: it ended)."""
    end = time.monotonic() + seconds
    while True:
        status, payload, _ = request(server, "GET", f"/api/job?id={job['id']}")
        assert status == 200, payload
        if until(payload) or time.monotonic() > end:
            return payload
        time.sleep(0.2)


def start_job(server, path: str, data: dict) -> dict:
    status, payload, _ = post_json(server, path, data)
    assert status == 202, payload
    assert payload["job"]["state"] == "running"
    return payload["job"]


RANGES = {"lengths": {"BC": [0.17, 0.19]}, "angle": [40, 50, 5]}


def test_variants_preview_task_sheets_as_a_job(server):
    ranges = {"lengths": {"AB": [0.05, 0.07], "BC": [0.16, 0.2]}, "angle": [30, 60, 5]}
    job = start_job(server, "/api/variants", {"toml": read_text(COMPRESSOR), "ranges": ranges,
                                             "count": 3, "seed": 4})
    assert job["kind"] == "variants" and job["total"] == 3
    ended = wait_for(server, job)
    assert ended["state"] == "done" and ended["done"] == 3, ended
    payload = ended["result"]
    assert "l_AB = { range = [0.05, 0.07], step = 0.001 }" in payload["template"]
    assert [v["student"] for v in payload["variants"]] == ["01", "02", "03"]
    for variant in payload["variants"]:
        assert 0.05 <= variant["values"]["l_AB"] <= 0.07
        assert 30 <= variant["values"]["phi"] <= 60
        assert variant["sheet"].startswith("<svg")
        assert variant["note"] == ""
    # a mistake in the request is its 400 at once, not a failed job
    status, payload, _ = post_json(server, "/api/variants", {
        "toml": read_text(COMPRESSOR), "ranges": {"lengths": {"AB": [0.07, 0.05]}}})
    assert status == 400 and "above" in one_line(payload)
    listed = request(server, "GET", "/api/jobs")[1]["jobs"]
    assert job["id"] in [entry["id"] for entry in listed]
    assert all("result" not in entry for entry in listed)   # the list stays small


def test_export_writes_the_lms_packages_as_a_job(server, folder):
    job = start_job(server, "/api/export", {"toml": read_text(COMPRESSOR), "folder": "run",
                                            "count": 2, "ranges": RANGES})
    assert job["kind"] == "export" and job["folder"] == "run"
    ended = wait_for(server, job)
    assert ended["state"] == "done", ended
    assert ended["result"] == {"folder": "run", "written": ended["result"]["written"],
                               "variants": 2, "rejected": 0}
    run = folder / "run"
    for name in ("template.toml", "variants/keys.json", "variants/01/task.svg",
                 "moodle/quiz.xml", "prairielearn/planmethod/info.json",
                 "gradescope/run_autograder"):
        assert (run / name).is_file(), name
    assert os.access(run / "gradescope" / "run_autograder", os.X_OK)
    # one run's files, nothing else: every file written is one the result counts
    assert len([path for path in run.rglob("*") if path.is_file()]) == ended["result"]["written"]
    assert not [path for path in folder.iterdir() if path.name.startswith(".run.")]
    status, payload, _ = post_json(server, "/api/export", {"toml": read_text(COMPRESSOR),
                                                          "folder": "run", "count": 1})
    assert status == 409 and "exists" in one_line(payload)
    # the exported run carries the manifest `variants --force` checks: it may replace it
    done = subprocess.run([sys.executable, "-m", "planmethod", "variants",
                           str(run / "template.toml"), "--count", "1", "--out",
                           str(run / "variants"), "--no-sheets", "--force"],
                          capture_output=True, text=True, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    assert not (run / "variants" / "01").exists() and (run / "variants" / "001").is_dir()
    # …and so do its LMS packages: `planmethod export` replaces each whole, as its own run
    keys = run / "variants" / "keys.json"
    for export_format, out, manifest in (
            ("prairielearn", run / "prairielearn", run / "prairielearn" / "planmethod"),
            ("gradescope", run / "gradescope", run / "gradescope")):
        assert (manifest / "manifest.json").is_file(), export_format
        done = subprocess.run([sys.executable, "-m", "planmethod", "export", str(keys),
                               "--format", export_format, "--out", str(out)],
                              capture_output=True, text=True, cwd=ROOT)
        assert done.returncode == 0, done.stderr
    # the studio's two students' task sheets went with their run: one student's now
    tasks = list((run / "prairielearn" / "planmethod").rglob("task_*.svg"))
    assert len(tasks) == len(json.loads(keys.read_text(encoding="utf-8"))["keys"]) == 1, tasks


@pytest.mark.parametrize(("path", "count", "limit"), [("/api/export", 1001, "1…1000"),
                                                      ("/api/export", 2000, "1…1000"),
                                                      ("/api/export", 0, "1…1000"),
                                                      ("/api/variants", 41, "1…40")])
def test_counts_are_limited_as_on_the_command_line(server, folder, path, count, limit):
    from planmethod.application.variants import MAX_VARIANTS

    assert f"1…{MAX_VARIANTS}" == "1…1000"   # the command line's limit, shared
    status, payload, _ = post_json(server, path, {"toml": read_text(COMPRESSOR),
                                                  "folder": "too-many", "count": count}
                                   if path == "/api/export" else
                                   {"toml": read_text(COMPRESSOR), "count": count})
    assert status == 400
    assert one_line(payload).startswith(f"count: must be a whole number in {limit}, got {count}")
    assert not (folder / "too-many").exists()


def hidden_leftovers(folder: Path) -> list[str]:
    return sorted(path.name for path in folder.iterdir() if ".export-" in path.name)


def test_a_long_export_leaves_solves_and_listings_answering_and_cancels_cleanly(server,
                                                                               folder):
    """A 200-variant export runs as a job; meanwhile a solve and a file listing answer before
    it ends (how soon is the benchmark's: benchmarks/studio.py); cancelled, it leaves no
    folder, and its process has ended."""
    job = start_job(server, "/api/export", {"toml": read_text(COMPRESSOR), "folder": "big",
                                            "count": 200, "ranges": RANGES})
    running = wait_for(server, job, until=lambda job: job["done"] >= 1 or
                       job["state"] != "running")
    assert running["state"] == "running" and running["phase"] == "variants", running
    status, solved, _ = request(server, "POST", "/api/solve", read_text(COMPRESSOR))
    assert status == 200 and solved["svg"]["velocity"].startswith("<svg")
    status, listed, _ = request(server, "GET", "/api/files")
    assert status == 200 and "compressor.toml" in listed["files"]
    from planmethod.grading.templates import to_toml

    tables = post_json(server, "/api/open", {"path": "compressor.toml"})[1]["tables"]
    status, _, _ = post_json(server, "/api/turn", {"toml": to_toml(tables), "angle": 90})
    assert status == 200
    still = request(server, "GET", f"/api/job?id={job['id']}")[1]
    assert still["state"] == "running" and still["done"] < 200, still   # before it ended
    status, cancelled, _ = post_json(server, "/api/cancel", {"id": job["id"]})
    assert status == 200 and cancelled["state"] == "cancelled"
    assert not (folder / "big").exists()
    assert hidden_leftovers(folder) == []
    assert server.jobs.get(job["id"]).process.poll() is not None
    # cancelling again, or a job that ended, leaves it as it ended
    assert post_json(server, "/api/cancel", {"id": job["id"]})[1]["state"] == "cancelled"
    status, payload, _ = post_json(server, "/api/cancel", {"id": "no-such-job"})
    assert status == 404 and "no job" in one_line(payload)


def test_a_third_job_is_refused_and_one_folder_gets_one_export(server, folder):
    first = start_job(server, "/api/export", {"toml": read_text(COMPRESSOR), "folder": "one",
                                              "count": 200})
    try:
        status, payload, _ = post_json(server, "/api/export", {
            "toml": read_text(COMPRESSOR), "folder": "one", "count": 1})
        assert status == 409 and "running" in one_line(payload)
        second = start_job(server, "/api/variants", {"toml": read_text(COMPRESSOR),
                                                     "count": 40})
        status, payload, _ = post_json(server, "/api/export", {
            "toml": read_text(COMPRESSOR), "folder": "three", "count": 1})
        assert status == 429 and payload["kind"] == "busy"
        assert "at most 2 at once" in one_line(payload)
        assert not (folder / "three").exists()
        post_json(server, "/api/cancel", {"id": second["id"]})
    finally:
        post_json(server, "/api/cancel", {"id": first["id"]})
    assert not (folder / "one").exists() and hidden_leftovers(folder) == []


# -- typed fields ---------------------------------------------------------------------------------
TYPED = {
    "overwrite as text": ("/api/save", {"path": "compressor.toml", "toml": "x",
                                        "overwrite": "false"}, "overwrite: must be true or false"),
    "template as text": ("/api/save", {"path": "t.toml", "toml": "x", "template": "false"},
                         "template: must be true or false"),
    "misspelt field": ("/api/save", {"path": "t.toml", "toml": "x", "overwite": True},
                       "overwite: unknown field"),
    "path as a number": ("/api/open", {"path": 5}, "path: must be text, got the number 5"),
    "toml missing": ("/api/turn", {"toml": None, "angle": 3}, "toml: is missing"),
    "angle as text": ("/api/turn", {"toml": "x", "angle": "120"},
                      "angle: must be a finite number, got the text '120'"),
    "count as text": ("/api/variants", {"toml": "x", "count": "3"}, "count: must be a whole"),
    "seed as a fraction": ("/api/variants", {"toml": "x", "seed": 1.5}, "seed: must be a whole"),
    "ranges as a list": ("/api/variants", {"toml": "x", "ranges": []},
                         "ranges: must be a table"),
    "a length as text": ("/api/variants", {"toml": "x", "ranges": {"lengths": {"BC": ["a", 1]}}},
                         "ranges.lengths.BC[0]: must be a finite number"),
    "a range misspelt": ("/api/variants", {"toml": "x", "ranges": {"angel": [1, 2, 1]}},
                         "ranges.angel: unknown field"),
    "formats as text": ("/api/export", {"toml": "x", "folder": "f", "formats": "moodle"},
                        "formats: must be a list"),
    "a format as a number": ("/api/export", {"toml": "x", "folder": "f", "formats": [1]},
                             "formats[0]: must be text"),
    "folder as a flag": ("/api/export", {"toml": "x", "folder": True},
                         "folder: must be text, got true"),
    "job id as a number": ("/api/cancel", {"id": 3}, "id: must be text"),
}


@pytest.mark.parametrize("case", list(TYPED))
def test_a_field_of_the_wrong_type_is_400_naming_it(server, folder, case):
    path, body, expected = TYPED[case]
    before = {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()}
    status, payload, _ = post_json(server, path, body)
    assert status == 400 and payload["kind"] == "input"
    assert one_line(payload).startswith(expected), payload
    # nothing written: the instructor's file is as it was, no template appeared
    assert {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()} == before


def test_a_job_asked_for_without_its_id_is_400(server):
    status, payload, _ = request(server, "GET", "/api/job")
    assert status == 400 and one_line(payload) == "id: is missing"


@pytest.mark.parametrize("asked", [True, False], ids=["some-asked", "nothing-asked"])
def test_a_template_saved_from_the_studio_runs_on_the_command_line(server, folder, asked):
    """Nothing asked asks everything (docs/studio.md): the template says so in its [ask]."""
    text = read_text(COMPRESSOR)
    if not asked:
        start = text.index("[ask]")
        text = text[:start] + text[text.index("\n[", start):]
    status, _, _ = post_json(server, "/api/save", {
        "template": True, "path": f"template-{asked}.toml", "toml": text,
        "ranges": {"lengths": {"AB": [0.055, 0.065]}, "angle": [30, 60, 10]}})
    assert status == 200
    done = subprocess.run([sys.executable, "-m", "planmethod", "variants",
                           str(folder / f"template-{asked}.toml"), "--count", "2", "--out",
                           str(folder / f"cli-run-{asked}"), "--no-sheets"],
                          capture_output=True, text=True, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    assert (folder / f"cli-run-{asked}" / "keys.json").is_file()


# -- the file system's odd corners (issue 35) ------------------------------------------------------
@pytest.fixture
def odd(tmp_path):
    """A studio serving a folder with the file system's odd corners beside two good exercise
    files: a link that loops, one named as an exercise, a link to nothing, a FIFO named as an
    exercise, a folder linked back to its parent."""
    folder = tmp_path / "odd"
    (folder / "sub").mkdir(parents=True)
    shutil.copy(COMPRESSOR, folder / "good.toml")
    shutil.copy(COMPRESSOR, folder / "sub" / "inner.toml")
    (folder / "loop").symlink_to("loop")
    (folder / "loop.toml").symlink_to("loop.toml")
    (folder / "nothing.toml").symlink_to("gone.toml")
    os.mkfifo(folder / "pipe.toml")
    (folder / "sub" / "up").symlink_to("..", target_is_directory=True)
    server = StudioServer(folder, 0)
    server.start()
    yield server
    server.stop()


def _kinds(folder: Path) -> dict[str, str]:
    """What each entry of ``folder`` is (links not followed), and a regular file's bytes."""
    def kind(path: Path) -> str:
        mode = os.lstat(path).st_mode
        if stat.S_ISREG(mode):
            return path.read_text(encoding="utf-8")
        return {stat.S_IFLNK: "link", stat.S_IFIFO: "FIFO", stat.S_IFCHR: "device",
                stat.S_IFDIR: "folder"}[stat.S_IFMT(mode)]

    return {str(path.relative_to(folder)): kind(path) for path in sorted(folder.rglob("*"))
            if "up" not in path.relative_to(folder).parts[1:]}


def test_the_listing_goes_around_what_it_cannot_follow(odd):
    """/api/files and /api/state answered 500 for a link that loops: they list the other
    files, and the listing says what it passed over and why."""
    for path in ("/api/files", "/api/state"):
        status, payload, _ = request(odd, "GET", path)
        assert status == 200 and payload["files"] == ["good.toml", "sub/inner.toml"]
    skipped = {entry["path"]: entry["why"] for entry in odd.workspace.listing()["skipped"]}
    assert skipped == {"loop": "a symbolic link that loops",
                       "loop.toml": "a symbolic link that loops",
                       "nothing.toml": "a symbolic link to nothing",
                       "pipe.toml": "not a regular file",
                       "sub/up": "a folder listed already (a link back to it)"}


@pytest.mark.parametrize("path", ["loop.toml", "loop/x.toml"])
def test_a_path_through_a_loop_is_one_line(odd, path):
    before = _kinds(odd.workspace.root)
    for call, body in (("/api/open", {"path": path}),
                       ("/api/save", {"path": path, "toml": read_text(COMPRESSOR),
                                      "overwrite": True})):
        status, payload, _ = post_json(odd, call, body)
        assert status == 400, (call, payload)
        assert one_line(payload) == f"path: {path!r} cannot be followed: a symbolic link that loops"
    assert _kinds(odd.workspace.root) == before


def _fifo_read_end(path: Path) -> int:
    """A reader on the FIFO (without it, writing refuses at once anyway)."""
    return os.open(path, os.O_RDONLY | os.O_NONBLOCK)


@pytest.mark.parametrize("special", ["FIFO", "device"])
def test_an_exercise_is_never_saved_into_a_fifo_or_a_device(odd, special):
    """Saved over a FIFO that a program reads (or a device) it answered 200 "saved" and
    saved nothing: refused in one line; the FIFO is still a FIFO and got nothing, the device
    is still the device, and the listing still lists the other files."""
    folder = odd.workspace.root
    target = folder / ("pipe.toml" if special == "FIFO" else "null.toml")
    if special == "device":
        try:
            os.mknod(target, stat.S_IFCHR | 0o666, os.makedev(1, 3))   # a twin of /dev/null
        except PermissionError:
            pytest.skip("making a device needs CAP_MKNOD (root)")
    reader = _fifo_read_end(target) if special == "FIFO" else None
    try:
        for body in ({"path": target.name, "toml": read_text(COMPRESSOR), "overwrite": True},
                     {"path": target.name, "toml": read_text(COMPRESSOR), "overwrite": True,
                      "template": True, "ranges": {"angle": [30, 60, 10]}}):
            status, payload, _ = post_json(odd, "/api/save", body)
            assert status == 400
            kind = "a FIFO" if special == "FIFO" else "a character device"
            assert one_line(payload).startswith(f"{target.name}: is {kind}, not a regular file")
        status, payload, _ = post_json(odd, "/api/open", {"path": target.name})
        assert status == 400 and "not a regular file" in one_line(payload)
        if reader is not None:   # nothing was written into it
            assert os.read(reader, 1 << 16) == b""
    finally:
        if reader is not None:
            os.close(reader)
    mode = os.lstat(target).st_mode
    assert stat.S_ISFIFO(mode) if special == "FIFO" else (
        stat.S_ISCHR(mode) and os.lstat(target).st_rdev == os.makedev(1, 3))
    assert request(odd, "GET", "/api/files")[1]["files"] == ["good.toml", "sub/inner.toml"]


def test_any_file_system_condition_is_a_4xx_of_one_line(odd, monkeypatch):
    """Permission denied (made here by the test: the tests run as root), a name too long, a
    file where a folder is expected, a folder where a file is: 400 with one line naming the
    path as the page gave it, never 500, never the folder's absolute path."""
    folder = odd.workspace.root
    (folder / "box.toml").mkdir()
    real_scandir, real_open = os.scandir, os.open

    def scandir(path="."):
        if Path(path).name == "sub":
            raise PermissionError(13, "Permission denied", str(path))
        return real_scandir(path)

    def opening(path, flags, *arguments, **keywords):
        if Path(path).name == "good.toml" and not flags & (os.O_WRONLY | os.O_RDWR):
            raise PermissionError(13, "Permission denied", str(path))
        return real_open(path, flags, *arguments, **keywords)

    monkeypatch.setattr(os, "scandir", scandir)
    monkeypatch.setattr(os, "open", opening)
    status, payload, _ = request(odd, "GET", "/api/files")
    assert status == 200 and payload["files"] == ["good.toml"]
    assert {"path": "sub", "why": "the folder cannot be read: permission denied"} in \
        odd.workspace.listing()["skipped"]
    cases = {
        ("/api/open", "good.toml"): "good.toml: cannot read the file (Permission denied)",
        ("/api/open", "box.toml"): "box.toml: is a folder, not a file",
        ("/api/save", "box.toml"): "box.toml: is a folder, not a file",
        ("/api/save", "good.toml/x.toml"): "good.toml/x.toml: good.toml is a file, not a folder",
        ("/api/open", "good.toml/x.toml"): "good.toml/x.toml: no such file",
        ("/api/save", "/".join(["d" * 250] * 20) + ".toml"): "name too long",
    }
    for (call, path), expected in cases.items():
        body = {"path": path} if call == "/api/open" else {
            "path": path, "toml": read_text(COMPRESSOR), "overwrite": True}
        status, payload, _ = post_json(odd, call, body)
        assert status == 400, (call, path, payload)
        message = one_line(payload)
        assert message.startswith(expected) or expected in message, (call, path, message)
        assert str(folder) not in message
    monkeypatch.undo()
    assert (folder / "good.toml").read_text(encoding="utf-8") == read_text(COMPRESSOR)


# -- the command ----------------------------------------------------------------------------------
def test_the_command_prints_its_address_and_stops_on_ctrl_c(tmp_path):
    """The address with a token of ≥ 40 characters; Ctrl-C stops it with status 0 (if it does
    not within 60 s, the test fails with every thread's stack: :meth:`Command.stopped`)."""
    command = Command(tmp_path)
    try:
        assert len(command.token) >= 40
        connection = http.client.HTTPConnection(HOST, command.port, timeout=30)
        connection.request("GET", "/api/state", headers={"X-Planmethod-Token": command.token})
        response = connection.getresponse()
        assert response.status == 200 and json.loads(response.read())["initial"] is None
        connection.close()
        command.process.send_signal(signal.SIGINT)
        assert command.stopped() == 0
        assert "stopped" in command.process.stderr.read()
    finally:
        command.stop()


class Command:
    """``planmethod studio`` started in a process of its own on a free port (with SIGINT
    ignored if asked, as a shell's background job has it), serving ``folder``."""

    def __init__(self, folder: Path, *, sigint_ignored: bool = False) -> None:
        def ignore_sigint() -> None:
            signal.signal(signal.SIGINT, signal.SIG_IGN)

        self.process = subprocess.Popen(
            [sys.executable, "-X", "faulthandler", "-m", "planmethod", "studio", "--no-browser",
             "--port", "0"],
            cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
            env={**os.environ, "PYTHONPATH": str(ROOT)},
            preexec_fn=ignore_sigint if sigint_ignored else None)
        lines = [self.process.stdout.readline() for _ in range(2)]
        address = lines[1].strip()
        assert address.startswith("http://127.0.0.1:") and "?token=" in address, lines
        self.port = int(address.split(":")[2].split("/")[0])
        self.token = address.split("token=")[1]

    def children(self) -> list[int]:
        """The process ids of the studio's jobs (Linux)."""
        found = []
        for task in Path(f"/proc/{self.process.pid}/task").iterdir():
            with contextlib.suppress(OSError):
                found += [int(pid) for pid in (task / "children").read_text().split()]
        return found

    def stopped(self, seconds: float = 60) -> int:
        """The exit status once the studio has ended; if it has not within ``seconds``, the
        test fails with every thread's stack (faulthandler's dump on SIGABRT)."""
        try:
            return self.process.wait(timeout=seconds)
        except subprocess.TimeoutExpired:
            self.process.send_signal(signal.SIGABRT)
            self.process.wait()
            pytest.fail("the studio did not stop:\n" + self.process.stderr.read()[-6000:])

    def stop(self) -> None:
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


@pytest.fixture
def command(tmp_path):
    started: list[Command] = []

    def start(**options) -> Command:
        started.append(Command(tmp_path, **options))
        return started[-1]

    shutil.copy(COMPRESSOR, tmp_path / "compressor.toml")
    yield start
    for each in started:
        each.stop()


def ended(pid: int, seconds: float = 60) -> bool:
    """Whether process ``pid`` has ended (gone, or a zombie nobody reaped) within
    ``seconds``."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            return True
        if state in ("Z", "X"):
            return True
        time.sleep(0.1)
    return False


def start_export_job(studio: Command, folder: str = "big") -> dict:
    """Start a 200-variant export on ``studio`` and wait until it computes."""
    job = start_job(studio, "/api/export", {"toml": read_text(COMPRESSOR), "folder": folder,
                                            "count": 200})
    running = wait_for(studio, job, until=lambda job: job["done"] >= 1
                       or job["state"] != "running")
    assert running["state"] == "running", running
    return running


needs_proc = pytest.mark.skipif(not Path("/proc/self/task").is_dir(),
                                reason="lists a process's children through /proc (Linux)")


@needs_proc
def test_ctrl_c_stops_the_command_and_its_jobs_even_with_sigint_ignored(command, tmp_path):
    studio = command(sigint_ignored=True)
    start_export_job(studio)
    jobs = studio.children()   # the job's, and one started ahead for the next job
    assert 1 <= len(jobs) <= 2
    studio.process.send_signal(signal.SIGINT)
    assert studio.stopped() == 0
    assert "stopped" in studio.process.stderr.read()
    assert all(ended(pid) for pid in jobs)
    assert not (tmp_path / "big").exists() and hidden_leftovers(tmp_path) == []


@needs_proc
def test_a_job_ends_with_its_studio_even_killed(command, tmp_path):
    studio = command()
    start_export_job(studio)
    jobs = studio.children()
    assert 1 <= len(jobs) <= 2
    studio.process.kill()   # no chance to stop its jobs: they see it gone
    studio.process.wait()
    assert all(ended(pid) for pid in jobs)
    assert not (tmp_path / "big").exists() and hidden_leftovers(tmp_path) == []


def test_dropped_connections_leave_one_line_each_and_no_traceback(command):
    """200 clients hang up mid-request (a reset in the middle of a body, a close in the middle
    of the headers): the studio goes on serving, and its terminal shows no traceback."""
    studio = command()
    start = (f"POST /api/solve HTTP/1.1\r\nHost: {HOST}:{studio.port}\r\n"
             f"X-Planmethod-Token: {studio.token}\r\n").encode()
    for number in range(200):
        connection = socket.create_connection((HOST, studio.port), timeout=30)
        if number % 2:
            connection.sendall(start + b"Content-Length: 1000\r\n\r\n" + b"x" * 10)
            connection.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER,
                                  struct.pack("ii", 1, 0))   # close with a reset
        else:
            connection.sendall(start[:30])
        connection.close()
    assert request(studio, "GET", "/api/files")[0] == 200
    studio.process.send_signal(signal.SIGINT)
    assert studio.stopped() == 0
    terminal = studio.process.stderr.read()
    assert "Traceback" not in terminal and "File \"" not in terminal
    lines = [line for line in terminal.splitlines() if line]
    assert all(line.startswith("planmethod studio: ") for line in lines), lines[:5]
    assert len(lines) <= 201   # at most one line a connection, and "stopped"


def test_the_command_refuses_a_file_outside_its_folder(tmp_path):
    done = subprocess.run([sys.executable, "-m", "planmethod", "studio", str(COMPRESSOR),
                           "--no-browser"], cwd=tmp_path, capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=60)
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and "only under the folder" in done.stderr


def test_a_folder_given_as_the_file_says_how_to_serve_it(tmp_path):
    (tmp_path / "course").mkdir()
    done = subprocess.run([sys.executable, "-m", "planmethod", "studio", "course",
                           "--no-browser"], cwd=tmp_path, capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=60)
    assert done.returncode == 2 and done.stderr.count("\n") == 1
    assert "is a folder" in done.stderr and "cd into it" in done.stderr


def test_a_busy_port_given_is_one_line(tmp_path):
    with socket.socket() as busy:
        busy.bind((HOST, 0))
        busy.listen()
        port = busy.getsockname()[1]
        start = time.perf_counter()
        done = subprocess.run([sys.executable, "-m", "planmethod", "studio", "--no-browser",
                               "--port", str(port)], cwd=tmp_path, capture_output=True,
                              text=True, env={**os.environ, "PYTHONPATH": str(ROOT)},
                              timeout=60)
    assert done.returncode == 2 and time.perf_counter() - start < 60
    assert done.stderr.startswith("planmethod: error: --port: cannot listen on")


# -- the language of the answers ------------------------------------------------------------------
@pytest.fixture
def pseudo(tmp_path, monkeypatch):
    """The pseudo language ``qps`` (every message marked ⟦…⟧) available in this process."""
    pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel")
    from planmethod.testing.pseudo import PSEUDO, pseudo_catalogue
    from planmethod.words import language

    pseudo_catalogue(tmp_path / "pseudo")
    monkeypatch.setenv(language.LOCALE_ENVIRONMENT, str(tmp_path / "pseudo"))
    monkeypatch.delenv(language.ENVIRONMENT, raising=False)
    language.catalogue.cache_clear()
    yield PSEUDO
    language.catalogue.cache_clear()


def test_answers_speak_the_exercises_language_or_the_studios(folder, pseudo):
    """Without --lang, an answer about an exercise speaks its [course] language; with --lang,
    every answer speaks that; a language that cannot be spoken is refused in one line."""
    course = read_text(COMPRESSOR) + f'\n[course]\nlanguage = "{pseudo}"\n'
    studio = StudioServer(folder, 0)
    studio.start()
    try:
        status, payload, _ = post_json(studio, "/api/turn", {"toml": course, "angle": 1e9})
        assert status == 400 and one_line(payload).startswith("angle: ⟦must be at most")
        status, payload, _ = post_json(studio, "/api/turn", {"toml": read_text(COMPRESSOR),
                                                             "angle": 1e9})
        assert status == 400 and "⟦" not in one_line(payload)
        assert request(studio, "GET", "/api/state")[1]["language"] == "en"
        status, payload, _ = post_json(studio, "/api/turn", {
            "toml": course.replace(f'"{pseudo}"', '"xx"'), "angle": 10})
        assert status == 400 and one_line(payload).startswith(
            "course.language: no catalogue for the language xx")
    finally:
        studio.stop()
    studio = StudioServer(folder, 0, language=pseudo)
    studio.start()
    try:
        status, payload, _ = request(studio, "GET", "/api/files", token=False)
        assert status == 403 and one_line(payload).startswith("⟦refused: no valid token")
        status, payload, _ = post_json(studio, "/api/turn", {
            "toml": course.replace(f'"{pseudo}"', '"en"'), "angle": 1e9})
        assert status == 400 and "⟦must be at most" in one_line(payload)
        assert request(studio, "GET", "/api/state")[1]["language"] == pseudo
    finally:
        studio.stop()
