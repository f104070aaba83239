# SPDX-License-Identifier: GPL-2.0-or-later
"""The web-server options shared by halmeter, halscope, halshow and halweb."""

from __future__ import annotations

import argparse


def add_web_args(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("web page (docs/halweb.md)")
    g.add_argument("--web", action="store_true", help="serve the live page")
    g.add_argument("--listen", default=None, help="ADDR[:PORT] (default 127.0.0.1:8080)")
    g.add_argument("--port", type=int, default=None, help="port (default 8080; 0: any free)")
    g.add_argument("--token", default=None, help="required with --listen off 127.0.0.1")
    g.add_argument("--read-only", action="store_true", help="the page cannot change HAL")
    g.add_argument("--rate", type=float, default=10.0, help="page updates per second")
