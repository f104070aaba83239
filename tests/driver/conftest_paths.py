# SPDX-License-Identifier: GPL-2.0-or-later
"""Paths for the driver tests: the build tree is $HM_BUILD (default build/)."""

from __future__ import annotations

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))


def bin_path(name: str) -> Path:
    return BUILD / "bin" / name
