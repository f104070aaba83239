# SPDX-License-Identifier: GPL-2.0-or-later
"""tests/machines: the example machines end to end (see test_machines.py)."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
