# SPDX-License-Identifier: GPL-2.0-or-later
"""The HAL core's structure rules (docs/engineering-standards.md), checked:

* tools (halcmd, rtapi_app's client side, halsampler/halstreamer, the Python
  module) read HAL through libhal's API only (hal.h, hal_query.h,
  hal_session.h), never through the shared-memory layout of hal_priv.h;
* files of the HAL core stay under ~800 lines;
* code names no people (no owner tags, no notes to teammates).
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HAL = ROOT / "host" / "hal"
CORE = [HAL / d for d in ("lib", "rtapi", "halcmd", "python", "utils")]
TOOLS = [
    *sorted((HAL / "halcmd").glob("*.[ch]")),
    HAL / "rtapi" / "rtapi_client.c",
    *sorted((HAL / "utils").glob("*.[ch]")),
    *sorted((HAL / "python").glob("*.[ch]")),
]
LAYOUT = re.compile(r'#include "hal_priv\.h"|\bSHMPTR\b|\bSHMOFF\b|\bhal_hdr\b|\bhalpr_find_')


def _sources() -> list[Path]:
    out: list[Path] = []
    for d in CORE:
        out += [p for p in sorted(d.iterdir()) if p.suffix in (".c", ".h", ".py", ".sh")]
    return out


def test_tools_use_the_api_only() -> None:
    assert len(TOOLS) > 8, TOOLS
    bad = [
        f"{p.relative_to(ROOT)}:{n}: {line.strip()}"
        for p in TOOLS
        for n, line in enumerate(p.read_text().splitlines(), 1)
        if LAYOUT.search(line)
    ]
    assert not bad, "tools use the private shared-memory layout:\n" + "\n".join(bad)


def test_files_stay_small() -> None:
    big = [
        f"{p.relative_to(ROOT)}: {n}"
        for p in _sources()
        if (n := len(p.read_text().splitlines())) > 800
    ]
    assert not big, "files over 800 lines:\n" + "\n".join(big)


def test_code_names_no_people() -> None:
    owner = re.compile(r"\b(owner:? h\d|h\d+ owns|owned by h\d|REQUESTS-h\d|h\d+py-)", re.I)
    files = (
        _sources()
        + sorted((ROOT / "tests" / "hal").glob("*.py"))
        + sorted((ROOT / "tests" / "python").rglob("*"))
    )
    bad = [
        f"{p.relative_to(ROOT)}:{n}"
        for p in files
        if p.is_file()
        for n, line in enumerate(p.read_text(errors="replace").splitlines(), 1)
        if owner.search(line)
    ]
    assert not bad, "owner names in code:\n" + "\n".join(bad)
