# SPDX-License-Identifier: GPL-2.0-or-later
"""Capture output files by extension, checked before anything is armed."""

from __future__ import annotations

import os
from pathlib import Path

from .capture import Capture
from .halapi import HalError

FORMATS = (".csv", ".vcd", ".png", ".svg")


def check_writable(path: str) -> None:
    """Fail now, with the reason, if `path` cannot be written later."""
    ext = Path(path).suffix.lower()
    if ext not in FORMATS:
        raise HalError(f"{path}: unknown capture format '{ext}' (one of {', '.join(FORMATS)})")
    existed = os.path.exists(path)
    try:
        with open(path, "a"):
            pass
    except OSError as e:
        raise HalError(f"cannot write the capture to {path}: {e.strerror}") from None
    if not existed:
        os.unlink(path)


def write(cap: Capture, path: str, title: str) -> None:
    from . import formats

    ext = Path(path).suffix.lower()
    try:
        if ext == ".csv":
            with open(path, "w") as f:
                formats.write_csv(cap, f)
        elif ext == ".vcd":
            with open(path, "w") as f:
                formats.write_vcd(cap, f, title)
        else:
            from .plot import write_plot

            write_plot(cap, path, title)
    except OSError as e:
        raise HalError(f"cannot write the capture to {path}: {e.strerror}") from None
