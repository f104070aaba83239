# SPDX-License-Identifier: GPL-2.0-or-later
"""Self-test of tests/cocotb/common/epp.py: a Python peripheral behind a
pass-through fixture answers EPP cycles correctly, slowly, never, or in
ways that break the handshake; the host model must complete good cycles
with the right bytes and timing and flag every bad one."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.triggers import Timer

from common.epp import CycleKind, EppHost, EppProtocolError, EppTiming
from common.runner import SIMULATORS, run


class FakePeripheral:
    """Watches the host strobes and answers with configurable behaviour."""

    def __init__(
        self,
        dut: Any,
        *,
        ack_ns: float = 100.0,
        release_ns: float = 50.0,
        mode: str = "good",
        read_value: int = 0x5A,
    ) -> None:
        self.dut = dut
        self.ack_ns = ack_ns
        self.release_ns = release_ns
        self.mode = mode
        self.read_value = read_value
        self.seen: list[tuple[str, int]] = []
        dut.p_d_o.value = 0
        dut.p_d_oe.value = 0
        dut.p_nwait.value = 0
        cocotb.start_soon(self._run())

    async def _run(self) -> None:
        dut = self.dut
        while True:
            await Timer(1, unit="ns")
            try:
                strobe_a = int(dut.epp_naddrstr.value) == 0
                strobe_d = int(dut.epp_ndatastr.value) == 0
            except ValueError:  # inputs not driven yet
                continue
            if not (strobe_a or strobe_d):
                continue
            write = int(dut.epp_nwrite.value) == 0
            kind = ("A" if strobe_a else "D") + ("w" if write else "r")
            self.seen.append((kind, int(dut.epp_d_i.value) if write else -1))
            if self.mode == "mute":
                await self._wait_release()
                continue
            if not write and self.mode != "no_drive":
                dut.p_d_o.value = self.read_value
                dut.p_d_oe.value = 1
            await Timer(int(self.ack_ns * 1000), unit="ps")
            dut.p_nwait.value = 1
            if self.mode == "wobble" and not write:
                await Timer(5, unit="ns")
                dut.p_d_o.value = self.read_value ^ 0xFF
            if self.mode == "drive_on_write" and write:
                dut.p_d_oe.value = 1
            await self._wait_release()
            await Timer(int(self.release_ns * 1000), unit="ps")
            dut.p_d_oe.value = 0
            if self.mode != "stuck":
                dut.p_nwait.value = 0

    async def _wait_release(self) -> None:
        dut = self.dut
        while int(dut.epp_ndatastr.value) == 0 or int(dut.epp_naddrstr.value) == 0:
            await Timer(5, unit="ns")


def host_for(dut: Any, **kw: Any) -> EppHost:
    h = EppHost(
        d_in=dut.epp_d_i,
        d_out=dut.epp_d_o,
        d_oe=dut.epp_d_oe,
        nwrite=dut.epp_nwrite,
        ndatastr=dut.epp_ndatastr,
        naddrstr=dut.epp_naddrstr,
        nwait=dut.epp_nwait,
        nreset=dut.epp_nreset,
        **kw,
    )
    h.start()
    return h


async def settle() -> None:
    await Timer(50, unit="ns")


@cocotb.test()
async def good_cycles(dut: Any) -> None:
    per = FakePeripheral(dut, ack_ns=300.0, read_value=0xC3)
    host = host_for(dut, timing=EppTiming(setup_ns=40.0, hold_ns=30.0))
    await settle()
    await host.write_addr(0x12)
    await host.outl(0x44332211)
    assert await host.inw() == 0xC3C3
    assert await host.read_addr() == 0xC3
    assert per.seen == [
        ("Aw", 0x12),
        ("Dw", 0x11),
        ("Dw", 0x22),
        ("Dw", 0x33),
        ("Dw", 0x44),
        ("Dr", -1),
        ("Dr", -1),
        ("Ar", -1),
    ]
    assert host.trace() == "A(12) W(11) W(22) W(33) W(44) R(c3) R(c3) a(c3)"
    for c in host.cycles:
        assert 300.0 <= (c.ack_latency_ns or 0) <= 306.0, c
        assert not c.timeout
    assert host.status == 0 and host.violations == []
    assert [c.kind for c in host.cycles][:2] == [CycleKind.ADDR_WRITE, CycleKind.DATA_WRITE]


@cocotb.test()
async def pc_pace_is_one_microsecond(dut: Any) -> None:
    FakePeripheral(dut, ack_ns=100.0)
    host = host_for(dut, timing=EppTiming.pc_isa())
    await settle()
    await host.write_data([1, 2, 3])
    for c in host.cycles:
        assert 1000.0 <= c.duration_ns < 1010.0, c
    assert abs(host.bus_time_ns() - 3000.0) < 30.0


@cocotb.test()
async def slow_but_in_time_is_fine(dut: Any) -> None:
    FakePeripheral(dut, ack_ns=9_000.0)
    host = host_for(dut)
    await settle()
    await host.write_addr(1)
    assert host.status == 0 and not host.cycles[-1].timeout


@cocotb.test()
async def no_answer_is_a_timeout(dut: Any) -> None:
    """A peripheral that never acknowledges: status bit 0 after ~10 us, the
    strobe is released, reads return None; clear_timeout clears it."""
    FakePeripheral(dut, mode="mute")
    host = host_for(dut)
    await settle()
    t0 = cocotb.utils.get_sim_time("ns")
    assert await host.read_data(1) == [None]
    dt = cocotb.utils.get_sim_time("ns") - t0
    assert 10_000.0 <= dt <= 10_100.0, dt
    assert host.status == 1 and host.timeout_count == 1
    await Timer(1, unit="ns")
    assert int(dut.epp_ndatastr.value) == 1
    assert await host.inl() == 0xFFFFFFFF  # timed-out bytes read as a floating bus
    host.clear_timeout()
    assert host.status == 0


@cocotb.test()
async def ack_without_driving_is_flagged(dut: Any) -> None:
    FakePeripheral(dut, mode="no_drive")
    host = host_for(dut)
    await settle()
    try:
        await host.read_data(1)
    except EppProtocolError as e:
        assert "does not drive" in str(e)
    else:
        raise AssertionError("a read acknowledged without bus drive was accepted")


@cocotb.test()
async def unstable_read_data_is_flagged(dut: Any) -> None:
    FakePeripheral(dut, mode="wobble")
    host = host_for(dut, strict=False)
    await settle()
    await host.read_data(1)
    assert any("changed while acknowledged" in v for v in host.violations), host.violations


@cocotb.test()
async def contention_is_flagged(dut: Any) -> None:
    FakePeripheral(dut, mode="drive_on_write")
    host = host_for(dut, strict=False)
    await settle()
    await host.write_data(0x33)
    assert any("contention" in v for v in host.violations), host.violations


@cocotb.test()
async def stuck_acknowledge_is_flagged(dut: Any) -> None:
    FakePeripheral(dut, mode="stuck")
    host = host_for(
        dut, strict=False, timing=EppTiming(release_timeout_ns=2_000.0, ready_timeout_ns=2_000.0)
    )
    await settle()
    await host.write_addr(3)
    assert any("holds the acknowledge" in v for v in host.violations), host.violations
    assert host.status == 1
    # The next cycle cannot start: the port times out waiting for "ready".
    host.clear_timeout()
    await host.write_addr(4)
    assert host.status == 1 and host.cycles[-1].timeout


@cocotb.test()
async def too_fast_and_spurious_acks_are_flagged(dut: Any) -> None:
    FakePeripheral(dut, ack_ns=20.0)
    host = host_for(dut, strict=False, timing=EppTiming(min_ack_ns=50.0))
    await settle()
    await host.write_addr(1)
    assert any("faster than" in v for v in host.violations), host.violations
    host.violations.clear()
    dut.p_nwait.value = 1  # acknowledge with no cycle running
    await Timer(100, unit="ns")
    dut.p_nwait.value = 0
    await Timer(10, unit="ns")
    assert any("no cycle is running" in v for v in host.violations), host.violations


@cocotb.test()
async def bad_arguments_are_refused(dut: Any) -> None:
    host = host_for(dut)
    for bad in (-1, 256):
        try:
            await host.write_data(bad)
        except ValueError:
            pass
        else:
            raise AssertionError(f"byte {bad} accepted")
    try:
        await host.outw(0x10000)
    except ValueError:
        pass
    else:
        raise AssertionError("outw accepted a 17-bit value")
    try:
        EppHost(
            d_in=dut.epp_d_i,
            d_out=dut.epp_d_o,
            d_oe=dut.epp_d_oe,
            nwrite=dut.epp_nwrite,
            ndatastr=dut.epp_ndatastr,
            naddrstr=dut.epp_naddrstr,
            nwait=dut.epp_nwait,
            ack_level=2,
        )
    except ValueError:
        pass
    else:
        raise AssertionError("ack_level 2 accepted")
    assert host.cycles == []


@pytest.mark.parametrize("sim", SIMULATORS)
def test_epp_model(sim: str) -> None:
    run(
        sim=sim,
        toplevel="epp_fixture",
        sources=[Path(__file__).parent / "epp_fixture.v"],
        test_module="test_epp_model",
        test_dir=Path(__file__).parent,
    )
