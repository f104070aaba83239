# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2gen: generated IDROMs against Mesa's stock pin maps (spec/pinmaps CSVs,
an independent extraction from the Mesa sources), the spec's worked MD
example and board table, the seed's dmesg pin list, consistency between the
four outputs, and clear errors for invalid descriptions."""

from __future__ import annotations

from typing import Any

import csv
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))

from hm2gen import DescriptionError, load_firmware  # noqa: E402
from hm2gen.model import Firmware  # noqa: E402
from hm2gen.emit import write_all  # noqa: E402

HM2 = ROOT / "hdl" / "hostmot2"
# In-repo copies of shared/spec/pinmaps and of the seed's 5i20 printout (a CI
# clone has no ../shared); see tests/data/README.md.
PINMAPS = ROOT / "tests" / "data" / "pinmaps"
SEED = ROOT / "tests" / "data" / "seeds" / "hostmot2-5i20-SVST8_4-pinout.txt"

# (board, firmware, CSV stem, module GTags that have no logic and so no MD)
FIRMWARES = [
    ("5i20", "SVST8_4", "PIN_SVST8_4_72", set()),
    ("5i20", "SV12", "PIN_SV12_72", set()),
    ("7i43", "SVST4_4", "PIN_SVST4_4_48", set()),
    ("7i43", "SV8", "PIN_SV8_48", set()),
    ("5i25", "7I76x2", "PIN_7I76x2_34", set()),
    # the same SVST8_4 pin file covers the other 72-pin boards
    ("5i23", "SVST8_4", "PIN_SVST8_4_72", set()),
    ("4i65", "SVST8_4", "PIN_SVST8_4_72", set()),
    ("4i68", "SVST8_4", "PIN_SVST8_4_72", set()),
]

# Spec section 16 board table (typed here independently of the board files).
BOARDS = {
    "5i20": dict(
        name="MESA5I20",
        size=200,
        pins=208,
        ports=3,
        pw=24,
        lo=33_333_333,
        hi=100_000_000,
        con=["P2", "P3", "P4"],
    ),
    "7i43": dict(
        name="MESA7I43",
        size=400,
        pins=144,
        ports=2,
        pw=24,
        lo=50_000_000,
        hi=100_000_000,
        con=["P4", "P3"],
    ),
    "5i23": dict(
        name="MESA5I23",
        size=400,
        pins=208,
        ports=3,
        pw=24,
        lo=48_000_000,
        hi=96_000_000,
        con=["P2", "P3", "P4"],
    ),
    "4i65": dict(
        name="MESA4I65",
        size=200,
        pins=208,
        ports=3,
        pw=24,
        lo=33_333_333,
        hi=100_000_000,
        con=["P1", "P3", "P4"],
    ),
    "4i68": dict(
        name="MESA4I68",
        size=400,
        pins=208,
        ports=3,
        pw=24,
        lo=48_000_000,
        hi=96_000_000,
        con=["P1", "P2", "P4"],
    ),
    "5i25": dict(
        name="MESA5I25",
        size=9,
        pins=144,
        ports=2,
        pw=17,
        lo=33_333_333,
        hi=200_000_000,
        con=["P3", "P2"],
    ),
}
DB25 = [1, 14, 2, 15, 3, 16, 4, 17, 5, 6, 7, 8, 9, 10, 11, 12, 13]


def docs_top(board: str, name: str) -> str:
    return f"hm2_{board}_{name}".lower()


def fw_path(board: str, name: str) -> Path:
    return HM2 / "firmware" / board / f"{name}.toml"


@pytest.fixture(scope="module")
def generated(tmp_path_factory: pytest.TempPathFactory) -> dict[tuple[str, str], dict]:
    out = tmp_path_factory.mktemp("gen")
    r = subprocess.run(
        [sys.executable, "-m", "hm2gen", "--all", str(HM2), "-o", str(out)],
        cwd=ROOT / "tools",
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    docs = {}
    for board, name, _, _ in FIRMWARES:
        d = out / board / name
        docs[(board, name)] = {
            "dir": d,
            "json": json.loads((d / f"{name}.json").read_text()),
            "hex": [int(x, 16) for x in (d / f"{name}.idrom.hex").read_text().split()],
            "pin": (d / f"{name}.PIN").read_text(),
            "inc": next(d.glob("*_inc.v")).read_text(),
            "top": (d / f"{docs_top(board, name)}.v").read_text(),
        }
    return docs


@pytest.mark.parametrize(
    "board,name,stem,omitted", FIRMWARES, ids=[f"{f[0]}-{f[1]}" for f in FIRMWARES]
)
def test_idrom_matches_stock_csv(
    generated: dict[tuple[str, str], dict[str, Any]], board: str, name: str, stem: str, omitted: Any
) -> None:
    words = generated[(board, name)]["hex"]
    assert len(words) == 256
    rows = list(csv.DictReader((PINMAPS / f"{stem}.csv").open()))
    b = BOARDS[board]
    # header (type 3, as Mesa's builds: PD offset 0x1C0)
    assert words[0:3] == [3, 0x40, 0x1C0]
    assert words[3].to_bytes(4, "little") + words[4].to_bytes(4, "little") == b["name"].encode()
    assert words[5:12] == [
        b["size"],
        b["pins"],
        b["ports"],
        b["ports"] * b["pw"],
        b["pw"],
        b["lo"],
        b["hi"],
    ]
    assert words[12:16] == [4, 64, 256, 256]
    # pin descriptors: every CSV row, then zeros
    pd = words[0x1C0 // 4 :]
    assert len(rows) == b["ports"] * b["pw"]
    for r in rows:
        io = int(r["io_pin"])
        w = pd[io]
        assert w >> 24 == 3, f"pin {io}: primary tag"
        assert (w >> 8) & 0xFF == int(r["sec_tag"]), f"pin {io}: sec tag"
        assert (w >> 16) & 0xFF == int(r["sec_unit"]), f"pin {io}: sec unit"
        assert w & 0xFF == int(r["sec_pin"]), f"pin {io}: sec pin"
        assert io // b["pw"] == int(r["port"]) and io % b["pw"] == int(r["port_bit"])
    assert all(w == 0 for w in pd[len(rows) :])
    # module descriptors: the CSV table minus the documented omissions
    mods = list(csv.DictReader((PINMAPS / f"{stem}.modules.csv").open()))
    expect = []
    for m in mods:
        w0 = (
            (int(m["instances"]) << 24)
            | (int(m["clock_tag"]) << 16)
            | (int(m["version"]) << 8)
            | int(m["gtag"])
        )
        w1 = (
            (int(m["strides_hex"], 16) << 24)
            | (int(m["num_registers"]) << 16)
            | int(m["base_address_hex"], 16)
        )
        expect.append((int(m["gtag"]), [w0, w1, int(m["mp_mask_hex"], 16)]))
    published = [w for g, w in expect if g not in omitted]
    md = words[0x40 // 4 : 0x1C0 // 4]
    for i, w in enumerate(published):
        assert md[3 * i : 3 * i + 3] == w, f"MD {i}"
    assert all(x == 0 for x in md[3 * len(published) :]), "MD table not terminated by zeros"
    # the omitted rows are exactly the documented ones, byte-identical in the JSON
    doc = generated[(board, name)]["json"]
    assert {m["gtag"] for m in doc["omitted_modules"]} == omitted
    for m in doc["omitted_modules"]:
        assert (m["gtag"], m["md_words"]) in expect


def test_spec_worked_md_example(generated: dict[tuple[str, str], dict[str, Any]]) -> None:
    """spec section 4: SVST8_4 on a 5I20."""
    md = generated[("5i20", "SVST8_4")]["hex"][16 : 16 + 21]
    assert md == [
        0x01010002,
        0x00030C00,
        0,
        0x03010003,
        0x00051000,
        0x1F,
        0x08010204,
        0x00053000,
        3,
        0x08020006,
        0x00054000,
        3,
        0x04010205,
        0x000A2000,
        0x1FF,
        0x01010080,
        0x00010200,
        0,
        0,
        0,
        0,
    ]


def test_seed_dmesg_pins(generated: dict[tuple[str, str], dict[str, Any]]) -> None:
    """The seed's 5i20 dmesg pin list: every module pin it prints is the same
    connector pin, module, unit and signal in our SVST8_4."""
    pins = generated[("5i20", "SVST8_4")]["json"]["pins"]
    names = {"Encoder": "Encoder", "PWMGen": "PWMGen", "StepGen": "StepGen"}
    sig = {
        "B": "B",
        "A": "A",
        "Index": "Index",
        "Out0 (PWM or Up)": "Out0",
        "Out1 (Dir or Down)": "Out1",
        "Not-Enable": "NotEnable",
        "Step": "Step",
        "Direction": "Direction",
    }
    pat = re.compile(r"IO Pin (\d{3}) \((P\d-\d\d)\): (\w+) #(\d+), pin (.+?) \((Input|Output)\)")
    seen = 0
    for line in SEED.read_text().splitlines():
        m = pat.search(line)
        if not m:
            continue
        io, label, mod, unit, signal, _ = m.groups()
        p = pins[int(io)]
        assert p["label"] == label
        assert p["sec_module"] == names[mod] and p["sec_unit"] == int(unit)
        if signal != "(unused)":  # 2.3-era driver: stepgen table pins it did not use
            assert p["sec_signal"] == sig[signal], line
        seen += 1
    assert seen >= 10
    assert pins[2]["label"] == "P2-05" and pins[60]["label"] == "P4-25"


@pytest.mark.parametrize(
    "board,name,stem,omitted", FIRMWARES, ids=[f"{f[0]}-{f[1]}" for f in FIRMWARES]
)
def test_outputs_agree(
    generated: dict[tuple[str, str], dict[str, Any]], board: str, name: str, stem: str, omitted: Any
) -> None:
    g = generated[(board, name)]
    doc, words = g["json"], g["hex"]
    b = BOARDS[board]
    assert doc["schema"] == "hm2gen-firmware/1"
    assert doc["idrom"]["words"] == words
    assert doc["id_block"]["words"] == [0x55AACAFE, 0x54534F48, 0x32544F4D, 0x400]
    assert doc["clocks"] == {"low_hz": b["lo"], "high_hz": b["hi"]}
    assert [c["name"] for c in doc["connectors"]] == b["con"]
    for p in doc["pins"]:
        assert words[doc["idrom"]["pd_offset"] // 4 + p["io"]] == p["pd_word"]
        want = DB25[p["bit"]] if b["pw"] == 17 else 2 * p["bit"] + 1
        assert p["label"] == f"{b['con'][p['port']]}-{want:02d}"
    # Verilog include: IDROM literal and ALT_SRC/ENC_SRC agree with the JSON
    inc = g["inc"]
    m = re.search(r"HM2_IDROM = 8192'h([0-9a-f_]+);", inc)
    assert m
    val = int(m.group(1).replace("_", ""), 16)
    assert [(val >> (32 * i)) & 0xFFFFFFFF for i in range(256)] == words
    m = re.search(r"HM2_ALT_SRC = (\d+)'h([0-9a-f_]+);", inc)
    assert m and int(m.group(1)) == 16 * len(doc["pins"])
    alt = int(m.group(2).replace("_", ""), 16)
    for p in doc["pins"]:
        assert (alt >> (16 * p["io"])) & 0xFFFF == p["alt_src"]
        # outputs of implemented modules are routed, GPIO / omitted modules are not
        routed = p["direction"] == "out" and p["sec_tag"] not in omitted
        assert (p["alt_src"] > 0) == routed, p
    # the top's port list is what the JSON tells the virtual board
    ports = re.findall(r"^\s+(input|output)\s+wire\s+(?:\[(\d+):0\])?\s*(\w+)", g["top"], re.M)
    got = [
        {"name": n, "dir": "in" if d == "input" else "out", "width": int(w) + 1 if w else 1}
        for d, w, n in ports
    ]
    assert got == [{k: p[k] for k in ("name", "dir", "width")} for p in doc["verilog"]["ports"]]
    names = [p["name"] for p in got]
    assert ("lb_addr" in names) == (b is not BOARDS["7i43"]) and ("epp_nwait" in names) == (
        b is BOARDS["7i43"]
    )
    assert got[-4:][0]["width"] == len(doc["pins"])
    # .PIN: one line per pin with connector pin, I/O, module, unit, signal
    lines = {
        int(x.split()[1]): x.split()
        for x in g["pin"].splitlines()
        if re.match(r"^\s+\d+\s+\d+\s+IOPort", x)
    }
    assert len(lines) == len(doc["pins"])
    for p in doc["pins"]:
        f = lines[p["io"]]
        assert int(f[0]) == p["connector_pin"]
        if p["sec_module"] is None:
            assert f[3] == "None"
        else:
            assert f[3:6] == [p["sec_module"], str(p["sec_unit"]), p["sec_signal"]]
            assert f[6] == ("(Out)" if p["direction"] == "out" else "(In)")


def test_alt_src_layout(generated: dict[tuple[str, str], dict[str, Any]]) -> None:
    """Module-output vector layout of the core: 0 none, then StepGen bits
    (instance*width+bit), then PWM Out0[], Out1[], NotEnable[]."""
    doc = generated[("5i20", "SVST8_4")]["json"]
    tw = doc["firmware"]["stepgen_table_width"]
    assert tw == 6
    pins = doc["pins"]
    assert pins[48]["alt_src"] == 1 and pins[49]["alt_src"] == 2  # StepGen 0 Step, Dir
    assert pins[71]["alt_src"] == 1 + 3 * tw + 5  # StepGen 3 Table5
    nsg = 4 * tw
    assert pins[7]["alt_src"] == 1 + nsg + 0  # PWM 0 Out0
    assert pins[9]["alt_src"] == 1 + nsg + 8 + 0  # PWM 0 Out1
    assert pins[10]["alt_src"] == 1 + nsg + 16 + 1  # PWM 1 NotEnable
    assert pins[0]["alt_src"] == 0  # encoder input


# ---------------------------------------------------------------- bad input

GOOD = """
name = "T"
board = "5i25"
ports = [
  ["StepGen 0 Step", "StepGen 0 Direction", "Encoder 0 A", "Encoder 0 B", "Encoder 0 Index",
   "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO"],
  ["GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO",
   "GPIO", "GPIO", "GPIO", "GPIO", "GPIO", "GPIO"],
]
[[modules]]
type = "Watchdog"
instances = 1
[[modules]]
type = "IOPort"
[[modules]]
type = "Encoder"
instances = 1
[[modules]]
type = "StepGen"
instances = 1
"""


def _write(tmp_path: Path, text: str) -> Path:
    fw = tmp_path / "firmware" / "x" / "T.toml"
    fw.parent.mkdir(parents=True, exist_ok=True)
    fw.write_text(text)
    return fw


def _load(tmp_path: Path, text: str) -> Firmware:
    return load_firmware(_write(tmp_path, text), HM2 / "boards")


def test_good_description_loads(tmp_path: Path) -> None:
    fw = _load(tmp_path, GOOD)
    assert fw.count("StepGen") == 1 and fw.stepgen_table_width == 2
    assert fw.encoder_src() == [[3, 4, 5, 0]]


BAD = [
    (
        '"Encoder 0 A", "Encoder 0 B", "Encoder 0 Index",\n   "GPIO", "GPIO"',
        '"Encoder 0 A", "Encoder 0 A", "Encoder 0 Index",\n   "GPIO", "GPIO"',
        "pin used twice",
    ),
    ('"StepGen 0 Step"', '"Frobnicator 0 Step"', "unknown module 'Frobnicator'"),
    ('"StepGen 0 Step"', '"StepGen 0 Steep"', "has no signal 'Steep'"),
    ('"StepGen 0 Step"', '"StepGen 3 Step"', "StepGen unit 3 does not exist"),
    ('"StepGen 0 Step"', '"PWMGen 0 Out0"', "module PWMGen is not in the module table"),
    ('"StepGen 0 Step"', '"StepGen zero Step"', "cannot parse"),
    ('"GPIO", "GPIO"],\n]', '"GPIO", "GPIO", "GPIO"],\n]', "too many pins on port 1"),
    ('"GPIO", "GPIO"],\n]', '"GPIO"],\n]', "lists 16 pins, port width is 17"),
    (
        'type = "Watchdog"\ninstances = 1\n',
        'type = "Widget"\ninstances = 1\n',
        "unknown module 'Widget'",
    ),
    ('type = "Watchdog"\ninstances = 1\n', 'type = "LED"\ninstances = 1\n', "has no Watchdog"),
    ('type = "StepGen"\ninstances = 1', 'type = "StepGen"\ninstances = 65', "out of range 1..64"),
    (
        'type = "StepGen"\ninstances = 1',
        'type = "StepGen"\ninstances = 1\n[[modules]]\n' 'type = "StepGen"\ninstances = 1',
        "listed twice",
    ),
    ('board = "5i25"', 'board = "9z99"', "9z99.toml: file not found"),
    ('board = "5i25"', 'board = "5i25"\nidrom_type = 4', "idrom_type must be 2 or 3"),
    ('board = "5i25"', 'board = "5i25"\ncolour = "red"', "unknown key(s) in firmware: colour"),
    ('name = "T"', 'name = "T x"', "may contain only letters"),
    ('name = "T"', 'name = "T', "not valid TOML"),
    (
        'type = "StepGen"\ninstances = 1',
        'type = "StepGen"\ninstances = 1\nversion = 0xC2',
        "StepGen: version 194 not implemented (known: 0x02, 0x42)",
    ),
    (
        'type = "Encoder"\ninstances = 1',
        'type = "Encoder"\ninstances = 1\nversion = true',
        "Encoder: version True not implemented",
    ),
    (
        '"GPIO", "GPIO", "GPIO", "GPIO"',
        '"Encoder 0 Probe", "GPIO", "GPIO", "GPIO"',
        "need the probe",
    ),
]


def test_newer_versions(tmp_path: Path) -> None:
    """version = 0x83 / 0x42 go into the module descriptors; the Probe pin
    (SecPin 0x05) is routed through its own table."""
    text = GOOD.replace(
        '"GPIO", "GPIO", "GPIO", "GPIO"', '"Encoder 0 Probe", "GPIO", "GPIO", "GPIO"', 1
    )
    text = text.replace(
        'type = "Encoder"\ninstances = 1', 'type = "Encoder"\ninstances = 1\nversion = 0x83'
    )
    text = text.replace(
        'type = "StepGen"\ninstances = 1', 'type = "StepGen"\ninstances = 1\nversion = 0x42'
    )
    fw = _load(tmp_path, text)
    words = {m.mtype.name: m.md_words()[0] for m in fw.md_table}
    assert (words["Encoder"] >> 8) & 0xFF == 0x83
    assert (words["StepGen"] >> 8) & 0xFF == 0x42
    assert fw.encoder_src() == [[3, 4, 5, 0]]
    assert fw.encoder_probe_src() == [6]
    probe = [p for p in fw.pins if p.signal == "Probe"]
    assert len(probe) == 1 and probe[0].pd_word & 0xFFFF == 0x0405  # QCount, Probe


@pytest.mark.parametrize("old,new,msg", BAD, ids=[b[2] for b in BAD])
def test_bad_description(tmp_path: Path, old: str, new: str, msg: str) -> None:
    assert old in GOOD
    with pytest.raises(DescriptionError) as e:
        _load(tmp_path, GOOD.replace(old, new, 1))
    assert msg in str(e.value)
    assert str(tmp_path) in str(e.value) or "9z99" in str(e.value)


def test_based_on(tmp_path: Path) -> None:
    """The 200K 7i43's descriptions: the 7i43's firmware, their board's
    FPGASize (spec section 16: 200 / 400) and part, everything else equal."""
    for name in ("SVST4_4", "SV8", "SVST2_4_7I47"):
        big = load_firmware(fw_path("7i43", name))
        small = load_firmware(fw_path("7i43-2", name))
        assert (small.board.name, small.board.fpga_part) == ("7i43-2", "3s200tq144")
        assert small.top_module == f"hm2_7i43_2_{name.lower()}"
        a, b = big.idrom(), small.idrom()
        assert (a[5], b[5]) == (400, 200)
        assert a[:5] + a[6:] == b[:5] + b[6:]
        assert small.alt_src() == big.alt_src() and small.encoder_src() == big.encoder_src()


BASED_BAD = [
    ('board = "5i25"\n', "must name its board"),
    ('board = "5i25"\nports = []\n', "unknown key(s) in a description with based_on: ports"),
    ('board = "5i25"\n', "is itself based on another description"),
    ('board = "5i25"\nidrom_type = 2\n', "unknown key(s) in a description with based_on"),
]


@pytest.mark.parametrize("extra,msg", BASED_BAD, ids=[b[1] for b in BASED_BAD])
def test_based_on_bad(tmp_path: Path, extra: str, msg: str) -> None:
    base = _write(tmp_path, GOOD)
    text = 'based_on = "T.toml"\n' + extra
    if "itself" in msg:  # based on U, which is based on T
        (base.parent / "U.toml").write_text(text)
        text = 'based_on = "U.toml"\n' + extra
    if msg == "must name its board":
        text = 'based_on = "T.toml"\n'
    derived = base.parent / "D.toml"
    derived.write_text(text)
    with pytest.raises(DescriptionError) as e:
        load_firmware(derived, HM2 / "boards")
    assert msg in str(e.value)
    assert str(tmp_path) in str(e.value)


def test_based_on_missing_file(tmp_path: Path) -> None:
    d = tmp_path / "D.toml"
    d.write_text('based_on = "nothere.toml"\nboard = "5i25"\n')
    with pytest.raises(DescriptionError, match="nothere.toml: file not found"):
        load_firmware(d, HM2 / "boards")


def test_too_many_pins_on_board(tmp_path: Path) -> None:
    boards = tmp_path / "boards"
    boards.mkdir()
    text = (HM2 / "boards" / "5i20.toml").read_text()
    seven = '"A", "B", "C", "D", "E", "F", "G"'
    (boards / "big.toml").write_text(
        text.replace('"P2", "P3", "P4"', seven).replace('name = "5i20"', 'name = "big"')
    )
    fw = _write(tmp_path, GOOD.replace('board = "5i25"', 'board = "big"'))
    with pytest.raises(DescriptionError, match="too many pins: 168 I/O pins"):
        load_firmware(fw, boards)


def test_cli_error_writes_nothing(tmp_path: Path) -> None:
    good = _write(tmp_path, GOOD)
    bad = tmp_path / "firmware" / "x" / "U.toml"
    bad.write_text(
        GOOD.replace('name = "T"', 'name = "U"').replace('"StepGen 0 Step"', '"Nope 0 A"')
    )
    out = tmp_path / "out"
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "hm2gen",
            "--boards",
            str(HM2 / "boards"),
            "-o",
            str(out),
            str(good),
            str(bad),
        ],
        cwd=ROOT / "tools",
        capture_output=True,
        text=True,
    )
    assert r.returncode == 1
    assert "hm2gen: error:" in r.stderr and "unknown module 'Nope'" in r.stderr
    assert not out.exists(), "an invalid description must leave no output at all"
    r = subprocess.run(
        [sys.executable, "-m", "hm2gen", "--check", "--boards", str(HM2 / "boards"), str(good)],
        cwd=ROOT / "tools",
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0 and "ok" in r.stdout


def test_idrom_type3_layout(tmp_path: Path) -> None:
    fw = _load(tmp_path, GOOD.replace('board = "5i25"', 'board = "5i25"\nidrom_type = 3'))
    words = fw.idrom()
    assert words[0:3] == [3, 0x40, 0x1C0]
    assert words[0x1C0 // 4] == 0x03000581  # StepGen 0 Step on I/O 0
    d = tmp_path / "o"
    write_all(fw, d)
    assert json.loads((d / "T.json").read_text())["idrom"]["pd_offset"] == 0x1C0


def test_build_outputs_current() -> None:
    """The build (tools/CMakeLists.txt) leaves every firmware's outputs in
    $HM_BUILD/generated/<board>/<name>/, equal to what the descriptions give
    now, and the generated tops pass Verilator's -Wall lint and Icarus -Wall."""
    import os
    import shutil

    gen = Path(os.environ.get("HM_BUILD", str(ROOT / "build"))) / "generated"
    assert gen.is_dir(), f"{gen} not built (run `make build`)"
    for board, name, _, _ in FIRMWARES:
        fw = load_firmware(fw_path(board, name))
        d = gen / board / name
        doc = json.loads((d / f"{name}.json").read_text())
        assert doc["idrom"]["words"] == fw.idrom(), f"{d} is stale"
        assert [int(x, 16) for x in (d / f"{name}.idrom.hex").read_text().split()] == fw.idrom()
        if shutil.which("verilator"):
            top = fw.top_module
            r = subprocess.run(
                [
                    "verilator",
                    "--lint-only",
                    "-Wall",
                    "-Wno-DECLFILENAME",
                    "--top-module",
                    top,
                    "-y",
                    str(HM2),
                    "-y",
                    str(ROOT / "hdl" / "common"),
                    f"-I{d}",
                    str(d / f"{top}.v"),
                ],
                capture_output=True,
                text=True,
            )
            assert r.returncode == 0, r.stdout + r.stderr
        if shutil.which("iverilog"):
            top = fw.top_module
            r = subprocess.run(
                [
                    "iverilog",
                    "-g2005",
                    "-Wall",
                    "-Wno-timescale",
                    "-s",
                    top,
                    "-y",
                    str(HM2),
                    "-y",
                    str(ROOT / "hdl" / "common"),
                    f"-I{d}",
                    "-o",
                    os.devnull,
                    str(d / f"{top}.v"),
                ],
                capture_output=True,
                text=True,
            )
            assert r.returncode == 0 and "warning" not in r.stderr.lower(), r.stderr
