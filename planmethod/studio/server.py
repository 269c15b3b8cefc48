"""The studio's HTTP server: the standard library's ``ThreadingHTTPServer``, bounded, and a
thin router over typed requests.

Why the standard library: the studio serves one page and a dozen JSON calls to one person on
one machine; ``http.server`` does that with no new dependency, and what a class does to it —
a long export while someone drags a point, connections dropped or left hanging — takes a few
short overrides here (a cap on handler threads, one deadline per request, jobs in processes:
:mod:`planmethod.studio.jobs`), which keep the safety rules below easy to read and to test.
(An ASGI stack — Starlette and uvicorn — would add two packages and still need the jobs.)

Safety, for a server that can write files:

* it listens on 127.0.0.1 only;
* every request needs the token made at start (``secrets.token_urlsafe``): in the query of the
  first page load (``/?token=…``), then in a cookie (HttpOnly, SameSite=Strict) or the header
  ``X-Planmethod-Token``; without it: 403;
* a ``Host`` other than ``127.0.0.1:PORT`` or ``localhost:PORT`` (DNS rebinding) and an
  ``Origin`` or ``Sec-Fetch-Site`` of another site (cross-site requests) are refused: 403;
* at most :data:`MAX_CONNECTIONS` connections are served at once, each by a thread; one more
  waits :data:`BUSY_WAIT` seconds for a place, then is answered 503;
* a request must arrive whole — request line, headers and body — within
  :data:`REQUEST_SECONDS` of its first byte (a client sending a byte a second is cut off), and
  a connection waits at most :data:`IDLE_SECONDS` for its next request;
* a body is at most :data:`~planmethod.studio.api.MAX_BODY` bytes (413 above, before reading
  it), read with one declared length only (411 without, 400 with two ``Content-Length``
  headers), and parsed with the command line's limits (TOML and JSON nesting, numbers' ranges:
  :mod:`planmethod.spec`); every field of a JSON body has a type (:mod:`~planmethod.studio.schema`);
* files are read and written only under the folder the studio was started in, with the
  command line's path rules and atomic writes (:class:`~planmethod.studio.api.Workspace`);
* long work (variants, export) runs as a job in a process of its own
  (:mod:`~planmethod.studio.jobs`), never in a request.

A refused or failed request answers ``{"error": "one line", "kind": …}`` with a 4xx status,
never a traceback; a client that hangs up mid-request is one line in the terminal.

Examples
--------
>>> import tempfile, urllib.request, json
>>> server = StudioServer(tempfile.mkdtemp(), port=0)
>>> thread = server.start()
>>> request = urllib.request.Request(server.url("/api/files"),
...                                  headers={"X-Planmethod-Token": server.token})
>>> json.load(urllib.request.urlopen(request))
{'files': [], 'skipped': []}
>>> server.stop()
"""

from __future__ import annotations

import contextlib
import hmac
import io
import json
import secrets
import socket
import socketserver
import sys
import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from http import HTTPStatus
from http.cookies import CookieError, SimpleCookie
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any
from urllib.parse import parse_qs, urlsplit

from ..errors import PlanmethodError, SpecError
from ..words import Message, current, message, render, speaking
from . import api, exercise_data, schema
from .jobs import BusyError, Jobs, NoSuchJobError
from .page import page_file, studio_page

__all__ = ["HOST", "StudioServer"]

#: the only address the studio listens on
HOST = "127.0.0.1"
#: the header and cookie that carry the token
TOKEN_HEADER = "X-Planmethod-Token"
#: after refusing a body that is too large, read and drop at most this much of it (bytes) for
#: at most this long (s), so that the client reads the answer instead of a reset connection
DRAIN_BYTES, DRAIN_SECONDS = 16_000_000, 2.0
#: connections served at once (a browser keeps up to six open per page), and how long one more
#: waits for a place before its 503 (s)
MAX_CONNECTIONS, BUSY_WAIT = 32, 0.5
#: a request arrives whole within this many seconds of its first byte; a connection waits this
#: long for its next request; an answer is sent within this long
REQUEST_SECONDS, IDLE_SECONDS, SEND_SECONDS = 10.0, 15.0, 30.0
#: how long a stopping studio waits for the requests in flight to end (s); a stalled client
#: never holds the stop (their threads are daemons, and end with the process)
CLOSE_SECONDS = 3.0


class RefusedError(PlanmethodError, PermissionError):
    """A request the studio will not serve: its HTTP status and one line."""

    def __init__(self, status: int, text: Message | str, kind: str = "refused") -> None:
        super().__init__(text)
        self.status, self.kind = status, kind


def _page(language: str) -> bytes:
    return studio_page(language)


def _note(text: Message | str) -> None:
    """One line in the studio's terminal."""
    with contextlib.suppress(OSError, ValueError):
        print(render(message("planmethod studio: {note}", note=text)).replace("\n", " "),
              file=sys.stderr, flush=True)


class StudioServer(ThreadingHTTPServer):
    """The studio: serves the page and the API for the files under ``folder``.

    ``port`` 0 takes a free port. ``initial`` is a file (relative to ``folder``) the page
    opens first. ``connections``, ``request_seconds`` and ``idle_seconds`` bound what clients
    may hold (:data:`MAX_CONNECTIONS`, :data:`REQUEST_SECONDS`, :data:`IDLE_SECONDS`).
    """

    daemon_threads = True
    allow_reuse_address = False
    request_queue_size = 64

    def __init__(self, folder: str | Path, port: int = 0, *, initial: str | None = None,
                 token: str | None = None, connections: int = MAX_CONNECTIONS,
                 request_seconds: float = REQUEST_SECONDS,
                 idle_seconds: float = IDLE_SECONDS, language: str | None = None) -> None:
        from ..application.language import run_language

        #: the language chosen at start (``--lang``), else None: each exercise's own
        self.language = language
        #: what the studio speaks where no exercise says otherwise (checked at start)
        self.base_language = run_language(language)
        self.workspace = api.Workspace(folder)
        self.token = token or secrets.token_urlsafe(32)
        self.initial = initial
        self.page = _page(self.base_language)   # in the language it speaks
        #: one computation at a time (solve, turn, open, save, a job's checks)
        self.lock = threading.Lock()
        self.jobs = Jobs()
        self.request_seconds, self.idle_seconds = request_seconds, idle_seconds
        self._places = threading.BoundedSemaphore(connections)
        #: the connections that hold a place (by id), so that each gives it back once
        self._holding: set[int] = set()
        self._holding_lock = threading.Lock()
        self.connections = connections
        self._thread: threading.Thread | None = None
        super().__init__((HOST, port), StudioHandler)

    def spoken(self, text: str | None) -> str:
        """The language of an answer about the exercise ``text`` (its ``[course]
        language``, unless the studio was started with ``--lang``)."""
        from ..application.language import run_language

        if text is None or self.language is not None:
            return self.base_language
        return run_language(None, text=text)

    @property
    def port(self) -> int:
        return int(self.server_address[1])

    @property
    def cookie_name(self) -> str:
        """Cookies are kept per host, not per port: each studio has its own."""
        return f"planmethod_studio_{self.port}"

    @property
    def hosts(self) -> tuple[str, ...]:
        return (f"{HOST}:{self.port}", f"localhost:{self.port}")

    @property
    def origins(self) -> tuple[str, ...]:
        return tuple(f"http://{host}" for host in self.hosts)

    def url(self, path: str = "/", *, token: bool = False) -> str:
        """The address of ``path`` on this server (with the token in its query if asked)."""
        return f"http://{HOST}:{self.port}{path}" + (f"?token={self.token}" if token else "")

    # -- bounded connections ------------------------------------------------------------------
    def process_request(self, request: Any, client_address: Any) -> None:
        """Serve a connection in a thread of its own if one of :attr:`connections` places is
        free within :data:`BUSY_WAIT` seconds; otherwise answer 503 and close it."""
        if not self._places.acquire(timeout=BUSY_WAIT):
            _refuse_busy(request, self.connections, self.base_language)
            self.shutdown_request(request)
            return
        with self._holding_lock:
            self._holding.add(id(request))
        try:
            super().process_request(request, client_address)
        except BaseException:
            # a Ctrl-C may land here after the connection's thread started, which gives its
            # place back too: the place is given back once, and the interrupt goes on
            self._give_back(request)
            raise

    def process_request_thread(self, request: Any, client_address: Any) -> None:
        try:
            super().process_request_thread(request, client_address)
        finally:
            self._give_back(request)

    def _give_back(self, request: Any) -> None:
        """Free the place ``request`` holds, once however many paths end it."""
        with self._holding_lock:
            if id(request) not in self._holding:
                return
            self._holding.discard(id(request))
        self._places.release()

    def handle_error(self, request: Any, client_address: Any) -> None:
        """What escaped a connection's handler: one line, never a traceback."""
        error = sys.exc_info()[1]
        if isinstance(error, ConnectionError | TimeoutError):
            _note(message("a client hung up ({kind})", kind=type(error).__name__))
        else:
            _note(_internal(error))

    def start(self) -> threading.Thread:
        """Serve in a background thread (for tests and benchmarks); :meth:`stop` ends it."""
        self._thread = threading.Thread(target=self.serve_forever, kwargs={"poll_interval": 0.1},
                                        daemon=True, name="planmethod-studio")
        self._thread.start()
        return self._thread

    def stop(self) -> None:
        """Stop serving, cancel the jobs and close the socket."""
        self.shutdown()
        self.close()
        if self._thread is not None:
            self._thread.join(5)

    def close(self) -> None:
        """Cancel every job (their processes end, their folders are removed) and close the
        socket."""
        self.jobs.close()
        self.server_close()

    def server_close(self) -> None:
        """Close the socket, and give the requests in flight :data:`CLOSE_SECONDS` in all to
        end (the standard server waits for every one, however long its client stalls)."""
        socketserver.TCPServer.server_close(self)   # the socket
        deadline = time.monotonic() + CLOSE_SECONDS
        for thread in list(vars(self).pop("_threads", ())):
            thread.join(max(0.0, deadline - time.monotonic()))


def _refuse_busy(request: socket.socket, connections: int, language: str) -> None:
    """Answer 503 on a connection the studio has no place for (best effort: never waits)."""
    busy = message("the studio is busy: {connections} connections are open, at most that many "
                   "at once; try again", connections=connections)
    body = json.dumps({"error": render(busy, language), "kind": "busy"}).encode()
    head = (f"HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json; "
            f"charset=utf-8\r\nContent-Length: {len(body)}\r\nRetry-After: 1\r\n"
            "Connection: close\r\n\r\n").encode()
    with contextlib.suppress(OSError):
        request.settimeout(0.2)
        request.sendall(head + body)


# -- the routes -----------------------------------------------------------------------------------
@dataclass(frozen=True)
class Route:
    """One address: its answer, what it reads — a JSON object with the fields of ``body``,
    an exercise's TOML (``toml``), a query with the fields of ``query`` — whether it
    computes (then it holds the server's lock) and the status of a good answer."""

    answer: Callable[[StudioServer, dict[str, Any]], Any]
    body: Mapping[str, schema.Field] | None = None
    toml: bool = False
    query: Mapping[str, schema.Field] | None = None
    computes: bool = False
    status: int = 200


def _json_body(text: str) -> dict[str, Any]:
    from ..spec import check_nesting

    check_nesting(text, syntax="json")

    def refuse(constant: str) -> None:
        raise SpecError(message("not a finite number: {constant}", constant=constant))

    try:
        data = json.loads(text, parse_constant=refuse)
    except ValueError as error:   # not JSON, or an integer of more digits than Python reads
        raise SpecError(message("not valid JSON: {error}", error=str(error))) from None
    if not isinstance(data, dict):
        raise SpecError(message("the request must be a JSON object"))
    return data


def _given(fields: dict[str, Any], *names: str) -> dict[str, Any]:
    """The options among ``names`` the request gave (the others keep the API's defaults)."""
    return {name: fields[name] for name in names if name in fields}


def _state(server: StudioServer, fields: dict) -> dict:
    from ..application.variants import MAX_VARIANTS

    return {"folder": server.workspace.root.name, "initial": server.initial,
            **server.workspace.listing(), "jobs": server.jobs.listing(),
            "limits": {"variants": api.MAX_PREVIEW, "export": MAX_VARIANTS},
            "language": current()}


def _files(server: StudioServer, fields: dict) -> dict:
    return server.workspace.listing()


def _solve(server: StudioServer, fields: dict) -> dict:
    return api.solve(fields["toml"], draft=fields.get("draft", False))


def _open(server: StudioServer, fields: dict) -> dict:
    return api.open_exercise(server.workspace, fields["path"])


def _save(server: StudioServer, fields: dict) -> dict:
    if fields["template"]:
        return api.save_template(server.workspace, fields["path"], fields["toml"],
                                 fields.get("ranges"), overwrite=fields["overwrite"])
    if "ranges" in fields:
        raise SpecError(message("ranges are saved with a template only (\"template\": true)"),
                        key="ranges")
    return api.save_exercise(server.workspace, fields["path"], fields["toml"],
                             overwrite=fields["overwrite"])


def _turn(server: StudioServer, fields: dict) -> dict:
    return api.turn(fields["toml"], fields["angle"])


def _variants(server: StudioServer, fields: dict) -> dict:
    arguments = api.prepare_variants(fields["toml"], fields.get("ranges") or {},
                                     **_given(fields, "count", "seed"))
    return {"job": server.jobs.start("variants", arguments, total=arguments["count"],
                                     language=current()).view()}


def _export(server: StudioServer, fields: dict) -> dict:
    arguments = api.prepare_export(server.workspace, fields["toml"], fields.get("ranges") or {},
                                   folder=fields["folder"],
                                   **_given(fields, "formats", "count", "seed"))
    return {"job": server.jobs.start("export", arguments, total=arguments["count"],
                                     language=current()).view()}


def _jobs(server: StudioServer, fields: dict) -> dict:
    return {"jobs": server.jobs.listing()}


def _job(server: StudioServer, fields: dict) -> dict:
    return server.jobs.get(fields["id"]).view(result=True)


def _cancel(server: StudioServer, fields: dict) -> dict:
    return server.jobs.cancel(fields["id"]).view()


ROUTES: dict[tuple[str, str], Route] = {
    ("GET", "/api/state"): Route(_state),
    ("GET", "/api/files"): Route(_files),
    ("GET", "/api/jobs"): Route(_jobs),
    ("GET", "/api/job"): Route(_job, query=schema.JOB),
    ("POST", "/api/solve"): Route(_solve, toml=True, computes=True),
    ("POST", "/api/open"): Route(_open, body=schema.OPEN, computes=True),
    ("POST", "/api/save"): Route(_save, body=schema.SAVE, computes=True),
    ("POST", "/api/turn"): Route(_turn, body=schema.TURN, computes=True),
    ("POST", "/api/variants"): Route(_variants, body=schema.VARIANTS, computes=True,
                                     status=202),
    ("POST", "/api/export"): Route(_export, body=schema.EXPORT, computes=True, status=202),
    ("POST", "/api/cancel"): Route(_cancel, body=schema.CANCEL),
}


class _DeadlineReader(io.RawIOBase):
    """A connection's socket, read with the time its handler allows: until the request's
    deadline once its first byte came (the whole request, not each read), until the idle
    limit before."""

    def __init__(self, connection: socket.socket, handler: StudioHandler) -> None:
        super().__init__()
        self.connection, self.handler = connection, handler

    def readable(self) -> bool:
        return True

    def readinto(self, buffer: Any) -> int:
        left = self.handler.time_left()
        if left <= 0:
            raise TimeoutError("the request took too long to arrive")
        self.connection.settimeout(left)
        count = self.connection.recv_into(buffer)
        if count:
            self.handler.begun()
        return count


class StudioHandler(BaseHTTPRequestHandler):
    """One connection: each request's safety checks, then its route."""

    server: StudioServer
    server_version = "planmethod-studio"
    sys_version = ""
    protocol_version = "HTTP/1.1"
    timeout = None   # the reads keep their own clock (_DeadlineReader), the answers theirs

    def setup(self) -> None:
        super().setup()
        # an answer's headers and body are two writes: without this the body's last segment
        # waits for the client's delayed acknowledgement of the headers (40 ms and more)
        self.connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.rfile.close()   # the socket's own file, replaced by one that keeps the deadline
        self.rfile = io.BufferedReader(_DeadlineReader(self.connection, self), 65536)
        self._deadline: float | None = None
        self._idle_until = time.monotonic() + self.server.idle_seconds

    def time_left(self) -> float:
        """How long the next read may wait (s)."""
        until = self._idle_until if self._deadline is None else self._deadline
        return until - time.monotonic()

    def begun(self) -> None:
        """The request's first bytes came: its deadline starts."""
        if self._deadline is None:
            self._deadline = time.monotonic() + self.server.request_seconds

    def handle_one_request(self) -> None:
        self._deadline = None
        self._idle_until = time.monotonic() + self.server.idle_seconds
        super().handle_one_request()

    def handle(self) -> None:
        """Serve the connection's requests; a client that hangs up mid-request is one line
        (between requests, nothing: that is how a connection ends)."""
        try:
            super().handle()
        except (ConnectionError, TimeoutError) as error:
            if self._deadline is not None:
                _note(message("a client hung up mid-request ({kind})",
                              kind=type(error).__name__))
            self.close_connection = True

    def do_GET(self) -> None:
        self._respond("GET")

    def do_POST(self) -> None:
        self._respond("POST")

    def do_PUT(self) -> None:
        self._respond("PUT")

    def do_DELETE(self) -> None:
        self._respond("DELETE")

    def do_HEAD(self) -> None:
        self._respond("HEAD")

    def log_message(self, format: str, *args: Any) -> None:
        """Requests are not logged (the terminal shows only the address and errors)."""

    def log_error(self, format: str, *args: Any) -> None:
        """A request cut off at its deadline is one line; other refusals, none."""
        if format.startswith("Request timed out") and self._deadline is not None:
            _note(_cut_off(self.server.request_seconds))

    # -- the checks -------------------------------------------------------------------------
    def _guard(self, query: dict[str, list[str]]) -> bool:
        """Refuse a foreign Host or Origin and a request without the token; True if the token
        came in the query (the page's first load: set the cookie)."""
        server = self.server
        if self.headers.get("Host", "") not in server.hosts:
            raise RefusedError(403, message("refused: the studio answers only to {host} (Host "
                                            "{given})", host=server.hosts[0],
                                            given=_given_host(self.headers.get("Host"))))
        origin = self.headers.get("Origin")
        if origin is not None and origin not in server.origins:
            raise RefusedError(403, message("refused: a request from another site ({origin!r})",
                                            origin=origin))
        if self.headers.get("Sec-Fetch-Site", "same-origin") not in ("same-origin", "none"):
            raise RefusedError(403, message("refused: a request from another site"))
        given = query.get("token", [None])[0]
        if given is not None and hmac.compare_digest(given.encode(), server.token.encode()):
            return True
        for candidate in (self.headers.get(TOKEN_HEADER), self._cookie()):
            if candidate is not None and hmac.compare_digest(candidate.encode(),
                                                             server.token.encode()):
                return False
        raise RefusedError(403, message("refused: no valid token (open the address the studio "
                                        "printed)"))

    def _cookie(self) -> str | None:
        try:
            cookie = SimpleCookie(self.headers.get("Cookie", ""))
        except CookieError:
            return None
        morsel = cookie.get(self.server.cookie_name)
        return morsel.value if morsel is not None else None

    def _framing(self, method: str) -> None:
        """Refuse a request whose body's length is not told once (checked before anything
        else: the connection cannot be read further)."""
        lengths = self.headers.get_all("Content-Length") or []
        if len(lengths) > 1:
            self.close_connection = True
            raise RefusedError(400, message("{count} Content-Length headers: a request has one",
                                            count=len(lengths)))
        if method == "POST":
            return
        if self.headers.get("Transfer-Encoding") or (lengths and lengths[0].strip() != "0"):
            self.close_connection = True
            raise RefusedError(400, message("a {method} request has no body", method=method))

    def _body(self) -> str:
        if self.headers.get("Transfer-Encoding"):
            self._drain = True
            raise RefusedError(411, message("a body must come with its length (no chunked "
                                            "encoding)"))
        length = self.headers.get("Content-Length")
        if length is None:
            self._drain = True
            raise RefusedError(411, message("a body must come with its length "
                                            "(Content-Length)"))
        try:
            size = int(length)
        except ValueError:
            self.close_connection = True
            raise RefusedError(400, message("Content-Length {length!r} is not a number",
                                            length=length[:40])) from None
        if size < 0:
            self.close_connection = True
            raise RefusedError(400, message("Content-Length is negative"))
        if size > api.MAX_BODY:
            self._drain = True
            raise RefusedError(413, message("the body is {size} bytes; at most {limit} are read",
                                            size=size, limit=api.MAX_BODY))
        try:
            data = self.rfile.read(size)
        except TimeoutError:
            self.close_connection = True
            _note(_cut_off(self.server.request_seconds))
            raise RefusedError(408, message("the request did not arrive within {seconds:g} s",
                                            seconds=self.server.request_seconds)) from None
        self._read = True
        if len(data) != size:
            self.close_connection = True
            raise RefusedError(400, message("the body ended before its length"))
        try:
            return data.decode("utf-8")
        except UnicodeDecodeError:
            raise RefusedError(400, message("the body is not UTF-8 text")) from None

    def _fields(self, route: Route, method: str, query: dict[str, list[str]]) -> dict[str, Any]:
        """What the request gives, typed by its route's schema."""
        fields: dict[str, Any] = {}
        if route.query is not None:
            given = {name: values[-1] for name, values in query.items() if name != "token"}
            fields |= schema.read_fields(given, route.query)
        if method == "POST":
            text = self._body()
            if route.toml and not self.headers.get("Content-Type", "").startswith(
                    "application/json"):
                fields["toml"] = text
            elif route.body is not None or route.toml:   # the page's exercise: Python's TOML
                data = exercise_data.with_toml(_json_body(text))
                fields |= schema.read_fields(data, route.body or schema.SOLVE)
        return fields

    # -- answering --------------------------------------------------------------------------
    def _respond(self, method: str) -> None:
        """Answer one request, in the studio's language, or its exercise's."""
        self._language = self.server.base_language
        with speaking(self._language):
            self._answer(method)

    def _answer(self, method: str) -> None:
        self._drain = self._read = False
        split = urlsplit(self.path)
        query = parse_qs(split.query)
        cookie = False
        try:
            self._framing(method)
            cookie = self._guard(query)
            if split.path == "/" and method in ("GET", "HEAD"):
                self._send(200, self.server.page, "text/html; charset=utf-8", cookie=cookie,
                           page=True, head=method == "HEAD")
                self.server.jobs.warm()   # a job's process, ready for the page's first job
                return
            found = page_file(split.path) if method in ("GET", "HEAD") else None
            if found is not None:   # a script of the page
                self._send(200, found.content, found.content_type, head=method == "HEAD")
                return
            route = ROUTES.get((method, split.path))
            if route is None:
                known = any(path == split.path for _, path in ROUTES)
                raise RefusedError(405 if known else 404, message(
                    "{method} {path}: not allowed", method=method, path=split.path) if known
                    else message("{method} {path}: no such address", method=method,
                                 path=split.path))
            fields = self._fields(route, method, query)
            self._language = self.server.spoken(fields.get("toml"))
            with speaking(self._language):
                payload = self._computed(route, fields)
            self._json(route.status, payload, cookie=cookie)
        except (ConnectionError, TimeoutError):
            raise
        except Exception as error:   # every failure: one line (_failure)
            with speaking(self._language):
                status, payload = _failure(error)
            if method == "POST" and not self._read and status != 408:
                self._drain = True   # a body left unread: read it away, then close
            self._json(status, payload)
        finally:
            if self._drain:
                self._drain_body()

    def _computed(self, route: Route, fields: dict[str, Any]) -> Any:
        """The route's answer (under the server's lock if it computes)."""
        if route.computes:
            with self.server.lock:
                return route.answer(self.server, fields)
        return route.answer(self.server, fields)

    def _json(self, status: int, payload: Any, *, cookie: bool = False) -> None:
        data = json.dumps(payload, ensure_ascii=False, allow_nan=False).encode("utf-8")
        self._send(status, data, "application/json; charset=utf-8", cookie=cookie)

    def _send(self, status: int, data: bytes, content_type: str, *, cookie: bool = False,
              page: bool = False, head: bool = False) -> None:
        self.connection.settimeout(SEND_SECONDS)
        self.send_response(status, HTTPStatus(status).phrase)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Length", str(len(data)))
        self.send_header("Cache-Control", "no-store")
        self.send_header("X-Content-Type-Options", "nosniff")
        self.send_header("Referrer-Policy", "no-referrer")
        self.send_header("X-Frame-Options", "DENY")
        if page:
            self.send_header("Content-Security-Policy",
                             "default-src 'none'; script-src 'self'; style-src "
                             "'unsafe-inline'; img-src data:; connect-src 'self'; "
                             "frame-ancestors 'none'; base-uri 'none'; form-action 'none'")
        if cookie:
            self.send_header("Set-Cookie", f"{self.server.cookie_name}={self.server.token}; "
                                           "Path=/; HttpOnly; SameSite=Strict")
        if (self._drain or self.close_connection
                or (status >= 400 and status not in (400, 404, 405, 409, 429))):
            self.send_header("Connection", "close")
            self.close_connection = True
        self.end_headers()
        if not head:
            self.wfile.write(data)
        self.wfile.flush()

    def _drain_body(self) -> None:
        """Read and drop what the client still sends of a refused body (bounded), so that it
        can read the answer: closing a socket with unread data resets the connection."""
        try:
            self.connection.shutdown(socket.SHUT_WR)
            self.connection.settimeout(0.2)
            deadline, total = time.monotonic() + DRAIN_SECONDS, 0
            while total < DRAIN_BYTES and time.monotonic() < deadline:
                chunk = self.connection.recv(65536)
                if not chunk:
                    break
                total += len(chunk)
        except OSError:
            pass


def _failure(error: Exception) -> tuple[int, dict[str, str]]:
    """A failed request's status and one-line answer; a bug is also one line in the
    terminal."""
    if isinstance(error, RefusedError):
        return error.status, {"error": str(error), "kind": error.kind}
    if isinstance(error, BusyError):
        return 429, {"error": str(error), "kind": "busy"}
    if isinstance(error, NoSuchJobError):
        return 404, {"error": str(error), "kind": "refused"}
    if isinstance(error, FileExistsError):
        return 409, {"error": render(message("{path} exists already", path=error.args[0])),
                     "kind": "exists"}
    if isinstance(error, PlanmethodError | OverflowError | RecursionError | MemoryError):
        return 400, api.error_payload(error)
    line = render(_internal(error)).replace("\n", " ")
    _note(line)
    return 500, {"error": line, "kind": "internal"}


def _internal(error: BaseException) -> Message:
    """A bug, in one line: its kind and what it says."""
    return message("internal error ({kind}): {error}", kind=type(error).__name__,
                   error=str(error))


def _cut_off(seconds: float) -> Message:
    return message("a request took longer than {seconds:g} s to arrive: cut off",
                   seconds=seconds)


def _given_host(host: str | None) -> str:
    """The ``Host`` a refused request gave, as the line shows it."""
    return repr(host) if host is not None else repr(render(message("missing")))
