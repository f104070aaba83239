# SPDX-License-Identifier: GPL-2.0-or-later
"""pluto_epp (the Pluto-P EPP front end) through the pin-level EPP host
model, against EppRegModel (spec/pluto.md section 2): address loads and
auto-increment, 16-bit write assembly, 32-bit read snapshots, unaligned and
out-of-range reads, address reads, handshake timing, nReset, and hosts that
misbehave (abandoned strobes, glitches) or a peripheral that cannot answer
(EPP timeout)."""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, Timer

from common.epp import EppHost, EppTiming
from common.runner import SIMULATORS, hdl, run
from pluto_common.bench import epp_host, start_clock_and_reset
from pluto_common.models import EppRegModel


class Core:
    """Stands in for a firmware core: five read registers, a write log."""

    def __init__(self, dut: Any, seed: int = 5) -> None:
        rng = random.Random(seed)
        self.dut = dut
        self.regs = {sel: rng.getrandbits(32) for sel in range(5)}
        self.writes: list[tuple[int, int]] = []
        self.snapshots: list[int] = []
        dut.rd_data.value = 0
        dut.rd_hit.value = 0
        cocotb.start_soon(self._serve())
        cocotb.start_soon(self._watch())

    async def _serve(self) -> None:
        # rd_sel changes on rising edges; present its register by the falling edge.
        while True:
            await FallingEdge(self.dut.clk)
            try:
                sel = int(self.dut.rd_sel.value)
            except ValueError:
                continue
            self.dut.rd_hit.value = int(sel in self.regs)
            self.dut.rd_data.value = self.regs.get(sel, 0xDEADBEEF)

    async def _watch(self) -> None:
        while True:
            await RisingEdge(self.dut.clk)
            if str(self.dut.wr_stb.value) == "1":
                self.writes.append((int(self.dut.wr_addr.value), int(self.dut.wr_data.value)))
            if str(self.dut.rd_stb.value) == "1":
                self.snapshots.append(int(self.dut.rd_sel.value))


async def setup(dut: Any, **kw: Any) -> tuple[EppHost, Core, EppRegModel]:
    kw.setdefault("ack_level", int(dut.ACK_LEVEL.value))
    host = epp_host(dut, **kw)
    core = Core(dut)
    await start_clock_and_reset(dut)
    await ClockCycles(dut.clk, 4)
    return host, core, EppRegModel(shared_lo=bool(int(dut.SHARED_LO.value)))


async def settle(dut: Any) -> None:
    await ClockCycles(dut.clk, 3)


@cocotb.test()
async def writes_assemble_16bit_words(dut: Any) -> None:
    host, core, model = await setup(dut)
    rng = random.Random(1)
    for _ in range(30):
        a = rng.randrange(32)
        await host.write_addr(a)
        model.addr_write(a)
        data = [rng.getrandbits(8) for _ in range(rng.randrange(1, 9))]
        await host.write_data(data)
        for b in data:
            model.data_write(b)
    await settle(dut)
    assert core.writes == model.writes, f"dut {core.writes[:8]} model {model.writes[:8]}"
    assert len(core.writes) > 20
    assert host.violations == []


@cocotb.test()
async def reads_snapshot_32bit_registers(dut: Any) -> None:
    host, core, model = await setup(dut)
    for sel in range(5):
        await host.write_addr(4 * sel)
        model.addr_write(4 * sel)
        value = await host.inl()
        assert value == core.regs[sel], f"sel {sel}: {value:#x} != {core.regs[sel]:#x}"
    # Burst over several registers, starting at 0, wrapping past 31 to 0.
    await host.write_addr(0)
    model.addr_write(0)
    got = await host.read_data(40)
    want = [model.data_read(core.regs) for _ in range(40)]
    assert got == want
    await settle(dut)
    # Snapshots only for selectors that exist; 5, 6, 7 return the stale buffer.
    assert core.snapshots == [0, 1, 2, 3, 4] + [s for s in model.snapshots]


@cocotb.test()
async def snapshot_is_coherent(dut: Any) -> None:
    """A register that changes during a 4-byte read is returned as it was
    at the first byte."""
    host, core, _ = await setup(dut)
    await host.write_addr(4)
    old = core.regs[1]
    first = await host.read_data(1)
    core.regs[1] = old ^ 0xFFFFFFFF
    rest = await host.read_data(3)
    assert first + rest == list(old.to_bytes(4, "little"))


@cocotb.test()
async def unaligned_and_out_of_range_reads(dut: Any) -> None:
    host, core, model = await setup(dut)
    await host.write_addr(8)
    model.addr_write(8)
    await host.read_data(4)
    for _ in range(4):
        model.data_read(core.regs)
    # Start at address 1 of register 0: stale buffer bytes (register 2's).
    for start in (1, 2, 3, 13, 22):
        await host.write_addr(start)
        model.addr_write(start)
        got = await host.read_data(3)
        want = [model.data_read(core.regs) for _ in range(3)]
        assert got == want, f"start {start}: {got} != {want}"
    # Selector 6 (address 24): no register, stale buffer.
    await host.write_addr(24)
    model.addr_write(24)
    got = await host.read_data(4)
    assert got == [model.data_read(core.regs) for _ in range(4)]
    await settle(dut)
    assert core.snapshots == model.snapshots


@cocotb.test()
async def address_read_and_reset(dut: Any) -> None:
    host, _, _ = await setup(dut)
    await host.write_addr(0x13)
    assert await host.read_addr() == 0x13
    await host.read_data(2)
    assert await host.read_addr() == 0x15
    await host.write_addr(0xFF)  # only bits 4..0 are kept
    assert await host.read_addr() == 0x1F
    await host.read_data(1)
    assert await host.read_addr() == 0x00  # wraps
    await host.write_addr(0x0A)
    await host.pulse_reset()
    assert await host.read_addr() == 0x00


@cocotb.test()
async def handshake_timing(dut: Any) -> None:
    """Acknowledge 4-5 clocks after the strobe (100-125 ns), read data on the
    bus before the acknowledge, cycle ends <= 3 clocks after the strobe."""
    timing = EppTiming(min_ack_ns=90.0, hold_ns=37.0, setup_ns=13.0)
    host, _, _ = await setup(dut, timing=timing)
    await host.write_addr(0)
    await host.read_data(8)
    await host.write_data(list(range(8)))
    for c in host.cycles:
        lat = c.ack_latency_ns
        assert lat is not None and 100.0 <= lat <= 125.0, f"{c}: ack after {lat} ns"
        release = c.t_end - c.t_release
        assert release <= 75.0 + 10.0 + 1e-6, f"{c}: cycle end {release} ns after strobe"
    assert host.violations == []


@cocotb.test()
async def abandoned_strobe_does_not_wedge(dut: Any) -> None:
    """A host that asserts a strobe and walks away (here for 200 us, far past
    any timeout), glitches of every short width, and both strobes at once:
    afterwards an address write re-synchronizes and traffic is exact."""
    host, core, model = await setup(dut, strict=False)
    await host.write_addr(2)
    await host.abandoned_strobe(write=True, value=0x55, hold_ns=200_000.0)
    level = int(dut.ACK_LEVEL.value)
    assert int(dut.epp_nwait.value) == 1 - level, "acknowledge must end with the strobe"
    await host.abandoned_strobe(write=False, hold_ns=50_000.0)
    for width in (3.0, 10.0, 20.0, 30.0, 45.0, 60.0, 80.0):
        await host.strobe_glitch(width, value=0xA5)
        await host.strobe_glitch(width, addr=True, value=0x1F)
    # Both strobes at once: an address cycle.
    dut.epp_nwrite.value = 0
    dut.epp_d_i.value = 0x07
    dut.epp_naddrstr.value = 0
    dut.epp_ndatastr.value = 0
    await Timer(500, unit="ns")
    await host.release_all()
    host.violations.clear()
    host.strict = True
    assert await host.read_addr() == 0x07
    # Well-formed traffic works and matches the model from here.
    core.writes.clear()
    await host.write_addr(0)
    model.addr_write(0)
    for b in [1, 2, 3, 4, 5, 6]:
        await host.write_data(b)
        model.data_write(b)
    await host.write_addr(0)
    model.addr_write(0)
    assert await host.inl() == core.regs[0]
    await settle(dut)
    assert core.writes == model.writes


@cocotb.test()
async def timeout_when_peripheral_is_held_in_reset(dut: Any) -> None:
    """The port gives up after ~10 us, sets status bit 0, releases the strobe;
    the driver's clear works and the next cycle succeeds."""
    host, core, _ = await setup(dut)
    dut.rst.value = 1
    t0 = cocotb.utils.get_sim_time("ns")
    value = await host.read_data(1)
    dt = cocotb.utils.get_sim_time("ns") - t0
    assert value == [None] and host.status & 1 == 1
    assert 10_000 <= dt < 10_500, f"timeout after {dt} ns"
    cyc = host.cycles[-1]
    await Timer(1, unit="ns")
    assert cyc.timeout and str(dut.epp_ndatastr.value) == "1"
    host.clear_timeout()
    assert host.status == 0
    dut.rst.value = 0
    await ClockCycles(dut.clk, 4)
    await host.write_addr(4)
    assert await host.inl() == core.regs[1]
    assert host.status == 0


@cocotb.test()
async def wrong_polarity_is_detected(dut: Any) -> None:
    """A host expecting the other nWait polarity sees a peripheral that
    never becomes ready: the model reports a timeout, never a fake cycle."""
    level = int(dut.ACK_LEVEL.value)
    host, _, _ = await setup(dut, ack_level=1 - level, strict=False)
    await host.write_addr(3)
    assert host.cycles[-1].timeout and host.status == 1


@pytest.mark.parametrize("sim", SIMULATORS)
@pytest.mark.parametrize("ack_level,shared_lo", [(1, 1), (0, 0)])
def test_pluto_epp(sim: str, ack_level: int, shared_lo: int) -> None:
    run(
        sim=sim,
        toplevel="pluto_epp",
        sources=[hdl("pluto", "pluto_epp.v")],
        test_module="test_pluto_epp",
        test_dir=Path(__file__).parent,
        parameters={"ACK_LEVEL": ack_level, "SHARED_LO": shared_lo},
    )
