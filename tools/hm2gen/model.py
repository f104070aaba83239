# SPDX-License-Identifier: GPL-2.0-or-later
"""Loading and checking board and firmware descriptions (TOML), and the
derived facts every output is made from: the module descriptor table, the pin
descriptors, the IDROM image and the routing tables of the Verilog core.

Every check raises :class:`DescriptionError` with the file and the reason;
nothing is written when a description is invalid."""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .catalog import (
    INSTANCE_STRIDE0,
    INSTANCE_STRIDE1,
    MODULES,
    REGISTER_STRIDE0,
    REGISTER_STRIDE1,
    ModuleType,
)

IDROM_WORDS = 256
IDROM_OFFSET = 0x400
MD_OFFSET = 0x40
# OffsetToPinDesc per IDROM type (spec section 3): type 2 documents 0x200,
# stock type-3 builds use 0x1C0.
PD_OFFSET = {2: 0x200, 3: 0x1C0}
MAX_IOWIDTH = 144  # firmware limit (spec section 3)
MAX_PORT_WIDTH = 32  # one 32-bit IOPort register per connector
BUSES = ("localbus", "epp")
PIN_STYLES = ("header50", "db25")
DB25_ORDER = (1, 14, 2, 15, 3, 16, 4, 17, 5, 6, 7, 8, 9, 10, 11, 12, 13)
GLOBAL_UNIT = 0x80
NAME_RE = re.compile(r"^[A-Za-z0-9_]+$")


class DescriptionError(ValueError):
    """An invalid board or firmware description."""


# ---------------------------------------------------------------- helpers


def _err(src: Path | str, msg: str) -> DescriptionError:
    return DescriptionError(f"{src}: {msg}")


def _get(table: dict[str, Any], key: str, typ: type, src: Path | str, ctx: str = "") -> Any:
    where = f"{ctx}." if ctx else ""
    if key not in table:
        raise _err(src, f"missing key '{where}{key}'")
    val = table[key]
    if typ is int and isinstance(val, bool):
        raise _err(src, f"'{where}{key}' must be an integer, got {val!r}")
    if not isinstance(val, typ):
        raise _err(src, f"'{where}{key}' must be {typ.__name__}, got {val!r}")
    return val


def _check_keys(table: dict[str, Any], allowed: set[str], src: Path | str, ctx: str) -> None:
    extra = sorted(set(table) - allowed)
    if extra:
        raise _err(src, f"unknown key(s) in {ctx}: {', '.join(extra)}")


def _load_toml(path: Path) -> dict[str, Any]:
    try:
        with path.open("rb") as f:
            return tomllib.load(f)
    except FileNotFoundError:
        raise DescriptionError(f"{path}: file not found") from None
    except tomllib.TOMLDecodeError as e:
        raise DescriptionError(f"{path}: not valid TOML: {e}") from None


def ascii_words(text: str) -> tuple[int, int]:
    """8 characters -> two little-endian 32-bit words."""
    b = text.encode("ascii")
    return int.from_bytes(b[0:4], "little"), int.from_bytes(b[4:8], "little")


# ---------------------------------------------------------------- board


@dataclass(frozen=True)
class Board:
    name: str
    idrom_name: str
    bus: str
    fpga_part: str
    fpga_size: int
    fpga_pins: int
    clock_low: int
    clock_high: int
    connectors: tuple[str, ...]
    port_width: int
    leds: int
    pin_style: str
    source: str

    @property
    def io_ports(self) -> int:
        return len(self.connectors)

    @property
    def io_width(self) -> int:
        return self.io_ports * self.port_width

    def connector_pin(self, bit: int) -> int:
        """Physical pin number on the connector of port bit ``bit``."""
        if self.pin_style == "header50":
            return 2 * bit + 1
        return DB25_ORDER[bit]


_BOARD_KEYS = {
    "name",
    "idrom_name",
    "bus",
    "fpga_part",
    "fpga_size",
    "fpga_pins",
    "clock_low",
    "clock_high",
    "connectors",
    "port_width",
    "leds",
    "pin_style",
}


def load_board(path: Path) -> Board:
    d = _load_toml(path)
    _check_keys(d, _BOARD_KEYS, path, "board")
    name = _get(d, "name", str, path)
    idrom_name = _get(d, "idrom_name", str, path)
    if len(idrom_name) != 8 or not idrom_name.isascii() or not idrom_name.isprintable():
        raise _err(path, f"idrom_name must be 8 printable ASCII characters, got {idrom_name!r}")
    bus = _get(d, "bus", str, path)
    if bus not in BUSES:
        raise _err(path, f"bus must be one of {', '.join(BUSES)}, got {bus!r}")
    style = _get(d, "pin_style", str, path)
    if style not in PIN_STYLES:
        raise _err(path, f"pin_style must be one of {', '.join(PIN_STYLES)}, got {style!r}")
    connectors = _get(d, "connectors", list, path)
    if not connectors or not all(isinstance(c, str) and c for c in connectors):
        raise _err(path, "connectors must be a non-empty list of names")
    if len(set(connectors)) != len(connectors):
        raise _err(path, f"connector names must be unique: {connectors}")
    pw = _get(d, "port_width", int, path)
    if not 1 <= pw <= MAX_PORT_WIDTH:
        raise _err(path, f"port_width {pw} out of range 1..{MAX_PORT_WIDTH}")
    if style == "db25" and pw > len(DB25_ORDER):
        raise _err(path, f"pin_style db25 has {len(DB25_ORDER)} I/O pins, port_width is {pw}")
    b = Board(
        name=name,
        idrom_name=idrom_name,
        bus=bus,
        fpga_part=_get(d, "fpga_part", str, path),
        fpga_size=_get(d, "fpga_size", int, path),
        fpga_pins=_get(d, "fpga_pins", int, path),
        clock_low=_get(d, "clock_low", int, path),
        clock_high=_get(d, "clock_high", int, path),
        connectors=tuple(connectors),
        port_width=pw,
        leds=_get(d, "leds", int, path),
        pin_style=style,
        source=str(path),
    )
    for k in ("clock_low", "clock_high"):
        if getattr(b, k) < 1_000_000:
            raise _err(path, f"{k} {getattr(b, k)} Hz is below 1 MHz (the driver rejects it)")
    if b.clock_high < b.clock_low:
        raise _err(path, "clock_high must not be slower than clock_low")
    if b.io_width > MAX_IOWIDTH:
        raise _err(
            path, f"too many pins: {b.io_width} I/O pins, " f"the firmware maximum is {MAX_IOWIDTH}"
        )
    if not 0 <= b.leds <= 32:
        raise _err(path, f"leds {b.leds} out of range 0..32")
    return b


# ---------------------------------------------------------------- firmware


@dataclass(frozen=True)
class ModuleUse:
    """One row of the firmware's module table."""

    mtype: ModuleType
    instances: int
    version: int = -1  # MD version; -1 = the catalog's

    @property
    def implemented(self) -> bool:
        return self.mtype.implemented

    @property
    def md_version(self) -> int:
        return self.mtype.version if self.version < 0 else self.version

    def md_words(self) -> tuple[int, int, int]:
        m = self.mtype
        w0 = (self.instances << 24) | (m.clock_tag << 16) | (self.md_version << 8) | m.gtag
        w1 = (m.strides << 24) | (m.registers << 16) | m.base
        return w0, w1, m.mp_bitmap

    @property
    def register_stride(self) -> int:
        return REGISTER_STRIDE1 if self.mtype.strides & 0x0F else REGISTER_STRIDE0

    @property
    def instance_stride(self) -> int:
        return INSTANCE_STRIDE1 if self.mtype.strides & 0xF0 else INSTANCE_STRIDE0


@dataclass(frozen=True)
class Pin:
    io: int
    port: int
    bit: int
    connector: str
    connector_pin: int
    module: str | None  # None = plain GPIO
    unit: int  # raw SecUnit byte
    signal: str | None
    sec_pin: int  # raw SecPin byte

    @property
    def label(self) -> str:
        return f"{self.connector}-{self.connector_pin:02d}"

    @property
    def sec_tag(self) -> int:
        return MODULES[self.module].gtag if self.module else 0

    @property
    def direction(self) -> str:
        if self.module is None:
            return ""
        return "out" if self.sec_pin & 0x80 else "in"

    @property
    def pd_word(self) -> int:
        prim = MODULES["IOPort"].gtag
        return (prim << 24) | (self.unit << 16) | (self.sec_tag << 8) | self.sec_pin


@dataclass
class Firmware:
    name: str
    board: Board
    idrom_type: int
    modules: list[ModuleUse]
    pins: list[Pin]
    source: str
    stepgen_table_width: int = 2
    notes: list[str] = field(default_factory=list)

    # ---- derived
    def module(self, name: str) -> ModuleUse | None:
        for m in self.modules:
            if m.mtype.name == name:
                return m
        return None

    def count(self, name: str) -> int:
        m = self.module(name)
        return m.instances if m and m.implemented else 0

    @property
    def md_table(self) -> list[ModuleUse]:
        """Module descriptors actually published (implemented modules)."""
        return [m for m in self.modules if m.implemented]

    @property
    def omitted(self) -> list[ModuleUse]:
        return [m for m in self.modules if not m.implemented]

    @property
    def leds(self) -> int:
        return self.board.leds if self.module("LED") else 0

    @property
    def top_module(self) -> str:
        """Verilog/C++ name: board names such as 5i22-1.5 (Mesa's firmware
        directory of a gate-size variant) become 5i22_1_5."""
        return re.sub(r"[^a-z0-9_]", "_", f"hm2_{self.board.name}_{self.name}".lower())

    def idrom(self) -> list[int]:
        b = self.board
        words = [0] * IDROM_WORDS
        lo, hi = ascii_words(b.idrom_name)
        pd_off = PD_OFFSET[self.idrom_type]
        header = [
            self.idrom_type,
            MD_OFFSET,
            pd_off,
            lo,
            hi,
            b.fpga_size,
            b.fpga_pins,
            b.io_ports,
            b.io_width,
            b.port_width,
            b.clock_low,
            b.clock_high,
            INSTANCE_STRIDE0,
            INSTANCE_STRIDE1,
            REGISTER_STRIDE0,
            REGISTER_STRIDE1,
        ]
        words[0:16] = header
        w = MD_OFFSET // 4
        for m in self.md_table:
            words[w : w + 3] = m.md_words()
            w += 3
        # words[w:w+3] stay 0: the GTag-0 terminator.
        p = pd_off // 4
        for pin in self.pins:
            words[p + pin.io] = pin.pd_word
        return words

    # ---- routing tables of the Verilog core (hdl/hostmot2/README.md)
    def module_output_index(self, pin: Pin) -> int:
        """Index into the core's module-output vector for an output pin (0 =
        none: plain GPIO, input, or a module without logic)."""
        if pin.module is None or pin.direction != "out" or not MODULES[pin.module].implemented:
            return 0
        nsg, tw = self.count("StepGen"), self.stepgen_table_width
        npwm = self.count("PWMGen")
        code = pin.sec_pin & 0x7F
        if pin.module == "StepGen":
            return 1 + pin.unit * tw + (code - 1)
        if pin.module == "PWMGen":
            return 1 + nsg * tw + (code - 1) * npwm + pin.unit
        if pin.module == "SSerial" and pin.signal and pin.signal.startswith("TxData"):
            return 1 + nsg * tw + 3 * npwm + pin.unit * self.sserial_channels + (code - 1)
        if pin.module == "SSerial":
            return 0  # TxEn: the channels drive no enable pin (full-duplex RS-422)
        raise DescriptionError(f"{self.source}: no output routing for module {pin.module}")

    @property
    def sserial_channels(self) -> int:
        """Channels per Smart Serial port: the highest TxData/RxData channel
        on any pin + 1 (0 without Smart Serial)."""
        n = 0
        for p in self.pins:
            if p.module == "SSerial" and p.signal and p.signal[:6] in ("TxData", "RxData"):
                n = max(n, (p.sec_pin & 0x0F))
        return n if self.count("SSerial") else 0

    @property
    def sserial_bit_div(self) -> int:
        """ClockLow periods per Smart Serial bit (2.5 MBaud nominal)."""
        return max(4, round(self.board.clock_low / 2_500_000))

    def sserial_rx_src(self) -> list[int]:
        """Per channel (port p, channel c at p*channels + c): RxData pin + 1."""
        nch = self.sserial_channels
        src = [0] * (self.count("SSerial") * nch)
        if not src:
            return src  # no Smart Serial logic in this firmware
        for p in self.pins:
            if p.module == "SSerial" and p.signal and p.signal.startswith("RxData"):
                src[p.unit * nch + (p.sec_pin & 0x0F) - 1] = p.io + 1
        return src

    def alt_src(self) -> list[int]:
        return [self.module_output_index(p) for p in self.pins]

    def encoder_src(self) -> list[list[int]]:
        """Per encoder instance: pin-input indexes (I/O pin + 1, 0 = tied 0)
        of A, B, Index, IndexMask."""
        n = self.count("Encoder")
        src = [[0, 0, 0, 0] for _ in range(n)]
        for p in self.pins:
            if p.module == "Encoder" and p.unit < n and p.signal != "Probe":
                src[p.unit][(p.sec_pin & 0x7F) - 1] = p.io + 1
        return src

    def encoder_probe_src(self) -> list[int]:
        """Per encoder instance: pin-input index (I/O pin + 1, 0 = tied 0)
        of Probe."""
        n = self.count("Encoder")
        src = [0] * n
        for p in self.pins:
            if p.module == "Encoder" and p.unit < n and p.signal == "Probe":
                src[p.unit] = p.io + 1
        return src


_FW_KEYS = {"name", "board", "idrom_type", "modules", "ports", "notes", "based_on"}
# keys a description based on another one may set (the rest comes from it)
_BASED_KEYS = {"based_on", "board", "notes"}
_MOD_KEYS = {"type", "instances", "version"}
_PIN_RE = re.compile(r"^\s*(\w+)\s+(\d+|all)\s+(\w+)\s*$")


def _parse_pin(text: str, src: str, io: int) -> tuple[str, int, str] | None:
    if text.strip().upper() == "GPIO":
        return None
    m = _PIN_RE.match(text)
    if not m:
        raise _err(
            src,
            f"I/O pin {io}: cannot parse {text!r} (expected 'GPIO' or "
            "'<Module> <unit> <Signal>', e.g. 'Encoder 0 A')",
        )
    mod, unit_s, sig = m.groups()
    if mod not in MODULES:
        raise _err(src, f"I/O pin {io}: unknown module {mod!r} (known: {', '.join(MODULES)})")
    mt = MODULES[mod]
    if sig not in mt.signals:
        known = ", ".join(mt.signals) or "none"
        raise _err(src, f"I/O pin {io}: module {mod} has no signal {sig!r} (known: {known})")
    unit = GLOBAL_UNIT if unit_s == "all" else int(unit_s)
    return mod, unit, sig


def based_on_path(path: Path, d: dict[str, Any]) -> Path:
    """The description a ``based_on`` key names (relative to the file)."""
    rel = _get(d, "based_on", str, str(path))
    return (Path(path).parent / rel).resolve()


def _based_on(path: Path, d: dict[str, Any]) -> dict[str, Any]:
    """The same firmware for another board of the same geometry (the 200K
    7i43): the named description with this file's board (and notes)."""
    src = str(path)
    _check_keys(d, _BASED_KEYS, src, "a description with based_on")
    if "board" not in d:
        raise _err(src, "a description with based_on must name its board")
    base_path = based_on_path(path, d)
    base = _load_toml(base_path)
    _check_keys(base, _FW_KEYS, str(base_path), "firmware")
    if "based_on" in base:
        raise _err(src, f"{base_path} is itself based on another description (one level only)")
    merged = {k: v for k, v in base.items()}
    merged.update({k: v for k, v in d.items() if k != "based_on"})
    return merged


def load_firmware(path: Path, boards_dir: Path | None = None) -> Firmware:
    """Load ``path`` (a firmware TOML) and its board from ``boards_dir``
    (default: ../../boards relative to the firmware file)."""
    path = Path(path)
    src = str(path)
    d = _load_toml(path)
    _check_keys(d, _FW_KEYS, src, "firmware")
    if "based_on" in d:
        d = _based_on(path, d)
    name = _get(d, "name", str, src)
    if not NAME_RE.match(name):
        raise _err(src, f"firmware name {name!r} may contain only letters, digits and '_'")
    board_name = _get(d, "board", str, src)
    if boards_dir is None:
        boards_dir = path.resolve().parents[2] / "boards"
    board = load_board(Path(boards_dir) / f"{board_name}.toml")
    idrom_type = d.get("idrom_type", 2)
    if idrom_type not in PD_OFFSET or isinstance(idrom_type, bool):
        raise _err(src, f"idrom_type must be 2 or 3, got {idrom_type!r}")
    notes = d.get("notes", [])
    if not isinstance(notes, list) or not all(isinstance(n, str) for n in notes):
        raise _err(src, "notes must be a list of strings")

    # ---- module table, in descriptor order
    raw_mods = _get(d, "modules", list, src)
    modules: list[ModuleUse] = []
    seen: set[str] = set()
    for i, rm in enumerate(raw_mods):
        if not isinstance(rm, dict):
            raise _err(src, f"modules[{i}] must be a table")
        _check_keys(rm, _MOD_KEYS, src, f"modules[{i}]")
        tname = _get(rm, "type", str, src, f"modules[{i}]")
        if tname not in MODULES:
            raise _err(src, f"modules[{i}]: unknown module {tname!r} (known: {', '.join(MODULES)})")
        if tname in seen:
            raise _err(src, f"modules[{i}]: module {tname} listed twice")
        seen.add(tname)
        mt = MODULES[tname]
        if tname == "IOPort":
            inst = rm.get("instances", board.io_ports)
            if inst != board.io_ports:
                raise _err(
                    src,
                    f"IOPort instances {inst} must equal the board's "
                    f"{board.io_ports} connectors",
                )
        else:
            inst = _get(rm, "instances", int, src, f"modules[{i}]")
        if not isinstance(inst, int) or isinstance(inst, bool) or not 1 <= inst <= mt.max_instances:
            raise _err(src, f"{tname}: instances {inst!r} out of range 1..{mt.max_instances}")
        if tname == "LED" and board.leds == 0:
            raise _err(src, f"LED module on board {board.name}, which has no LEDs")
        version = rm.get("version", mt.version)
        allowed = (mt.version, *mt.alt_versions)
        if isinstance(version, bool) or version not in allowed:
            known = ", ".join(f"0x{v:02X}" for v in allowed)
            raise _err(src, f"{tname}: version {version!r} not implemented (known: {known})")
        modules.append(ModuleUse(mt, inst, version))
    for required in ("Watchdog", "IOPort"):
        if required not in seen:
            raise _err(src, f"module table has no {required} (the driver requires one)")
    if board.bus != "epp" and "TranslationRAM" in seen:
        raise _err(src, "TranslationRAM exists only behind the EPP front end")
    md_slots = (PD_OFFSET[idrom_type] - MD_OFFSET) // 12 - 1  # keep a terminator
    n_md = sum(1 for m in modules if m.implemented)
    if n_md > md_slots:
        raise _err(
            src,
            f"too many modules: {n_md} descriptors, IDROM type {idrom_type} "
            f"has room for {md_slots}",
        )
    counts = {m.mtype.name: m.instances for m in modules}
    versions = {m.mtype.name: m.md_version for m in modules}

    # ---- pins
    ports = _get(d, "ports", list, src)
    if len(ports) != board.io_ports:
        raise _err(
            src,
            f"{len(ports)} ports given, board {board.name} has {board.io_ports} "
            f"connectors ({', '.join(board.connectors)})",
        )
    max_pins = (IDROM_WORDS * 4 - PD_OFFSET[idrom_type]) // 4
    if board.io_width > max_pins:
        raise _err(
            src,
            f"too many pins: {board.io_width} I/O pins do not fit the {max_pins} "
            f"pin descriptors of IDROM type {idrom_type}",
        )
    pins: list[Pin] = []
    used: dict[tuple[str, int, str], int] = {}
    for pi, plist in enumerate(ports):
        if not isinstance(plist, list) or not all(isinstance(s, str) for s in plist):
            raise _err(src, f"ports[{pi}] must be a list of strings")
        if len(plist) > board.port_width:
            raise _err(
                src,
                f"too many pins on port {pi} ({board.connectors[pi]}): "
                f"{len(plist)} given, port width is {board.port_width}",
            )
        if len(plist) < board.port_width:
            raise _err(
                src,
                f"port {pi} ({board.connectors[pi]}) lists {len(plist)} pins, "
                f"port width is {board.port_width} (write 'GPIO' for plain pins)",
            )
        for bit, text in enumerate(plist):
            io = pi * board.port_width + bit
            parsed = _parse_pin(text, src, io)
            con, cpin = board.connectors[pi], board.connector_pin(bit)
            if parsed is None:
                pins.append(Pin(io, pi, bit, con, cpin, None, 0, None, 0))
                continue
            mod, unit, sig = parsed
            if mod not in counts:
                raise _err(src, f"I/O pin {io}: module {mod} is not in the module table")
            if unit != GLOBAL_UNIT and unit >= counts[mod]:
                raise _err(
                    src,
                    f"I/O pin {io}: {mod} unit {unit} does not exist " f"({counts[mod]} instances)",
                )
            if unit == GLOBAL_UNIT and MODULES[mod].implemented:
                raise _err(src, f"I/O pin {io}: shared ('all') pins are not supported for {mod}")
            if mod == "Encoder" and sig == "Probe" and versions[mod] != 0x83:
                raise _err(
                    src,
                    f"I/O pin {io}: Encoder Probe pins need the probe-capable "
                    "encoder (version = 0x83 in its module entry)",
                )
            key = (mod, unit, sig)
            if key in used:
                raise _err(
                    src,
                    f"pin used twice: {mod} {unit_text(unit)} {sig} is on I/O pin "
                    f"{used[key]} and on I/O pin {io}",
                )
            used[key] = io
            pins.append(Pin(io, pi, bit, con, cpin, mod, unit, sig, MODULES[mod].signals[sig]))

    tw = 2
    for p in pins:
        if p.module == "StepGen":
            tw = max(tw, (p.sec_pin & 0x7F))
    return Firmware(
        name=name,
        board=board,
        idrom_type=idrom_type,
        modules=modules,
        pins=pins,
        source=src,
        stepgen_table_width=tw,
        notes=list(notes),
    )


def unit_text(unit: int) -> str:
    return "all" if unit == GLOBAL_UNIT else str(unit)
