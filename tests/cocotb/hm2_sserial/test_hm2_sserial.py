# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_sserial (one port, two channels) against the register protocol of
spec/hostmot2.md section 9.9, with a pin-level Python model of the remote
(remote_model.py) on channel 0 and nothing on channel 1: local reads,
discovery in normal and setup mode, process data both ways, remote memory
reads and writes, and the faults (no answer = unplugged cable, bad CRC,
doit on a stopped channel), each visible in Data and in the CS register."""

from __future__ import annotations

from typing import Any

from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge

from common.hm2bus import Hm2Bus
from common.runner import SIMULATORS, hdl, run
from remote_model import RemoteModel, serve

DIV = 8
BASE = 0x5A00
CMD, DATA = BASE, BASE + 0x100


def cs(c: int) -> int:
    return BASE + 0x200 + 4 * c


def iface(k: int, c: int) -> int:
    return BASE + 0x300 + 0x100 * k + 4 * c


class Port:
    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.bus = Hm2Bus(dut)

    async def start(self, remote: RemoteModel) -> None:
        cocotb.start_soon(Clock(self.dut.clk, 20, unit="ns").start())
        self.dut.rx.value = 0b11
        self.dut.rst.value = 1
        await ClockCycles(self.dut.clk, 3)
        await FallingEdge(self.dut.clk)
        self.dut.rst.value = 0
        tx0, rx0 = self.dut.tx0, self.dut.rx0
        cocotb.start_soon(serve(self.dut.clk, tx0, rx0, DIV, remote))

    async def command(self, w: int, limit: int = 20000) -> int:
        """Write a command, wait until the Command register reads 0, return Data."""
        await self.bus.write(CMD, w)
        for _ in range(limit // 50):
            if await self.bus.read(CMD) == 0:
                return await self.bus.read(DATA)
            await ClockCycles(self.dut.clk, 50)
        raise AssertionError(f"command {w:#x} never finished")


@cocotb.test()
async def sserial_protocol(dut: Any) -> None:
    r = RemoteModel(memory={0x100 + i: i * 7 & 0xFF for i in range(16)})
    p = Port(dut)
    await p.start(r)
    # local reads: channel count, version, bit divisor
    assert await p.command(0x2000) == 2
    assert await p.command(0x2001) == 1
    assert await p.command(0x2002) == DIV
    # start normal mode on both channels in mode 3: channel 1 has no remote
    await p.bus.write(cs(0), 3)
    await p.bus.write(cs(1), 3)
    assert await p.command(0xA03) == 0b10
    assert r.mode == 3
    assert await p.bus.read(iface(0, 0)) == int.from_bytes(b"7I76", "little")
    assert await p.bus.read(iface(1, 0)) == 0x12345678
    assert await p.bus.read(iface(2, 0)) == 0x0200 << 16 | 0x0100
    st0, st1 = await p.bus.read(cs(0)), await p.bus.read(cs(1))
    assert st0 >> 24 == 24 and (st0 >> 16) & 0xFF == 40 and (st0 >> 14) & 3 == 2, hex(st0)
    assert (st0 >> 8) & 0x1F == 0
    assert (st1 >> 14) & 3 == 0 and (st1 >> 8) & 1 == 1, hex(st1)  # stopped, no answer
    # process data: 24 bits out, 40 bits in
    for out, inp in ((0xABCDEF, 0x12_3456_789A), (0x000001, 0xFF_0000_0001)):
        r.inputs = inp
        r.status = 0x5A
        await p.bus.write(iface(0, 0), out | 0xFF000000)  # bits past out_bits not sent
        assert await p.command(0x1001) == 0
        assert r.outputs == out
        assert await p.bus.read(iface(0, 0)) == inp & 0xFFFFFFFF
        assert await p.bus.read(iface(1, 0)) == inp >> 32
        assert (await p.bus.read(cs(0))) & 0x1FFF == 0x5A
    # doit on the stopped channel 1 fails without touching channel 0
    n = len(r.frames)
    assert await p.command(0x1003) == 0b10
    assert len(r.frames) == n + 1
    # unplugged cable: no answer; plugged again: fine
    r.plugged = False
    assert await p.command(0x1001) == 0b01
    assert (await p.bus.read(cs(0))) >> 8 & 0x1F == 0b00001
    r.plugged = True
    assert await p.command(0x1001) == 0
    # a corrupt answer is a CRC error
    r.corrupt_crc = True
    assert await p.command(0x1001) == 0b01
    assert (await p.bus.read(cs(0))) >> 8 & 0x1F == 0b00010
    r.corrupt_crc = False
    # setup mode: remote memory reads (1..4 bytes) and a write
    assert await p.command(0x800) == 0
    assert (await p.bus.read(cs(0))) >> 14 & 3 == 0
    await p.bus.write(cs(0), 0)
    assert await p.command(0x901) == 0
    assert (await p.bus.read(cs(0))) >> 14 & 3 == 1
    for n_bytes in (1, 2, 4):
        await p.bus.write(cs(0), 0x1000_0000 | (n_bytes - 1) << 24 | 0x104)
        assert await p.command(0x1001) == 0
        want = int.from_bytes(bytes(r.memory[0x104 + i] for i in range(n_bytes)), "little")
        assert await p.bus.read(iface(0, 0)) == want
    await p.bus.write(iface(0, 0), 0xC0FFEE11)
    await p.bus.write(cs(0), 0x2000_0000 | 3 << 24 | 0x300)
    r.status = 0
    assert await p.command(0x1001) == 0
    assert [r.memory[0x300 + i] for i in range(4)] == [0x11, 0xEE, 0xFF, 0xC0]
    # a CS word with an unknown operation is a bad command (no frame sent)
    n = len(r.frames)
    await p.bus.write(cs(0), 0x7000_0000)
    assert await p.command(0x1001) == 0b01
    assert (await p.bus.read(cs(0))) >> 8 & 0x1F == 0b10000
    assert len(r.frames) == n
    # registers of channels past NCHAN and of port 1 read 0
    for a in (cs(2), iface(0, 7), BASE + 0x40, BASE + 0x600):
        await p.bus.read_expect_zero(a)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_sserial(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_sserial_tb",
        sources=[
            Path(__file__).parent / "hm2_sserial_tb.v",
            hdl("hostmot2", "hm2_sserial.v"),
            hdl("hostmot2", "hm2_sserial_chan.v"),
            hdl("hostmot2", "hm2_sserial_uart.v"),
            hdl("common", "sync_ff.v"),
        ],
        test_module="test_hm2_sserial",
        test_dir=Path(__file__).parent,
    )
