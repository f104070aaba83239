# SPDX-License-Identifier: GPL-2.0-or-later
"""Build HostMot2 register images from the stock pin-map CSVs.

An independent reference for the driver tests: it follows the IDROM layout
of the spec (ID block at 0x100, type-3 IDROM at 0x400, module descriptors at
+0x40, pin descriptors at +0x1C0) and shares no code with the C driver.
"""

from __future__ import annotations

import csv
import struct
from pathlib import Path

# board -> (connectors, port width, clock low, clock high, fpga size, pins)
BOARDS = {
    "5i20": (["P2", "P3", "P4"], 24, 33_333_333, 100_000_000, "MESA5I20"),
    "7i43": (["P4", "P3"], 24, 50_000_000, 100_000_000, "MESA7I43"),
    "5i25": (["P3", "P2"], 17, 33_333_333, 200_000_000, "MESA5I25"),
}
DB25 = [1, 14, 2, 15, 3, 16, 4, 17, 5, 6, 7, 8, 9, 10, 11, 12, 13]


PINMAPS = Path(__file__).resolve().parents[1] / "data" / "pinmaps"


def read_csv(name: str) -> list[dict[str, str]]:
    with open(PINMAPS / name, newline="") as f:
        return list(csv.DictReader(f))


def build_image(board: str, pins_csv: str, modules_csv: str) -> bytes:
    conns, width, clk_lo, clk_hi, bname = BOARDS[board]
    pins = read_csv(pins_csv)
    mods = read_csv(modules_csv)
    mem = bytearray(0x10000)

    def put(addr: int, word: int) -> None:
        mem[addr : addr + 4] = struct.pack("<I", word & 0xFFFFFFFF)

    put(0x100, 0x55AACAFE)
    mem[0x104:0x10C] = b"HOSTMOT2"
    put(0x10C, 0x400)
    header = [
        3,
        0x40,
        0x1C0,
        0,
        0,
        200,
        208,
        len(conns),
        len(pins),
        width,
        clk_lo,
        clk_hi,
        4,
        64,
        256,
        256,
    ]
    for i, w in enumerate(header):
        put(0x400 + 4 * i, w)
    mem[0x40C:0x414] = bname.encode()
    for i, m in enumerate(mods):
        a = 0x440 + 12 * i
        put(
            a,
            int(m["instances"]) << 24
            | int(m["clock_tag"]) << 16
            | int(m["version"]) << 8
            | int(m["gtag"]),
        )
        put(
            a + 4,
            int(m["strides_hex"], 16) << 24
            | int(m["num_registers"]) << 16
            | int(m["base_address_hex"], 16),
        )
        put(a + 8, int(m["mp_mask_hex"], 16))
    for i, p in enumerate(pins):
        put(
            0x5C0 + 4 * i,
            3 << 24 | int(p["sec_unit"]) << 16 | int(p["sec_tag"]) << 8 | int(p["sec_pin"]),
        )
    return bytes(mem)


def connector(board: str, io: int) -> str:
    conns, width, *_ = BOARDS[board]
    bit = io % width
    pin = 2 * bit + 1 if width == 24 else DB25[bit] if width == 17 else io + 1
    return f"{conns[io // width]}-{pin:02d}"


PWM_NAMES = {"Out0": "Out0 (PWM or Up)", "Out1": "Out1 (Dir or Down)", "NotEnable": "Not-Enable"}
FUNC = {4: "Encoder", 5: "StepGen", 6: "PWMGen", 193: "Smart Serial Interface"}
# Smart Serial pins as LinuxCNC's hostmot2 names them: TxDataN -> txN,
# RxDataN -> rxN, TxEnN -> txenN.
SSERIAL_NAMES = {
    **{f"TxData{k}": f"tx{k}" for k in range(8)},
    **{f"RxData{k}": f"rx{k}" for k in range(8)},
    **{f"TxEn{k}": f"txen{k}" for k in range(8)},
}


def expected_pin_lines(
    board: str, pins_csv: str, counts: dict[int, int], stepgen_width: int | None = None
) -> list[str]:
    """The driver's pin report for a config, from the CSV and the spec rules
    (spec §10.5 allocation, §14 line format, seed behaviour for unused
    stepgen pins when stepgen_width is not given)."""
    prefix = f"hm2/hm2_{board}.0: "
    lines = []
    for p in read_csv(pins_csv):
        io = int(p["io_pin"])
        tag, unit, sp = int(p["sec_tag"]), int(p["sec_unit"]), int(p["sec_pin"])
        head = f"{prefix}    IO Pin {io:03d} ({connector(board, io)}):"
        used = tag in FUNC and unit < counts.get(tag, 64 if tag == 193 else 0)
        name = p["sec_pin_name"]
        if tag == 193:
            name = SSERIAL_NAMES[name]
        if tag == 6:
            name = PWM_NAMES[name]
        if tag == 5 and (sp & 0x7F) > 2:
            if stepgen_width is None:
                name = "(unused)"
            elif (sp & 0x7F) > stepgen_width:
                used = False
            else:
                name = name + "Pin"
        if used:
            d = "Output" if sp & 0x80 else "Input"
            lines.append(f"{head} {FUNC[tag]} #{unit}, pin {name} ({d})")
        else:
            lines.append(f"{head} IOPort")
    return lines
