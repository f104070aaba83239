# SPDX-License-Identifier: GPL-2.0-or-later
"""pluto_servo top, pin level, through the EPP host model replaying the
LinuxCNC pluto_servo driver's per-cycle transactions (spec sections 3, 4,
11): register map, PWM duty and modes on the UP/DN pins, dedicated outputs,
encoders (x4, index latch, polarity, filter, read-once flag, test mode),
inputs word, watchdog bite and recovery, LED, a wedged host."""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, Timer

from common.epp import EppHost
from common.runner import SIMULATORS, hdl, run
from pluto_common.bench import epp_host, pins, start_clock_and_reset
from pluto_common.driver import ServoDriver
from pluto_common.models import PWM_PERIOD, servo_ctrl_word, servo_pwm_word

SOURCES = [
    hdl("pluto", f"{m}.v")
    for m in (
        "pluto_epp",
        "pluto_quad",
        "pluto_pwm_counter",
        "pluto_pwm",
        "pluto_wdt",
        "pluto_servo",
    )
]
OUTS = 19
LED = 18
GRAY = [(0, 0), (1, 0), (1, 1), (0, 1)]


def up_pin(n: int) -> int:
    return 10 + 2 * n


def dn_pin(n: int) -> int:
    return 11 + 2 * n


class InPins:
    """The 20 input pins: IN0-7, QZ0-3 (8-11), QB0-3 (12-15), QA0-3 (16-19)."""

    def __init__(self, dut: Any, value: int = 0) -> None:
        self.dut = dut
        self.value = value
        dut.io_in.value = value

    def set(self, bit: int, level: int) -> None:
        self.value = (self.value & ~(1 << bit)) | (level << bit)
        self.dut.io_in.value = self.value

    def quad(self, ch: int, a: int, b: int) -> None:
        self.set(16 + ch, a)
        self.set(12 + ch, b)


class Board:
    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.inp = InPins(dut)
        self.host: EppHost = epp_host(dut)
        self.drv = ServoDriver(self.host)
        self.phase = [0, 0, 0, 0]

    async def start(self) -> None:
        await start_clock_and_reset(self.dut)
        await ClockCycles(self.dut.clk, 10)

    def pins(self) -> int:
        return pins(int(self.dut.io_out.value), int(self.dut.io_oe.value), OUTS)

    async def move(self, ch: int, steps: int, clocks_per_state: int = 3) -> None:
        """Drive quadrature on QA/QB of channel ch (A leading B = up)."""
        d = 1 if steps > 0 else -1
        for _ in range(abs(steps)):
            self.phase[ch] = (self.phase[ch] + d) % 4
            self.inp.quad(ch, *GRAY[self.phase[ch]])
            await ClockCycles(self.dut.clk, clocks_per_state)

    async def on_clocks(self, clocks: int = PWM_PERIOD) -> list[int]:
        """Clocks each output pin was high during ``clocks`` clocks."""
        acc = [0] * OUTS
        for _ in range(clocks):
            await RisingEdge(self.dut.clk)
            p = self.pins()
            for i in range(OUTS):
                acc[i] += (p >> i) & 1
        return acc


@cocotb.test()
async def driver_write_sets_pwm_and_outputs(dut: Any) -> None:
    b = Board(dut)
    await b.start()
    words = [
        servo_pwm_word(0.25),  # up/down, positive
        servo_pwm_word(-0.5),  # up/down, negative -> pulses on DN1
        servo_pwm_word(-0.75, pwmdir=True),  # pwm+dir, negative -> DN2 high
        servo_pwm_word(0.1, dout_up=True),  # UP3 inverted by dout.16
    ]
    douts = 0b1010011001
    ctrl = servo_ctrl_word(douts, z_polarity=False, watchdog=False, test_encoder=False)
    cycles = await b.drv.write(words, ctrl)
    raw = b"".join(w.to_bytes(2, "little") for w in words) + ctrl.to_bytes(2, "little")
    assert b.host.trace(cycles) == "A(00) " + " ".join(f"W({x:02x})" for x in raw)
    await ClockCycles(dut.clk, 4)
    on = await b.on_clocks()
    duty = [w & 0x7FF for w in words]
    assert duty == [511, 1023, 1535, 204]
    assert (on[up_pin(0)], on[dn_pin(0)]) == (511, 0)
    assert (on[up_pin(1)], on[dn_pin(1)]) == (0, 1023)
    assert (on[up_pin(2)], on[dn_pin(2)]) == (1535, PWM_PERIOD)
    assert (on[up_pin(3)], on[dn_pin(3)]) == (PWM_PERIOD - 204, 0)
    for i in range(10):
        assert on[i] == PWM_PERIOD * ((douts >> i) & 1), f"OUT{i}"
    # LED = UP0 xor DN0.
    assert on[LED] == 511
    # Disabled channels give word 0: both pins low.
    await b.drv.write([0, 0, 0, 0], 0)
    await ClockCycles(dut.clk, 4)
    on = await b.on_clocks(300)
    assert sum(on) == 0


@cocotb.test()
async def pdm_from_pwm0_applies_to_all(dut: Any) -> None:
    b = Board(dut)
    await b.start()
    words = [servo_pwm_word(0.5, is_pdm=True)] + [servo_pwm_word(0.5)] * 3
    await b.drv.write(words, 0)
    await ClockCycles(dut.clk, 4)
    seq: list[list[int]] = [[], [], [], []]
    for _ in range(PWM_PERIOD):
        await RisingEdge(dut.clk)
        p = b.pins()
        for n in range(4):
            seq[n].append((p >> up_pin(n)) & 1)
    for n in range(4):
        assert sum(seq[n]) == 1023
        edges = sum(1 for i in range(1, PWM_PERIOD) if seq[n][i] != seq[n][i - 1])
        assert edges > 100, f"channel {n} not in PDM mode ({edges} edges)"


@cocotb.test()
async def driver_read_encoders_and_inputs(dut: Any) -> None:
    b = Board(dut)
    await b.start()
    rng = random.Random(4)
    moves = [[rng.randrange(-300, 300) for _ in range(3)] for _ in range(4)]
    expect = [0, 0, 0, 0]
    for k in range(3):
        for ch in range(4):
            await b.move(ch, moves[ch][k], clocks_per_state=2)
            expect[ch] += moves[ch][k]
        dins = rng.getrandbits(8)
        for i in range(8):
            b.inp.set(i, (dins >> i) & 1)
        await ClockCycles(dut.clk, 4)
        cycles = await b.drv.read()
        # Spec section 11: A(00) R x4 [status check] R x16.
        assert str(cycles[0]) == "A(00)" and len(cycles) == 21
        assert [c.kind.value for c in cycles[1:]] == ["R"] * 20
        assert b.drv.last_count == expect, f"{b.drv.last_count} != {expect}"
        assert b.drv.din == b.inp.value, f"din {b.drv.din:#x} pins {b.inp.value:#x}"
    # Inputs word layout: QZ at 11..8, QB at 15..12, QA at 19..16.
    b.inp.set(8 + 2, 1)
    b.inp.quad(3, 1, 0)
    await ClockCycles(dut.clk, 4)
    await b.drv.read()
    assert (b.drv.din >> 10) & 1 == 1 and (b.drv.din >> 19) & 1 == 1 and (b.drv.din >> 15) & 1 == 0


@cocotb.test()
async def wrap_is_extended_by_driver(dut: Any) -> None:
    """More than 8191 counts in total, read often enough: the driver's
    extended count keeps going past the 14-bit wrap."""
    b = Board(dut)
    await b.start()
    total = 0
    for _ in range(5):
        await b.move(1, -4000, clocks_per_state=1)
        total -= 4000
        await ClockCycles(dut.clk, 4)
        await b.drv.read()
    assert b.drv.last_count[1] == total


@cocotb.test()
async def index_latch_polarity_and_filter(dut: Any) -> None:
    b = Board(dut)
    await b.start()
    for zpol in (0, 1):
        ctrl = servo_ctrl_word(0, z_polarity=bool(zpol), watchdog=False, test_encoder=False)
        await b.drv.write([0] * 4, ctrl)
        b.inp.set(8 + 2, zpol)  # index idle level
        await ClockCycles(dut.clk, 20)
        await b.drv.read()  # clear any flag the polarity change produced
        await b.move(2, 37)
        # A glitch shorter than the filter (6 clocks = 150 ns): ignored.
        b.inp.set(10, 1 - zpol)
        await Timer(150, unit="ns")
        b.inp.set(10, zpol)
        await ClockCycles(dut.clk, 20)
        await b.drv.read()
        assert not b.drv.indexed[2], f"zpol {zpol}: 150 ns glitch latched"
        # A real index pulse (250 ns) at count 37 + 5.
        await b.move(2, 5)
        at = b.drv.last_count[2] + 5
        b.inp.set(10, 1 - zpol)
        await Timer(250, unit="ns")
        b.inp.set(10, zpol)
        await ClockCycles(dut.clk, 20)
        await b.move(2, 11)
        await b.drv.read()
        assert b.drv.indexed[2], f"zpol {zpol}: index missed"
        assert b.drv.last_index[2] == at
        assert b.drv.last_count[2] == at + 11
        await b.drv.read()
        assert not b.drv.indexed[2], "index seen must be reported once"


@cocotb.test()
async def encoder_test_mode(dut: Any) -> None:
    """Control bit 13: encoder 0 follows OUT0/OUT1 (A/B) and OUT2 (Z)."""
    b = Board(dut)
    await b.start()
    b.inp.quad(0, 0, 0)
    phase = 0
    for _ in range(10):
        phase = (phase + 1) % 4
        a, bb = GRAY[phase]
        await b.drv.write([0] * 4, servo_ctrl_word(a | bb << 1, False, False, True))
    await ClockCycles(dut.clk, 4)
    await b.drv.read()
    assert b.drv.last_count[0] == 10
    await b.drv.write([0] * 4, servo_ctrl_word(a | bb << 1 | 4, False, False, True))
    await ClockCycles(dut.clk, 20)
    await b.drv.write([0] * 4, servo_ctrl_word(a | bb << 1, False, False, True))
    await b.drv.read()
    assert b.drv.indexed[0] and b.drv.last_index[0] == 10


@cocotb.test()
async def watchdog_bites_and_recovers(dut: Any) -> None:
    b = Board(dut)
    await b.start()
    douts = 0x3FF
    words = [servo_pwm_word(0.5)] * 4
    # Without the watchdog bit nothing ever trips.
    await b.drv.write(words, servo_ctrl_word(douts, False, False, False))
    await Timer(7, unit="ms")
    assert int(dut.io_oe.value) == (1 << OUTS) - 1
    # Armed: trips 127 PWM periods after the last pet (6.499 ms).
    await b.drv.write(words, servo_ctrl_word(douts, False, True, False))
    t_pet = cocotb.utils.get_sim_time("ns")
    while int(dut.io_oe.value) != 0:
        await FallingEdge(dut.clk)
    dt = cocotb.utils.get_sim_time("ns") - t_pet
    assert 126 * PWM_PERIOD * 25 <= dt <= 127 * PWM_PERIOD * 25 + 200, f"bite after {dt} ns"
    assert b.pins() == (1 << OUTS) - 1  # all floating: pull-ups
    # EPP still answers while bitten; the next pet restores the outputs.
    await b.drv.read()
    await b.drv.write(words, servo_ctrl_word(douts, False, True, False))
    await ClockCycles(dut.clk, 2)
    assert int(dut.io_oe.value) == (1 << OUTS) - 1
    assert b.pins() & 0x3FF == douts


@cocotb.test()
async def unaligned_read_returns_stale_bytes(dut: Any) -> None:
    """Reads that do not start at a multiple of 4 return the bytes of the
    last snapshot (documented in docs/pluto-servo-firmware.md)."""
    b = Board(dut)
    await b.start()
    for i in range(8):
        b.inp.set(i, (0xA5 >> i) & 1)
    await ClockCycles(dut.clk, 4)
    await b.host.write_addr(16)
    word = await b.host.inl()
    assert word & 0xFF == 0xA5
    await b.move(0, 3)
    await b.host.write_addr(1)
    got = await b.host.read_data(3)
    assert got == list(word.to_bytes(4, "little")[1:])
    # Out-of-range selector 5 (address 20): stale buffer too.
    await b.host.write_addr(20)
    assert await b.host.inl() == word


@cocotb.test()
async def wedged_host_does_not_stop_the_firmware(dut: Any) -> None:
    """A host that dies in the middle of a strobe: PWM keeps running, the
    watchdog still bites; when the host comes back the next driver cycle
    works."""
    b = Board(dut)
    await b.start()
    words = [servo_pwm_word(0.25)] * 4
    await b.drv.write(words, servo_ctrl_word(0x155, False, True, False))
    await b.host.write_addr(0)
    await b.host.abandoned_strobe(write=True, value=0x77)  # never released
    on = await b.on_clocks()
    assert on[up_pin(1)] == 511
    await Timer(7, unit="ms")
    assert int(dut.io_oe.value) == 0, "watchdog must bite while the host is wedged"
    await b.host.release_all()
    b.host.violations.clear()
    await b.drv.write(words, servo_ctrl_word(0x2AA, False, True, False))
    await ClockCycles(dut.clk, 4)
    assert int(dut.io_oe.value) == (1 << OUTS) - 1
    assert b.pins() & 0x3FF == 0x2AA
    await b.drv.read()
    assert b.host.status == 0


@cocotb.test()
async def dead_board_sets_communication_error(dut: Any) -> None:
    """A board that does not answer (held in reset, as while unconfigured):
    the first 32-bit read times out (~10 us per cycle), the driver's
    communication-error path counts it, clears the timeout and stops; the
    write path then sends nothing (spec section 9)."""
    b = Board(dut)
    await b.start()
    dut.rst.value = 1
    cycles = await b.drv.read()
    assert [c.timeout for c in cycles] == [True] * 5  # A(00) + 4 reads, then stop
    assert b.drv.communication_error == 1 and b.host.status == 0
    assert await b.drv.write([servo_pwm_word(0.5)] * 4, 0x3FF) == []
    # Recovery as the user does it: reset the parameter, board alive again.
    dut.rst.value = 0
    await ClockCycles(dut.clk, 10)
    b.drv.communication_error = 0
    await b.drv.write([0] * 4, 0x155)
    await ClockCycles(dut.clk, 4)
    assert b.pins() & 0x3FF == 0x155
    cycles = await b.drv.read()
    assert len(cycles) == 21 and not any(c.timeout for c in cycles)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_pluto_servo(sim: str) -> None:
    run(
        sim=sim,
        toplevel="pluto_servo",
        sources=SOURCES,
        test_module="test_pluto_servo",
        test_dir=Path(__file__).parent,
    )
