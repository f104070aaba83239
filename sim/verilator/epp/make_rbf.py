# SPDX-License-Identifier: GPL-2.0-or-later
"""Write a virtual Pluto-P firmware file (<name>.rbf): the 68-byte image of
sim/verilator/src/fwimage.h for board "pluto", whose design-id field is the
CRC-32 of the firmware name (the board checks it, see pluto_board.cpp).
Usage: make_rbf.py FIRMWARE OUT"""

from __future__ import annotations

import sys
import zlib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "tools" / "vbfw"))
import vbfw  # noqa: E402


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    fw, out = argv[1], Path(argv[2])
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(vbfw.make_image("pluto", fw, zlib.crc32(fw.encode())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
