# SPDX-License-Identifier: GPL-2.0-or-later
"""`loadrt hostmot2; loadrt hm2_pci` under our halrun on a fake sysfs tree
($HM2_PCI_SYSFS_ROOT): the device directories have the kernel's id files,
"resource" table and resourceN files of the BAR size, so the driver finds,
maps (mmap of a regular file) and registers the boards exactly as on real
hardware.  The register images come from the stock pin-map CSVs
(hm2image.py, independent of the C driver); the expected pin report from
the same CSVs and the spec rules.  Messages are LinuxCNC 2.9's hm2_pci
strings (spec §14)."""

from __future__ import annotations

import os
import re
import struct
import subprocess
import sys
import uuid
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from conftest_paths import BUILD, bin_path  # noqa: E402
from hm2image import build_image, expected_pin_lines  # noqa: E402

HALRUN = bin_path("halrun")
RTLIB = BUILD / "lib" / "rtlib"
pytestmark = pytest.mark.requires_build(HALRUN, RTLIB / "hostmot2.so", RTLIB / "hm2_pci.so")

IORESOURCE_IO = 0x100
IORESOURCE_MEM = 0x200
WINDOW = 0x10000

# (vendor, device, subsystem vendor, subsystem device, {bar: (size, is_io)}, window BAR)
PLX9030_5I20 = (
    0x10B5,
    0x9030,
    0x10B5,
    0x3131,
    {0: (0x80, 0), 1: (0x80, 1), 2: (0x10, 1), 5: (WINDOW, 0)},
    5,
)
MESA_5I25 = (0x2718, 0x5125, 0x2718, 0x5125, {0: (WINDOW, 0)}, 0)


def add_device(root: Path, addr: str, kind: tuple, image: bytes | None = None) -> Path:
    vendor, device, svendor, sdevice, bars, window = kind
    d = root / "bus" / "pci" / "devices" / addr
    d.mkdir(parents=True)
    for name, val in (
        ("vendor", vendor),
        ("device", device),
        ("subsystem_vendor", svendor),
        ("subsystem_device", sdevice),
    ):
        (d / name).write_text(f"0x{val:04x}\n")
    lines = []
    for i in range(13):
        if i in bars:
            size, is_io = bars[i]
            start = 0xE000 + 0x100 * i if is_io else 0xF0000000 + 0x100000 * i
            flags = 0x40000 | (IORESOURCE_IO | 1 if is_io else IORESOURCE_MEM)
            lines.append(f"0x{start:016x} 0x{start + size - 1:016x} 0x{flags:016x}")
            (d / f"resource{i}").write_bytes(bytes(size))
        else:
            lines.append("0x" + "0" * 16 + " 0x" + "0" * 16 + " 0x" + "0" * 16)
    (d / "resource").write_text("\n".join(lines) + "\n")
    (d / "enable").write_text("0\n")
    if image is not None:
        (d / f"resource{window}").write_bytes(image)
    return d


def tree(tmp_path: Path) -> Path:
    root = tmp_path / "sys"
    (root / "bus" / "pci" / "devices").mkdir(parents=True)
    return root


def halrun(tmp_path: Path, root: Path, script: str, *opts: str) -> subprocess.CompletedProcess[str]:
    f = tmp_path / "test.hal"
    f.write_text(script)
    env = dict(os.environ)
    env["HAL_INSTANCE"] = "hm2-pci-" + uuid.uuid4().hex[:10]
    env["HM_BUILD"] = str(BUILD)
    env["HM2_PCI_SYSFS_ROOT"] = str(root)
    env["HM2_FIRMWARE_PATH"] = str(tmp_path / "fw")
    return subprocess.run(
        [str(HALRUN), *opts, "-f", str(f)],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
        cwd=tmp_path,
    )


def squeeze(out: str) -> list[str]:
    return [re.sub(" +", " ", x).strip() for x in out.splitlines()]


IMG_5I20 = build_image("5i20", "PIN_SVST8_4_72.csv", "PIN_SVST8_4_72.modules.csv")
IMG_5I25 = build_image("5i25", "PIN_7I76x2_34.csv", "PIN_7I76x2_34.modules.csv")


def test_no_boards(tmp_path: Path) -> None:
    """LinuxCNC 2.9's hm2_pci fails the load with -ENODEV when it found no
    board (its rtapi_app_main, disassembled: num_boards == 0 -> hal_exit,
    return -19); ours does too and also says why."""
    root = tree(tmp_path)
    add_device(root, "0000:00:1f.0", (0x8086, 0x1234, 0x8086, 0x0001, {0: (0x1000, 0)}, 0))
    # a PLX 9030 that belongs to some other product: never touched
    other = add_device(root, "0000:01:00.0", (0x10B5, 0x9030, 0x10B5, 0x9050, PLX9030_5I20[4], 5))
    r = halrun(tmp_path, root, "loadrt hostmot2\nloadrt hm2_pci\nshow comp\n", "-k")
    out = r.stdout + r.stderr
    assert r.returncode != 0, out
    assert "hm2_pci: loading Mesa AnyIO HostMot2 driver version 0.7" in out
    assert f"hm2_pci: no Mesa AnyIO board found in {root}/bus/pci/devices" in out
    assert "hm2_pci: rtapi_app_main: No such device (-19)" in out
    assert "discovered" not in out
    assert "hm2_pci" not in r.stdout.split("Loaded HAL Components:")[-1]
    assert (other / "enable").read_text() == "0\n"


def test_enable_fails(tmp_path: Path) -> None:
    """A device that cannot be enabled fails the load (2.9: failed_errno =
    -ENODEV after 'failed to enable PCI device')."""
    root = tree(tmp_path)
    dev = add_device(root, "0000:01:00.0", MESA_5I25, IMG_5I25)
    (dev / "enable").unlink()
    (dev / "enable").mkdir()
    r = halrun(tmp_path, root, "loadrt hostmot2\nloadrt hm2_pci\n")
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert "hm2_pci: skipping AnyIO board at 0000:01:00.0, failed to enable PCI device" in out
    assert "/0000:01:00.0/enable: Is a directory" in out
    assert "hm2_pci: rtapi_app_main: No such device (-19)" in out


SEED = "num_encoders=1 num_pwmgens=1 num_stepgens=3"


def test_5i20_seed_config(tmp_path: Path) -> None:
    root = tree(tmp_path)
    dev = add_device(root, "0000:02:02.0", PLX9030_5I20, IMG_5I20)
    script = f"""loadrt hostmot2
loadrt hm2_pci config="{SEED}"
loadrt threads name1=servo period1=1000000
addf hm2_5i20.0.read servo
addf hm2_5i20.0.write servo
setp hm2_5i20.0.gpio.012.is_output 1
setp hm2_5i20.0.gpio.012.out 1
simrun 5ms
loadusr -w cp {dev}/resource5 {tmp_path}/snap.bin
getp hm2_5i20.0.watchdog.timeout_ns
show funct hm2_5i20
show pin hm2_5i20.0.encoder.00.count
getp hm2_5i20.0.io_error
"""
    r = halrun(tmp_path, root, script, "-S")
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    lines = squeeze(out)
    i_disc = lines.index("hm2_pci: discovered 5i20 at 0000:02:02.0")
    # no firmware= on a programmable board: the core's warning
    assert any("no firmware specified in config modparam!" in x for x in lines)
    want = [
        re.sub(" +", " ", w).strip()
        for w in expected_pin_lines("5i20", "PIN_SVST8_4_72.csv", {4: 1, 6: 1, 5: 3})
    ]
    assert [x for x in lines if "IO Pin " in x] == want
    i_reg = lines.index("hm2/hm2_5i20.0: registered")
    i_init = lines.index("hm2_5i20.0: initialized AnyIO board at 0000:02:02.0")
    assert i_disc < i_reg < i_init
    for f in ("read", "write", "read_gpio", "write_gpio"):
        assert re.search(rf"\bhm2_5i20\.0\.{f}$", out, re.M), f
    assert "hm2_5i20.0.encoder.00.count" in out
    assert "hm2_5i20.0: dropping AnyIO board at 0000:02:02.0" in out
    # enabled through sysfs as the kernel's pci_enable_device would be,
    # disabled again at unload
    assert (dev / "enable").read_text().startswith("0")
    # write() went through the mapping into the BAR: watchdog timer at
    # 0x0C00 = timeout_ns at ClockLow 33.333333 MHz, - 1 (spec §8),
    # GPIO 12 = port 0 bit 12: DDR (0x1100) and data (0x1000) bit set.
    # (snapshot taken while running: unload makes the watchdog bite)
    bar = (tmp_path / "snap.bin").read_bytes()
    word = lambda a: struct.unpack_from("<I", bar, a)[0]  # noqa: E731
    timeout_ns = int(next(x for x in r.stdout.splitlines() if re.fullmatch(r"\d+", x.strip())))
    assert word(0x0C00) == timeout_ns * 33_333_333 // 1_000_000_000 - 1
    assert word(0x1100) & (1 << 12)
    assert word(0x1000) & (1 << 12)
    # the LAS0BRD..LAS3BRD READY fix-up landed in the PLX register BAR
    ctrl = (dev / "resource1").read_bytes()
    assert all(struct.unpack_from("<I", ctrl, 0x28 + 4 * i)[0] & 2 for i in range(4))


def test_two_boards_config_per_board(tmp_path: Path) -> None:
    """config[i] goes to the i-th board found (bus order); names count per
    board type."""
    root = tree(tmp_path)
    add_device(root, "0000:03:00.0", MESA_5I25, IMG_5I25)
    add_device(root, "0000:01:00.0", MESA_5I25, IMG_5I25)
    add_device(root, "0000:02:00.0", PLX9030_5I20, IMG_5I20)
    r = halrun(
        tmp_path,
        root,
        "loadrt hostmot2\n"
        'loadrt hm2_pci config="num_encoders=0,num_encoders=1 num_stepgens=0,'
        'num_stepgens=1"\nshow pin\n',
    )
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    lines = squeeze(out)
    order = [x for x in lines if x.startswith("hm2_pci: discovered")]
    assert order == [
        "hm2_pci: discovered 5i25 at 0000:01:00.0",
        "hm2_pci: discovered 5i20 at 0000:02:00.0",
        "hm2_pci: discovered 5i25 at 0000:03:00.0",
    ]
    assert "hm2_5i25.0: initialized AnyIO board at 0000:01:00.0" in lines
    assert "hm2_5i20.0: initialized AnyIO board at 0000:02:00.0" in lines
    assert "hm2_5i25.1: initialized AnyIO board at 0000:03:00.0" in lines
    assert "hm2_5i25.0.encoder.00" not in r.stdout
    assert "hm2_5i20.0.encoder.00.count" in r.stdout
    assert "hm2_5i20.0.stepgen.00" not in r.stdout
    assert "hm2_5i25.1.stepgen.00.position-cmd" in r.stdout
    assert "hm2_5i25.1.stepgen.01" not in r.stdout
    # the 5i25's P3 pins carry DB25 numbers (17-pin port)
    assert "hm2/hm2_5i25.0: 34 I/O Pins used:" in lines


def test_more_than_eight_boards(tmp_path: Path) -> None:
    """2.9 handles 8 boards (config[8]); a ninth is skipped, not fatal."""
    root = tree(tmp_path)
    for i in range(9):
        add_device(root, f"0000:0{i + 1}:00.0", MESA_5I25, IMG_5I25)
    r = halrun(tmp_path, root, "loadrt hostmot2\nloadrt hm2_pci\n")
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert "hm2_5i25.7: initialized AnyIO board at 0000:08:00.0" in out
    assert "hm2_pci: skipping AnyIO board at 0000:09:00.0, this driver can only handle 8" in out


def test_bad_image_fails_load(tmp_path: Path) -> None:
    root = tree(tmp_path)
    add_device(root, "0000:01:00.0", MESA_5I25, IMG_5I25)
    dev = add_device(root, "0000:02:00.0", MESA_5I25, bytes(WINDOW))  # FPGA not configured
    r = halrun(tmp_path, root, "loadrt hostmot2\nloadrt hm2_pci\nshow pin\n", "-k")
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert "hm2/hm2_5i25.1: invalid cookie, got 0x00000000, expected 0x55AACAFE" in out
    assert "hm2_5i25.1: board fails HM2 registration" in out
    # the whole load fails (as 2.9): the good board is dropped again
    assert "hm2_5i25.0: dropping AnyIO board at 0000:01:00.0" in out
    assert "Component Pins:" in r.stdout  # show pin ran (-k)
    assert "hm2_5i25.0.gpio" not in r.stdout and "hm2_5i25.1." not in r.stdout
    assert (dev / "enable").read_text().startswith("0")


def test_bad_sysfs_entries(tmp_path: Path) -> None:
    root = tree(tmp_path)
    # window BAR too small, and a device whose ids are unreadable
    add_device(root, "0000:01:00.0", (0x2718, 0x5125, 0x2718, 0x5125, {0: (0x1000, 0)}, 0))
    junk = add_device(root, "0000:02:00.0", MESA_5I25, IMG_5I25)
    (junk / "device").write_text("garbage\n")
    r = halrun(tmp_path, root, "loadrt hostmot2\nloadrt hm2_pci\n")
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert "hm2_5i25.0: could not map in FPGA address space" in out
    assert "0000:01:00.0: BAR 0 is 4096 bytes, need 65536" in out
    assert "discovered 5i25 at 0000:02:00.0" not in out


def test_5i20_firmware_without_fpga(tmp_path: Path) -> None:
    """firmware= on a 5i20 whose PLX registers are plain files (nobody
    answers /INIT): the reset check fails with 2.9's messages, and the
    firmware of another FPGA family is refused before touching the board."""
    root = tree(tmp_path)
    add_device(root, "0000:02:02.0", PLX9030_5I20, IMG_5I20)
    fw = tmp_path / "fw" / "hm2" / "5i20"
    fw.mkdir(parents=True)

    def bit(part: str) -> bytes:
        def small(tag: str, text: str) -> bytes:
            b = text.encode() + b"\0"
            return tag.encode() + struct.pack(">H", len(b)) + b

        body = b"\xaa\x99\x55\x66" * 16
        return (
            bytes([0, 9, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F, 0xF0, 0, 0, 1])
            + small("a", "T.ncd")
            + small("b", part)
            + small("c", "2026/11/24")
            + small("d", "00:00:00")
            + b"e"
            + struct.pack(">I", len(body))
            + body
        )

    (fw / "T.BIT").write_bytes(bit("2s200pq208"))
    (fw / "X.BIT").write_bytes(bit("3s400pq208"))
    r = halrun(tmp_path, root, 'loadrt hostmot2\nloadrt hm2_pci config="firmware=hm2/5i20/T.BIT"\n')
    out = r.stdout + r.stderr
    assert r.returncode != 0
    # all bits read 0 from the file: /INIT and DONE low after /PROGRAM, then
    # /INIT never rises
    assert "hm2_5i20.0: FPGA did not come out of /INIT" in out
    assert "hm2/hm2_5i20.0: failed to reset fpga, aborting hm2_register" in out
    assert "hm2_5i20.0: board fails HM2 registration" in out

    r = halrun(tmp_path, root, 'loadrt hostmot2\nloadrt hm2_pci config="firmware=hm2/5i20/X.BIT"\n')
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert (
        "hm2/hm2_5i20.0: board has FPGA '2s200pq208', but the firmware in hm2/5i20/X.BIT "
        "is for FPGA '3s400pq208'"
    ) in out
    assert "FPGA did not" not in out


HM2PINOUT = bin_path("hm2pinout")


def pinout(root: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env["HM2_PCI_SYSFS_ROOT"] = str(root)
    return subprocess.run(
        [str(HM2PINOUT), *args], capture_output=True, text=True, timeout=60, env=env
    )


@pytest.mark.requires_build(HM2PINOUT)
def test_hm2pinout_pci_source(tmp_path: Path) -> None:
    root = tree(tmp_path)
    add_device(root, "0000:01:00.0", (0x8086, 0x1234, 0x8086, 0x0001, {0: (0x1000, 0)}, 0))
    dev = add_device(root, "0000:02:02.0", PLX9030_5I20, IMG_5I20)
    add_device(root, "0000:03:00.0", MESA_5I25, IMG_5I25)
    img = tmp_path / "5i20.img"
    img.write_bytes(IMG_5I20)

    r = pinout(root, "-c", SEED, "pci:0000:02:02.0")
    assert r.returncode == 0, r.stderr
    want = [
        re.sub(" +", " ", w).strip()
        for w in expected_pin_lines("5i20", "PIN_SVST8_4_72.csv", {4: 1, 6: 1, 5: 3})
    ]
    assert [x for x in squeeze(r.stdout) if "IO Pin " in x] == want
    # the same report as from the image file itself; short address form
    r2 = pinout(root, "-c", SEED, "pci:02:02.0")
    assert r2.stdout == r.stdout
    assert pinout(root, "-c", SEED, f"image:{img}").stdout == r.stdout
    # read-only: nothing programmed, enable restored
    assert (dev / "enable").read_text().startswith("0")

    # first board found, here the 5i20; -n sets the name's index
    r = pinout(root, "-n", "1", "pci:")
    assert r.returncode == 0, r.stderr
    assert "hm2/hm2_5i20.1: 72 I/O Pins used:" in r.stdout
    r = pinout(root, "pci:0000:03:00.0")
    assert "hm2/hm2_5i25.0: 34 I/O Pins used:" in r.stdout

    for addr, msg in (
        (
            "0000:01:00.0",
            "hm2pinout: PCI device 0000:01:00.0 (8086:1234, subsystem "
            "8086:0001) is not a Mesa Anything-I/O board",
        ),
        ("0000:09:00.0", "hm2pinout: no PCI device 0000:09:00.0"),
    ):
        r = pinout(root, f"pci:{addr}")
        assert r.returncode == 1 and msg in r.stderr and r.stdout == ""
    empty = tree(tmp_path / "e")
    r = pinout(empty, "pci:")
    assert r.returncode == 1
    assert "no Mesa Anything-I/O PCI board among the 0 devices in" in r.stderr


GENERATED_5I25 = BUILD / "generated" / "5i25" / "7I76x2" / "7I76x2.idrom.hex"


@pytest.mark.requires_build(GENERATED_5I25, HM2PINOUT)
def test_generated_5i25_firmware_over_pci(tmp_path: Path) -> None:
    """The IDROM hm2gen generated for our 5i25 firmware, placed in a BAR0
    window (ID block of spec §2 + IDROM at 0x400), loads through hm2_pci
    and gives the same pin report as hm2pinout on the .idrom.hex file."""
    mem = bytearray(WINDOW)
    struct.pack_into("<I", mem, 0x100, 0x55AACAFE)
    mem[0x104:0x10C] = b"HOSTMOT2"
    struct.pack_into("<I", mem, 0x10C, 0x400)
    words = [int(x, 16) for x in GENERATED_5I25.read_text().split()]
    for i, w in enumerate(words):
        struct.pack_into("<I", mem, 0x400 + 4 * i, w)
    root = tree(tmp_path)
    add_device(root, "0000:01:00.0", MESA_5I25, bytes(mem))
    cfg = "num_encoders=1 num_stepgens=2"
    ref = subprocess.run(
        [str(HM2PINOUT), "-b", "5i25", "-c", cfg, str(GENERATED_5I25)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert ref.returncode == 0, ref.stderr
    want = [x for x in squeeze(ref.stdout) if "IO Pin " in x]
    assert len(want) == 34
    r = halrun(
        tmp_path,
        root,
        f'loadrt hostmot2\nloadrt hm2_pci config="{cfg}"\n' "show pin hm2_5i25.0.stepgen\n",
    )
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert [x for x in squeeze(out) if "IO Pin " in x] == want
    assert "hm2_5i25.0.stepgen.01.position-cmd" in r.stdout
    assert "hm2_5i25.0.stepgen.02" not in r.stdout
