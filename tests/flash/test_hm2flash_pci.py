# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2flash's pci: source on a fake sysfs tree ($HM2_PCI_SYSFS_ROOT, as the
hm2_pci tests build it): the board is found by its PCI ids and its window
mapped; a window without a flash interface behind it (a plain file) gives
the SPI timeout error instead of hanging; no board gives mesaflash's
"No 5I25 board found" style message."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from flashhelpers import hm2flash_binary

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "driver"))
from test_hal_hm2_pci import MESA_5I25, PLX9030_5I20, WINDOW, add_device, tree  # noqa: E402

from flashhelpers import vboard  # noqa: E402


def run(root: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, HM2_PCI_SYSFS_ROOT=str(root))
    return subprocess.run(
        [str(hm2flash_binary()), *args], capture_output=True, text=True, timeout=120, env=env
    )


def test_pci_window_without_flash_interface(tmp_path: Path) -> None:
    root = tree(tmp_path)
    add_device(root, "0000:01:00.0", MESA_5I25, bytes(WINDOW))
    p = run(root, "--device", "5i25", "--addr", "pci:01:00.0")
    assert p.returncode == 1
    assert "timeout waiting for SPI data" in p.stderr
    # the tool wrote /CS high and a byte: nothing else in the window changed
    data = (root / "bus/pci/devices/0000:01:00.0/resource0").read_bytes()
    assert data[:0x70] == bytes(0x70) and data[0x7C:] == bytes(WINDOW - 0x7C)


def test_pci_no_board(tmp_path: Path) -> None:
    root = tree(tmp_path)
    p = run(root, "--device", "5i25", "--addr", "pci:")
    assert p.returncode == 1
    assert "No 5i25 board found (among the 0 PCI devices in" in p.stderr
    add_device(root, "0000:01:00.0", MESA_5I25, bytes(WINDOW))
    p = run(root, "--device", "5i25", "--addr", "pci:02:00.0")
    assert "No 5i25 board found at 02:00.0" in p.stderr


def test_pci_program_5i20_without_fpga(tmp_path: Path) -> None:
    """--program on a PLX 9030 board goes through hm2_pci's reset/program:
    the fake bridge's control register never shows the reset (a card whose
    FPGA does not answer), which hm2_pci reports in LinuxCNC's words."""
    root = tree(tmp_path)
    add_device(root, "0000:01:00.0", PLX9030_5I20)
    bit = str(vboard.firmware_file("5i20", "SVST8_4"))
    p = run(root, "--device", "5i20", "--addr", "pci:", "--program", bit)
    assert p.returncode == 1
    assert "Programming FPGA (PCI bridge configuration port)..." in p.stdout
    assert "FPGA did not reset" in p.stderr or "/INIT" in p.stderr, p.stderr
    assert "programming the FPGA of hm2_5i20.0 failed" in p.stderr
