# SPDX-License-Identifier: GPL-2.0-or-later
"""halweb's server without a browser: HTTP, token, read-only, the websocket
protocol (docs/halweb.md), clients that vanish mid-stream.  Values are
compared with halcmd's getp/gets, errors with halcmd's."""

from __future__ import annotations

import json
import re
import socket
import urllib.error
import urllib.request
from pathlib import Path

import pytest
from websockets.sync.client import connect

from hvutil import BIN, BUILT, LiveHal

pytestmark = pytest.mark.requires_build(*BUILT)

LIVE = """\
loadrt threads name1=fast period1=1000000
loadrt siggen
addf siggen.0.update fast
newsig free float
sets free 1.5
start
"""


@pytest.fixture
def live(tmp_path: Path) -> LiveHal:
    hal = LiveHal(tmp_path, LIVE)
    yield hal
    hal.stop()


def ws_url(url: str) -> str:
    base, _, query = url.partition("?")
    return base.replace("http://", "ws://") + "ws" + ("?" + query if query else "")


def recv_type(ws: object, kind: str, limit: int = 200) -> dict[str, object]:
    for _ in range(limit):
        m = json.loads(ws.recv(timeout=20))  # type: ignore[attr-defined]
        if m["type"] == kind:
            return m  # type: ignore[no-any-return]
    raise AssertionError(f"no {kind} message")


def test_page_and_files_are_local(live: LiveHal) -> None:
    _, url = live.start_web(BIN / "halweb")
    assert url.startswith("http://127.0.0.1:")
    with urllib.request.urlopen(url) as r:
        html = r.read().decode()
        csp = r.headers["Content-Security-Policy"]
    assert "default-src 'self'" in csp and "script-src 'self'" in csp
    refs = re.findall(r'(?:src|href)="([^"]+)"', html)
    assert refs and all("//" not in ref and not ref.startswith("/") for ref in refs), refs
    for ref in refs:
        with urllib.request.urlopen(url + ref) as r:
            assert r.status == 200 and len(r.read()) > 100
    js = urllib.request.urlopen(url + "dygraph.min.js").read()
    assert js == Path("/usr/share/javascript/dygraphs/dygraph.min.js").read_bytes()
    with pytest.raises(urllib.error.HTTPError) as e:
        urllib.request.urlopen(url + "nope.html")
    assert e.value.code == 404


def test_values_and_set_like_halcmd(live: LiveHal) -> None:
    _, url = live.start_web(BIN / "halweb", "sig+free", "param+fast.tmax")
    with connect(ws_url(url)) as ws:
        hello = recv_type(ws, "hello")
        assert hello["read_only"] is False and hello["threads"] == ["fast"]
        assert hello["watch"] == [["sig", "free"], ["param", "fast.tmax"]]
        ws.send(
            json.dumps({"op": "watch", "items": [["sig", "free"], ["pin", "siggen.0.amplitude"]]})
        )
        v = recv_type(ws, "values")
        while v["names"] != [["sig", "free"], ["pin", "siggen.0.amplitude"]]:
            v = recv_type(ws, "values")
        assert v["values"] == [
            live.halcmd("gets", "free").stdout.strip(),
            live.getp("siggen.0.amplitude"),
        ]
        ws.send(
            json.dumps({"op": "set", "kind": "pin", "name": "siggen.0.amplitude", "value": "3.25"})
        )
        s = recv_type(ws, "set")
        assert s["ok"] is True and s["value"] == "3.25"
        assert live.getp("siggen.0.amplitude") == "3.25"
        for kind, name, value, args in [
            ("pin", "siggen.0.sine", "1", ["setp", "siggen.0.sine", "1"]),
            ("param", "fast.tmax", "x", ["setp", "fast.tmax", "x"]),
            ("sig", "nosig", "1", ["sets", "nosig", "1"]),
        ]:
            ws.send(json.dumps({"op": "set", "kind": kind, "name": name, "value": value}))
            s = recv_type(ws, "set")
            reason = live.halcmd(*args).stderr.splitlines()[0].split(": ", 1)[-1]
            assert s["ok"] is False and s["error"] == reason
        ws.send(json.dumps({"op": "tree", "pattern": "siggen.0.a"}))
        t = recv_type(ws, "tree")
        assert [i["name"] for i in t["items"]["pin"]] == ["siggen.0.amplitude"]
        assert t["items"]["pin"][0]["value"] == "3.25"
        ws.send(json.dumps({"op": "bogus"}))
        assert recv_type(ws, "error")["error"] == "unknown op 'bogus'"
        ws.send("not json")
        assert "error" in recv_type(ws, "error")


def test_read_only(live: LiveHal) -> None:
    _, url = live.start_web(BIN / "halweb", "--read-only")
    with connect(ws_url(url)) as ws:
        assert recv_type(ws, "hello")["read_only"] is True
        ws.send(json.dumps({"op": "set", "kind": "sig", "name": "free", "value": "9"}))
        s = recv_type(ws, "set")
        assert s["ok"] is False and "read-only" in str(s["error"])
        ws.send(
            json.dumps(
                {"op": "scope_run", "setup": {"channels": ["siggen.0.sine"], "thread": "fast"}}
            )
        )
        assert "read-only page" in str(recv_type(ws, "error")["error"])
    assert live.halcmd("gets", "free").stdout.strip() == "1.5"
    assert "scope_rt" not in live.halcmd("show", "comp").stdout


def test_token(live: LiveHal) -> None:
    _, url = live.start_web(BIN / "halweb", "--listen", "127.0.0.2", "--token", "s3cret-token")
    assert url.startswith("http://127.0.0.2:") and url.endswith("/?token=s3cret-token")
    with urllib.request.urlopen(url) as r:
        assert r.status == 200
    bare = url.split("?")[0]
    for bad in (bare, bare + "?token=wrong", bare + "ws"):
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(bad)
        assert e.value.code == 403
    with connect(ws_url(url)) as ws:
        assert recv_type(ws, "hello")["type"] == "hello"


@pytest.mark.parametrize(
    "args,message",
    [
        (["--listen", "0.0.0.0"], "--listen 0.0.0.0 opens HAL to the network: give a --token"),
        (["--listen", "127.0.0.2"], "give a --token"),
        (["--listen", "nohost"], "--listen nohost: not an IP address"),
        (["--token", "short"], "--token: at least 8 printable characters"),
        (["--port", "70000"], "port '70000': 0 to 65535"),
        (["nope"], "no pin, signal or parameter named 'nope'"),
    ],
)
def test_bad_server_options(live: LiveHal, args: list[str], message: str) -> None:
    r = live.run(BIN / "halweb", *args)
    assert r.returncode == 1 and message in r.stderr


def test_port_in_use(live: LiveHal) -> None:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    s.listen()
    port = s.getsockname()[1]
    r = live.run(BIN / "halweb", "--port", str(port))
    s.close()
    assert r.returncode == 1 and f"cannot listen on 127.0.0.1:{port}" in r.stderr


def test_client_vanishing_mid_stream(live: LiveHal) -> None:
    """Connections dropped without a closing handshake, while values and a
    scope are streaming: the server goes on serving, HAL is untouched."""
    srv, url = live.start_web(
        BIN / "halscope",
        "--web",
        "-c",
        "siggen.0.sine",
        "--thread",
        "fast",
        "--mode",
        "roll",
        "--rate",
        "50",
    )
    for _ in range(3):
        with connect(ws_url(url)) as ws:
            recv_type(ws, "hello")
            ws.send(json.dumps({"op": "watch", "items": [["pin", "siggen.0.sine"]]}))
            recv_type(ws, "scope_chunk")
            ws.socket.shutdown(socket.SHUT_RDWR)  # the browser tab is gone
            ws.socket.close()
    with connect(ws_url(url)) as ws:
        recv_type(ws, "hello")
        chunk = recv_type(ws, "scope_chunk")
        assert chunk["names"] == ["siggen.0.sine"] and chunk["lost"] == 0
    assert srv.poll() is None, "the server is still running"
    assert live.halcmd("gets", "free").stdout.strip() == "1.5"
    assert "scope.sample" in live.halcmd("show", "thread").stdout


def test_scope_over_the_websocket(live: LiveHal) -> None:
    """Setups from the page: a bad one changes nothing and says why; a
    setup file is parsed by the server; a good one runs and captures."""
    _, url = live.start_web(BIN / "halweb", "--page", "scope")
    with connect(ws_url(url)) as ws:
        recv_type(ws, "hello")
        for setup, message in [
            ({"channels": ["nope"], "thread": "fast"}, "no pin, signal or parameter named 'nope'"),
            ({"channels": ["siggen.0.sine"], "thread": "slow"}, "thread 'slow' does not exist"),
            (
                {"channels": ["siggen.0.sine"], "thread": "fast", "samples": "x"},
                "bad scope setting",
            ),
            (
                {"channels": ["siggen.0.sine"], "thread": "fast", "trigger": "siggen.0.cosine"},
                "the trigger 'siggen.0.cosine' is not one of the channels",
            ),
        ]:
            ws.send(json.dumps({"op": "scope_run", "setup": setup}))
            assert message in str(recv_type(ws, "error")["error"])
        assert "scope_rt" not in live.halcmd("show", "comp").stdout
        text = "thread fast\nsamples 50\nmode single\ntrigger none\nchan pin siggen.0.sine\n"
        ws.send(json.dumps({"op": "scope_load", "text": text}))
        setup = recv_type(ws, "scope_setup")["setup"]
        assert setup["samples"] == 50 and setup["channels"][0]["name"] == "siggen.0.sine"
        ws.send(json.dumps({"op": "scope_load", "text": "samples x\n"}))
        assert recv_type(ws, "error")["error"] == "setup:1: 'x' is not a number"
        ws.send(json.dumps({"op": "scope_run", "setup": setup}))
        cap = recv_type(ws, "scope")
        assert cap["names"] == ["siggen.0.sine"] and len(cap["columns"][0]) == 50
        assert cap["interval"] == 1_000_000 and cap["trigger"] is None
