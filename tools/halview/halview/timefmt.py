# SPDX-License-Identifier: GPL-2.0-or-later
"""Durations as halcmd's simrun takes them: 1000000, 10ms, 2s, 250us, 40ns."""

from __future__ import annotations

import re

from .halapi import HalError

_UNITS = {"": 1, "ns": 1, "us": 1_000, "ms": 1_000_000, "s": 1_000_000_000}


def parse_ns(text: str) -> int:
    m = re.fullmatch(r"\s*([0-9]+(?:\.[0-9]*)?)\s*(ns|us|ms|s|)\s*", text)
    if not m:
        raise HalError(f"duration '{text}': a number with ns, us, ms or s")
    value = float(m.group(1)) * _UNITS[m.group(2)]
    if value != int(value) or value <= 0:
        raise HalError(f"duration '{text}': must be a positive whole number of ns")
    return int(value)
