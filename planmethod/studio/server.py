"""The studio's HTTP server: the standard library's ``ThreadingHTTPServer`` and a thin router.

Why the standard library: the studio serves one page and a dozen JSON calls to one person on
one machine; ``http.server`` does that with no new dependency, and its plainness keeps the
safety rules below easy to read and to test. (An ASGI stack — Starlette and uvicorn — would add
two packages for features the studio does not use.)

Safety, for a server that can write files:

* it listens on 127.0.0.1 only;
* every request needs the token made at start (``secrets.token_urlsafe``): in the query of the
  first page load (``/?token=…``), then in a cookie (HttpOnly, SameSite=Strict) or the header
  ``X-Planmethod-Token``; without it: 403;
* a ``Host`` other than ``127.0.0.1:PORT`` or ``localhost:PORT`` (DNS rebinding) and an
  ``Origin`` or ``Sec-Fetch-Site`` of another site (cross-site requests) are refused: 403;
* a body is at most :data:`~planmethod.studio.api.MAX_BODY` bytes (413 above, before reading
  it), read with a declared length only (411 otherwise), and parsed with the command line's
  limits (TOML and JSON nesting, numbers' ranges: :mod:`planmethod.spec`);
* files are read and written only under the folder the studio was started in, with the
  command line's path rules and atomic writes (:class:`~planmethod.studio.api.Workspace`).

A refused or failed request answers ``{"error": "one line", "kind": …}`` with a 4xx status,
never a traceback.

Examples
--------
>>> import tempfile, urllib.request, json
>>> server = StudioServer(tempfile.mkdtemp(), port=0)
>>> thread = server.start()
>>> request = urllib.request.Request(server.url("/api/files"),
...                                  headers={"X-Planmethod-Token": server.token})
>>> json.load(urllib.request.urlopen(request))
{'files': []}
>>> server.stop()
"""

from __future__ import annotations

import hmac
import json
import secrets
import socket
import sys
import threading
import time
from collections.abc import Callable
from http import HTTPStatus
from http.cookies import CookieError, SimpleCookie
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from pathlib import Path
from typing import Any
from urllib.parse import parse_qs, urlsplit

from ..errors import PlanmethodError, SpecError
from . import api

__all__ = ["HOST", "StudioServer"]

#: the only address the studio listens on
HOST = "127.0.0.1"
#: the header and cookie that carry the token
TOKEN_HEADER = "X-Planmethod-Token"
#: after refusing a body that is too large, read and drop at most this much of it (bytes) for
#: at most this long (s), so that the client reads the answer instead of a reset connection
DRAIN_BYTES, DRAIN_SECONDS = 16_000_000, 2.0


class RefusedError(PlanmethodError, PermissionError):
    """A request the studio will not serve: its HTTP status and one line."""

    def __init__(self, status: int, message: str, kind: str = "refused") -> None:
        super().__init__(message)
        self.status, self.kind = status, kind


def _page() -> bytes:
    return resources.files("planmethod.studio").joinpath("studio.html").read_bytes()


class StudioServer(ThreadingHTTPServer):
    """The studio: serves the page and the API for the files under ``folder``.

    ``port`` 0 takes a free port. ``initial`` is a file (relative to ``folder``) the page
    opens first.
    """

    daemon_threads = True
    allow_reuse_address = False

    def __init__(self, folder: str | Path, port: int = 0, *, initial: str | None = None,
                 token: str | None = None) -> None:
        self.workspace = api.Workspace(folder)
        self.token = token or secrets.token_urlsafe(32)
        self.initial = initial
        self.page = _page()
        self.lock = threading.Lock()
        self._thread: threading.Thread | None = None
        super().__init__((HOST, port), StudioHandler)

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

    def start(self) -> threading.Thread:
        """Serve in a background thread (for tests and benchmarks); :meth:`stop` ends it."""
        self._thread = threading.Thread(target=self.serve_forever, kwargs={"poll_interval": 0.1},
                                        daemon=True, name="planmethod-studio")
        self._thread.start()
        return self._thread

    def stop(self) -> None:
        """Stop serving and close the socket."""
        self.shutdown()
        self.server_close()
        if self._thread is not None:
            self._thread.join(5)


# -- the routes -----------------------------------------------------------------------------------
Route = Callable[["StudioServer", dict[str, Any], str], Any]


def _json_body(text: str) -> dict[str, Any]:
    from ..spec import check_nesting

    check_nesting(text)

    def refuse(constant: str) -> None:
        raise SpecError(f"not a finite number: {constant}")

    try:
        data = json.loads(text, parse_constant=refuse)
    except json.JSONDecodeError as error:
        raise SpecError(f"not valid JSON: {error}") from None
    if not isinstance(data, dict):
        raise SpecError("the request must be a JSON object")
    return data


def _state(server: StudioServer, query: dict, body: str) -> dict:
    return {"folder": server.workspace.root.name, "initial": server.initial,
            "files": server.workspace.files()}


def _files(server: StudioServer, query: dict, body: str) -> dict:
    return {"files": server.workspace.files()}


def _solve(server: StudioServer, query: dict, body: str) -> dict:
    return api.solve(body)


def _open(server: StudioServer, query: dict, body: str) -> dict:
    return api.open_exercise(server.workspace, _json_body(body).get("path"))


def _save(server: StudioServer, query: dict, body: str) -> dict:
    data = _json_body(body)
    if data.get("template"):
        return api.save_template(server.workspace, data.get("path"), data.get("toml"),
                                 data.get("ranges"), overwrite=bool(data.get("overwrite")))
    return api.save_exercise(server.workspace, data.get("path"), data.get("toml"),
                             overwrite=bool(data.get("overwrite")))


def _turn(server: StudioServer, query: dict, body: str) -> dict:
    data = _json_body(body)
    return api.turn(_text(data), data.get("angle"))


def _variants(server: StudioServer, query: dict, body: str) -> dict:
    data = _json_body(body)
    return api.variants(_text(data), data.get("ranges") or {}, count=data.get("count", 6),
                        seed=data.get("seed", 0))


def _export(server: StudioServer, query: dict, body: str) -> dict:
    data = _json_body(body)
    return api.export(server.workspace, _text(data), data.get("ranges") or {},
                      folder=data.get("folder"), formats=data.get("formats", list(api.FORMATS)),
                      count=data.get("count", 30), seed=data.get("seed", 0))


def _text(data: dict[str, Any]) -> str:
    text = data.get("toml")
    if not isinstance(text, str):
        raise SpecError("the exercise must be TOML text", key="toml")
    return text


ROUTES: dict[tuple[str, str], Route] = {
    ("GET", "/api/state"): _state,
    ("GET", "/api/files"): _files,
    ("POST", "/api/solve"): _solve,
    ("POST", "/api/open"): _open,
    ("POST", "/api/save"): _save,
    ("POST", "/api/turn"): _turn,
    ("POST", "/api/variants"): _variants,
    ("POST", "/api/export"): _export,
}


class StudioHandler(BaseHTTPRequestHandler):
    """One request: the safety checks, then the route."""

    server: StudioServer
    server_version = "planmethod-studio"
    sys_version = ""
    protocol_version = "HTTP/1.1"
    #: seconds a connection may stay idle (or a body may take to arrive)
    timeout = 60

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

    # -- the checks -------------------------------------------------------------------------
    def _guard(self, query: dict[str, list[str]]) -> bool:
        """Refuse a foreign Host or Origin and a request without the token; True if the token
        came in the query (the page's first load: set the cookie)."""
        server = self.server
        if self.headers.get("Host", "") not in server.hosts:
            raise RefusedError(403, f"refused: the studio answers only to {server.hosts[0]} (Host "
                               f"{self.headers.get('Host', 'missing')!r})")
        origin = self.headers.get("Origin")
        if origin is not None and origin not in server.origins:
            raise RefusedError(403, f"refused: a request from another site ({origin!r})")
        if self.headers.get("Sec-Fetch-Site", "same-origin") not in ("same-origin", "none"):
            raise RefusedError(403, "refused: a request from another site")
        given = query.get("token", [None])[0]
        if given is not None and hmac.compare_digest(given.encode(), server.token.encode()):
            return True
        for candidate in (self.headers.get(TOKEN_HEADER), self._cookie()):
            if candidate is not None and hmac.compare_digest(candidate.encode(),
                                                             server.token.encode()):
                return False
        raise RefusedError(403, "refused: no valid token (open the address the studio printed)")

    def _cookie(self) -> str | None:
        try:
            cookie = SimpleCookie(self.headers.get("Cookie", ""))
        except CookieError:
            return None
        morsel = cookie.get(self.server.cookie_name)
        return morsel.value if morsel is not None else None

    def _body(self) -> str:
        if self.headers.get("Transfer-Encoding"):
            self._drain = True
            raise RefusedError(411, "a body must come with its length (no chunked encoding)")
        length = self.headers.get("Content-Length")
        if length is None:
            self._drain = True
            raise RefusedError(411, "a body must come with its length (Content-Length)")
        try:
            size = int(length)
        except ValueError:
            raise RefusedError(400, f"Content-Length {length!r} is not a number") from None
        if size < 0:
            raise RefusedError(400, "Content-Length is negative")
        if size > api.MAX_BODY:
            self._drain = True
            raise RefusedError(413, f"the body is {size} bytes; at most {api.MAX_BODY} are read")
        data = self.rfile.read(size)
        if len(data) != size:
            raise RefusedError(400, "the body ended before its length")
        try:
            return data.decode("utf-8")
        except UnicodeDecodeError:
            raise RefusedError(400, "the body is not UTF-8 text") from None

    # -- answering --------------------------------------------------------------------------
    def _respond(self, method: str) -> None:
        self._drain = False
        split = urlsplit(self.path)
        query = parse_qs(split.query)
        cookie = False
        try:
            cookie = self._guard(query)
            if split.path == "/" and method in ("GET", "HEAD"):
                self._send(200, self.server.page, "text/html; charset=utf-8", cookie=cookie,
                           page=True, head=method == "HEAD")
                return
            route = ROUTES.get((method, split.path))
            if route is None:
                known = any(path == split.path for _, path in ROUTES)
                raise RefusedError(405 if known else 404,
                              f"{method} {split.path}: " + ("not allowed" if known else
                                                            "no such address"))
            body = self._body() if method == "POST" else ""
            with self.server.lock:
                payload = route(self.server, query, body)
            self._json(200, payload, cookie=cookie)
        except RefusedError as refused:
            self._json(refused.status, {"error": refused.message, "kind": refused.kind})
        except FileExistsError as error:
            self._json(409, {"error": f"{error.args[0]} exists already", "kind": "exists"})
        except (PlanmethodError, OverflowError, RecursionError, MemoryError) as error:
            self._json(400, api.error_payload(error))
        except (BrokenPipeError, ConnectionResetError):   # the page went away: nothing to say
            self.close_connection = True
        except Exception as error:   # a bug: one line to the page and the terminal
            message = f"internal error ({type(error).__name__}): {error}".replace("\n", " ")
            print(f"planmethod studio: {message}", file=sys.stderr)
            try:
                self._json(500, {"error": message, "kind": "internal"})
            except OSError:
                self.close_connection = True
        finally:
            if self._drain:
                self._drain_body()

    def _json(self, status: int, payload: Any, *, cookie: bool = False) -> None:
        data = json.dumps(payload, ensure_ascii=False, allow_nan=False).encode("utf-8")
        self._send(status, data, "application/json; charset=utf-8", cookie=cookie)

    def _send(self, status: int, data: bytes, content_type: str, *, cookie: bool = False,
              page: bool = False, head: bool = False) -> None:
        self.send_response(status, HTTPStatus(status).phrase)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Length", str(len(data)))
        self.send_header("Cache-Control", "no-store")
        self.send_header("X-Content-Type-Options", "nosniff")
        self.send_header("Referrer-Policy", "no-referrer")
        self.send_header("X-Frame-Options", "DENY")
        if page:
            self.send_header("Content-Security-Policy",
                             "default-src 'none'; script-src 'unsafe-inline'; style-src "
                             "'unsafe-inline'; img-src data:; connect-src 'self'; "
                             "frame-ancestors 'none'; base-uri 'none'; form-action 'none'")
        if cookie:
            self.send_header("Set-Cookie", f"{self.server.cookie_name}={self.server.token}; "
                                           "Path=/; HttpOnly; SameSite=Strict")
        if self._drain or (status >= 400 and status not in (400, 404, 405, 409)):
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
