# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2gen: turn one HostMot2 firmware description (board + modules + pin map)
into the Verilog parameters of the generic core, the IDROM image, the .PIN
file and a JSON description.  See docs/hm2gen.md."""

from __future__ import annotations

from .catalog import MODULES, ModuleType
from .model import DescriptionError, Firmware, load_firmware

__all__ = ["MODULES", "ModuleType", "DescriptionError", "Firmware", "load_firmware"]
__version__ = "1.0"
