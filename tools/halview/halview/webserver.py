# SPDX-License-Identifier: GPL-2.0-or-later
"""The one web server of halmeter, halscope, halshow and halweb.

Static files (the page, its script and style, and the dygraphs library the
build copied from Debian's libjs-dygraphs) over HTTP, live data over a
websocket at /ws, JSON messages both ways (docs/halweb.md).  Every response
carries a Content-Security-Policy that allows this origin only, so the page
cannot load anything from elsewhere.  With a token, every request must carry
it (?token=...), compared in constant time.  A read-only server refuses
every change to HAL.
"""

from __future__ import annotations

import asyncio
import hmac
import json
import mimetypes
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import parse_qs

from websockets.asyncio.server import ServerConnection, serve
from websockets.datastructures import Headers
from websockets.exceptions import ConnectionClosed
from websockets.http11 import Request, Response

from . import halapi, model, setupfile
from .capture import ScopeConfig
from .halapi import HalError
from .webscope import WebScope, config_from_json, config_json

STATIC = Path(__file__).resolve().parent / "static"
# dygraphs sets style attributes in the markup it builds, hence 'unsafe-inline'
# for styles; scripts, connections and images come from this origin only.
CSP = (
    "default-src 'self'; script-src 'self'; connect-src 'self'; img-src 'self' data:; "
    "style-src 'self' 'unsafe-inline'"
)
READ_ONLY = "this page is read-only (the server was started with --read-only)"


def share_dir() -> Path:
    env = os.environ.get("HALWEB_SHARE")
    if env:
        return Path(env)
    build = Path(os.environ.get("HM_BUILD", Path(__file__).resolve().parents[3] / "build"))
    return build / "share" / "halweb"


@dataclass
class Options:
    host: str = "127.0.0.1"
    port: int = 8080
    token: str | None = None
    read_only: bool = False
    rate: float = 10.0
    page: str = "show"
    watch: list[tuple[int, str]] = field(default_factory=list)
    scope_cfg: ScopeConfig | None = None
    fformat: str | None = None


class Client:
    """One open page."""

    def __init__(self, ws: ServerConnection, watch: list[tuple[int, str]]) -> None:
        self.ws = ws
        self.watch = list(watch)
        self.seq = 0
        self.acked = 0
        self.window = 0  # 0: no flow control; else at most this many unacknowledged


class Server:
    def __init__(self, opts: Options) -> None:
        self.opts = opts
        self.clients: set[Client] = set()
        self.loop: asyncio.AbstractEventLoop | None = None
        self.scope = WebScope(self.publish_threadsafe)
        self.last_scope: dict[str, object] | None = None
        self.files = {
            "/": (STATIC / "index.html", "text/html; charset=utf-8"),
            "/app.js": (STATIC / "app.js", "text/javascript; charset=utf-8"),
            "/style.css": (STATIC / "style.css", "text/css; charset=utf-8"),
            "/dygraph.min.js": (share_dir() / "dygraph.min.js", "text/javascript; charset=utf-8"),
            "/dygraph.min.css": (share_dir() / "dygraph.min.css", "text/css; charset=utf-8"),
        }
        for path, (f, _) in self.files.items():
            if not f.exists():
                raise HalError(f"{f} is missing (needed for {path}): build the tree (make)")

    # ---- HTTP ------------------------------------------------------------

    def _token_ok(self, request: Request) -> bool:
        if self.opts.token is None:
            return True
        q = parse_qs(request.path.partition("?")[2])
        given = q.get("token", [""])[0]
        return hmac.compare_digest(given.encode(), self.opts.token.encode())

    def _response(self, status: int, body: bytes, ctype: str) -> Response:
        reason = {200: "OK", 403: "Forbidden", 404: "Not Found"}.get(status, "Error")
        headers = Headers(
            [
                ("Content-Type", ctype),
                ("Content-Length", str(len(body))),
                ("Content-Security-Policy", CSP),
                ("X-Content-Type-Options", "nosniff"),
                ("Cache-Control", "no-store"),
            ]
        )
        return Response(status, reason, headers, body)

    def process_request(self, conn: ServerConnection, request: Request) -> Response | None:
        path = request.path.partition("?")[0]
        if not self._token_ok(request):
            return self._response(403, b"a valid token is required (?token=...)\n", "text/plain")
        if path == "/ws":
            return None  # the websocket handshake goes on
        if path == "/favicon.ico":
            return self._response(200, b"", "image/x-icon")
        if path not in self.files:
            return self._response(404, f"no such page: {path}\n".encode(), "text/plain")
        f, ctype = self.files[path]
        return self._response(200, f.read_bytes(), ctype or mimetypes.guess_type(str(f))[0])

    # ---- websocket -------------------------------------------------------

    def publish_threadsafe(self, msg: dict[str, object]) -> None:
        """From the scope thread: send to every page."""
        if msg.get("type") == "scope":
            self.last_scope = msg
        if self.loop is not None:
            self.loop.call_soon_threadsafe(self._broadcast, json.dumps(msg))

    def _broadcast(self, text: str) -> None:
        for c in list(self.clients):
            asyncio.ensure_future(self._send(c, text))

    async def _send(self, c: Client, text: str) -> None:
        try:
            await c.ws.send(text)
        except ConnectionClosed:
            self.clients.discard(c)

    def hello(self) -> dict[str, object]:
        return {
            "type": "hello",
            "page": self.opts.page,
            "read_only": self.opts.read_only,
            "rate": self.opts.rate,
            "simclock": halapi.simclock(),
            "instance": os.environ.get("HAL_INSTANCE", "0") or "0",
            "threads": halapi.list_names(halapi.THREAD),
            "watch": [[halapi.KIND_NAMES[k], n] for k, n in self.opts.watch],
            "scope": config_json(self.scope.cfg if self.scope.cfg.channels else self._cfg0()),
            "scope_running": self.scope.running,
            "fformat": self.opts.fformat,
        }

    def _cfg0(self) -> ScopeConfig:
        cfg = self.opts.scope_cfg or ScopeConfig()
        if not cfg.thread:
            threads = halapi.list_names(halapi.THREAD)
            cfg.thread = threads[0] if threads else ""
        return cfg

    async def handler(self, ws: ServerConnection) -> None:
        client = Client(ws, self.opts.watch)
        self.clients.add(client)
        pusher = asyncio.ensure_future(self._push_values(client))
        try:
            await ws.send(json.dumps(self.hello()))
            if self.last_scope is not None:
                await ws.send(json.dumps(self.last_scope))
            async for text in ws:
                reply = await asyncio.get_running_loop().run_in_executor(
                    None, self.handle_message, client, text
                )
                if reply is not None:
                    await ws.send(json.dumps(reply))
        except ConnectionClosed:
            pass
        finally:
            pusher.cancel()
            self.clients.discard(client)

    async def _push_values(self, c: Client) -> None:
        period = 1.0 / self.opts.rate
        try:
            while True:
                if c.window and c.seq - c.acked >= c.window:
                    await asyncio.sleep(min(period, 0.005))  # the page is still drawing
                    continue
                t_read = time.time()
                vals = halapi.get_many(c.watch)
                c.seq += 1
                msg = {
                    "type": "values",
                    "seq": c.seq,
                    "t_read": t_read,
                    "hal_time": halapi.now_ns(),
                    "names": [[halapi.KIND_NAMES[k], n] for k, n in c.watch],
                    "values": vals,
                }
                await c.ws.send(json.dumps(msg))
                await asyncio.sleep(max(0.0, period - (time.time() - t_read)))
        except ConnectionClosed:
            self.clients.discard(c)

    def handle_message(self, c: Client, text: str) -> dict[str, object] | None:
        try:
            msg = json.loads(text)
            if not isinstance(msg, dict):
                raise HalError("a message is a JSON object")
            return self._dispatch(c, msg)
        except (HalError, ValueError, KeyError, TypeError) as e:
            return {"type": "error", "error": str(e)}

    def _dispatch(self, c: Client, msg: dict[str, object]) -> dict[str, object] | None:
        op = msg.get("op")
        if op == "tree":
            snap = model.snapshot(str(msg.get("pattern", "")))
            return {"type": "tree", "items": {k: [i.to_json() for i in v] for k, v in snap.items()}}
        if op == "watch":
            items = msg.get("items", [])
            if not isinstance(items, list):
                raise HalError("watch: a list of [kind, name]")
            watch = []
            for k, n in items:
                if k not in ("pin", "param", "sig"):
                    raise HalError(f"cannot watch a {k}")
                watch.append((halapi.KIND_BY_NAME[k], str(n)))
            c.watch = watch
            return None
        if op == "set":
            return self._set(msg)
        if op == "scope_run":
            return self._scope_run(msg)
        if op == "scope_stop":
            self.scope.stop()
            return {"type": "scope_status", "text": "stopped", "error": False, "running": False}
        if op == "scope_load":
            cfg = setupfile.loads(str(msg.get("text", "")), "setup")
            return {"type": "scope_setup", "setup": config_json(cfg)}
        if op == "flow":
            c.window = max(0, int(msg.get("window", 0)))  # type: ignore[call-overload]
            return None
        if op == "ack":
            c.acked = max(c.acked, int(msg.get("seq", 0)))  # type: ignore[call-overload]
            return None
        if op == "ping":
            return {"type": "pong", "t": msg.get("t")}
        raise HalError(f"unknown op '{op}'")

    def _set(self, msg: dict[str, object]) -> dict[str, object]:
        kind, name, value = str(msg["kind"]), str(msg["name"]), str(msg["value"])
        reply: dict[str, object] = {"type": "set", "kind": kind, "name": name}
        if self.opts.read_only:
            return reply | {"ok": False, "error": READ_ONLY}
        if kind not in ("pin", "param", "sig"):
            return reply | {"ok": False, "error": f"a {kind} has no value to set"}
        try:
            now = model.set_item(halapi.KIND_BY_NAME[kind], name, value)
        except HalError as e:
            return reply | {"ok": False, "error": str(e)}
        return reply | {"ok": True, "value": now}

    def _scope_run(self, msg: dict[str, object]) -> dict[str, object]:
        setup = msg.get("setup")
        if not isinstance(setup, dict):
            raise HalError("scope_run: a setup object is needed")
        cfg = config_from_json(setup)
        self.scope.start(cfg, may_change_hal=not self.opts.read_only)
        return {"type": "scope_setup", "setup": config_json(cfg), "running": True}

    # ---- running ---------------------------------------------------------

    async def run(self, ready: "asyncio.Future[tuple[str, int]] | None" = None) -> None:
        self.loop = asyncio.get_running_loop()
        async with serve(
            self.handler,
            self.opts.host,
            self.opts.port,
            process_request=self.process_request,
            max_size=2**22,
            # a page (or an HTTP client) that does not answer the closing
            # handshake holds the server's exit at most this long, well
            # inside the 2 s that the end of a session grants a component
            close_timeout=0.5,
        ) as server:
            sock = next(iter(server.sockets))
            host, port = sock.getsockname()[:2]
            if ready is not None:
                ready.set_result((host, port))
            if self.opts.scope_cfg is not None and self.opts.scope_cfg.channels:
                try:
                    self.scope.start(self.opts.scope_cfg, not self.opts.read_only)
                except HalError as e:
                    self.scope.cfg = self.opts.scope_cfg
                    self.scope.status(str(e), error=True)
                    raise
            try:
                await asyncio.Future()
            finally:
                self.scope.stop()
