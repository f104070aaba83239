# SPDX-License-Identifier: GPL-2.0-or-later
"""halweb: the live web page of halmeter, halscope and halshow (docs/halweb.md).

Listens on 127.0.0.1:8080 by default and prints the URL.  Another address
(--listen) needs --token: nobody on the network may change HAL without it;
--read-only refuses every change.
"""

from __future__ import annotations

import argparse
import asyncio
import ipaddress
import signal
import sys

from . import halapi, model
from .capture import ScopeConfig
from .halapi import HalError
from .session import SessionComponent
from .webargs import add_web_args
from .webserver import Options, Server

LOCAL = ("127.0.0.1", "::1", "localhost")


def parse_listen(listen: str | None, port: int | None) -> tuple[str, int]:
    host, p = "127.0.0.1", 8080
    if listen:
        text = listen
        if text.startswith("["):  # [v6]:port
            h, _, rest = text[1:].partition("]")
            host = h
            if rest.startswith(":"):
                p = _port(rest[1:])
        elif text.count(":") == 1:
            h, _, ps = text.partition(":")
            host, p = h or host, _port(ps)
        else:
            host = text
        if host != "localhost":
            try:
                ipaddress.ip_address(host)
            except ValueError:
                raise HalError(f"--listen {listen}: not an IP address") from None
    if port is not None:
        p = _port(str(port))
    return host, p


def _port(text: str) -> int:
    if not text.isdigit() or int(text) > 65535:
        raise HalError(f"port '{text}': 0 to 65535")
    return int(text)


def make_options(
    a: argparse.Namespace,
    page: str,
    watch: list[tuple[int, str]] | None = None,
    scope_cfg: ScopeConfig | None = None,
    fformat: str | None = None,
) -> Options:
    host, port = parse_listen(a.listen, a.port)
    if host not in LOCAL and not a.token:
        raise HalError(
            f"--listen {host} opens HAL to the network: give a --token (the page's URL "
            "then carries it), and consider --read-only"
        )
    if a.token is not None and (len(a.token) < 8 or not a.token.isprintable() or " " in a.token):
        raise HalError("--token: at least 8 printable characters without spaces")
    if a.rate <= 0 or a.rate > 1000:
        raise HalError(f"--rate {a.rate}: more than 0, at most 1000 updates per second")
    return Options(
        host=host,
        port=port,
        token=a.token,
        read_only=a.read_only,
        rate=a.rate,
        page=page,
        watch=watch or [],
        scope_cfg=scope_cfg,
        fformat=fformat,
    )


def url_of(host: str, port: int, token: str | None) -> str:
    h = f"[{host}]" if ":" in host else host
    return f"http://{h}:{port}/" + (f"?token={token}" if token else "")


def serve(opts: Options) -> int:
    server = Server(opts)

    async def main() -> None:
        ready: asyncio.Future[tuple[str, int]] = asyncio.get_running_loop().create_future()
        task = asyncio.ensure_future(server.run(ready))
        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.add_signal_handler(sig, task.cancel)
        done, _ = await asyncio.wait({task, ready}, return_when=asyncio.FIRST_COMPLETED)
        if ready.done():
            host, port = ready.result()
            mode = "read-only" if opts.read_only else "read-write"
            print(f"halweb: {url_of(host, port, opts.token)} ({mode})", flush=True)
        try:
            await task
        except asyncio.CancelledError:
            pass

    try:
        with SessionComponent("halweb"):
            asyncio.run(main())
    except OSError as e:
        raise HalError(f"cannot listen on {opts.host}:{opts.port}: {e.strerror}") from None
    return 0


def serve_from_args(
    a: argparse.Namespace,
    page: str,
    watch: list[tuple[int, str]] | None = None,
    scope_cfg: ScopeConfig | None = None,
    fformat: str | None = None,
) -> int:
    halapi.require_session()
    return serve(make_options(a, page, watch, scope_cfg, fformat))


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="halweb", description="Serve HAL's live web page.")
    p.add_argument("watch", nargs="*", help="items to watch: pin+NAME sig+NAME param+NAME")
    p.add_argument("--page", choices=("show", "meter", "scope"), default="show")
    add_web_args(p)
    return p


def main(argv: list[str] | None = None) -> int:
    a = build_parser().parse_args(argv)
    try:
        halapi.require_session()
        watch = [model.parse_item(w) for w in a.watch]
        return serve(make_options(a, a.page, watch))
    except HalError as e:
        print(f"halweb: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
