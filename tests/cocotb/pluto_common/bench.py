# SPDX-License-Identifier: GPL-2.0-or-later
"""Test-bench helpers shared by the Pluto-P cocotb tests."""

from __future__ import annotations

from typing import Any

from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge

from common.epp import EppHost, EppTiming

CLK_PERIOD_NS = 25  # 40 MHz


def epp_host(
    dut: Any, *, ack_level: int = 1, timing: EppTiming | None = None, strict: bool = True
) -> EppHost:
    """An EPP host on a design with the pluto_epp pin names."""
    host = EppHost(
        d_in=dut.epp_d_i,
        d_out=dut.epp_d_o,
        d_oe=dut.epp_d_oe,
        nwrite=dut.epp_nwrite,
        ndatastr=dut.epp_ndatastr,
        naddrstr=dut.epp_naddrstr,
        nwait=dut.epp_nwait,
        nreset=dut.epp_nreset,
        ack_level=ack_level,
        timing=timing,
        strict=strict,
    )
    host.start()
    return host


async def start_clock_and_reset(dut: Any, cycles: int = 5) -> None:
    Clock(dut.clk, CLK_PERIOD_NS, unit="ns").start()
    dut.rst.value = 1
    await ClockCycles(dut.clk, cycles)
    dut.rst.value = 0
    await RisingEdge(dut.clk)


def pins(out: int, oe: int, width: int) -> int:
    """Pin levels with the board's pull-ups: an undriven pin reads 1."""
    full = (1 << width) - 1
    return (out & oe) | (~oe & full)
