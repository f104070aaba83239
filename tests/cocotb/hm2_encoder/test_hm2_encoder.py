# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_encoder_bank at pin level.

Encoder pins are driven asynchronously (times not tied to ClockLow) by
:class:`common.pins.QuadSource`; every pin change is logged.  At the end of
each test the clock-by-clock reference model (encoder_model.py) replays the
logged pin levels as the firmware's synchronizers sampled them, plus the
register writes at the clocks they were taken, and every register read the
test made must match it bit for bit.  Independent checks on top: the count
equals the source's true position, glitches shorter than the filter change
nothing, index latches the count at the index, the timestamp follows
TSDiv."""

from __future__ import annotations

from typing import Any

import random
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, Timer
from cocotb.utils import get_sim_time

from common.hm2bus import Hm2Bus
from common.pins import QuadSource, VectorLog
from common.runner import SIMULATORS, hdl, run
from encoder_model import (
    CCR_ABGATE,
    CCR_ABMASKPOL,
    CCR_CLRIDX,
    CCR_FILTER,
    CCR_IDXPOL,
    CCR_JUSTONCE,
    CCR_LATCHIDX,
    CCR_MASKPOL,
    CCR_PROBE,
    CCR_PROBEPOL,
    CCR_QERR,
    CCR_UPDOWN,
    CCR_USEMASK,
    EncoderBankModel,
)

BASE = 0x3000
PERIOD = 30  # ns, 33.33 MHz ClockLow
CLOCK_LOW = 1e9 / PERIOD
R_COUNT, R_CCR, R_TSDIV, R_TSCOUNT, R_QFILTER = range(5)


def addr(reg: int, inst: int = 0) -> int:
    return BASE + reg * 0x100 + inst * 4


def s16(v: int) -> int:
    v &= 0xFFFF
    return v - 0x10000 if v & 0x8000 else v


class Harness:
    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.num = int(dut.NUM.value)
        self.bus = Hm2Bus(dut)
        self.writes: dict[int, list[tuple[int, int, int]]] = {}
        self.reads: list[tuple[int, int, int, int]] = []  # cycle, reg, inst, value
        self.t_ref = 0.0
        self.logs: list[VectorLog] = []
        self.src: list[QuadSource] = []
        self.vecs: list[_Vec] = []

    async def start(self, idle: int = 0) -> None:
        """Reset with every input pin at ``idle`` (1 = pulled-up, unconnected)."""
        d = self.dut
        for sig in (d.enc_a, d.enc_b, d.enc_idx, d.enc_idxmask, d.enc_probe):
            sig.value = ((1 << self.num) - 1) if idle else 0
        cocotb.start_soon(Clock(d.clk, PERIOD, unit="ns").start())
        d.rst.value = 1
        self.bus.idle()
        await ClockCycles(d.clk, 3)
        await FallingEdge(d.clk)
        d.rst.value = 0
        await RisingEdge(d.clk)
        self.t_ref = get_sim_time("ns")
        pins = (d.enc_a, d.enc_b, d.enc_idx, d.enc_idxmask, d.enc_probe)
        self.logs = [VectorLog(s).start() for s in pins]
        init = ((1 << self.num) - 1) if idle else 0
        self.vecs = [_Vec(x, init) for x in pins]
        # a QuadSource drives its pins to state 00 when made: none for idle-high
        self.src = [] if idle else [_BitSource(self.vecs, i) for i in range(self.num)]
        # pin changes happen off the clock edges: start a little after one
        await Timer(7.321, unit="ns")

    def cycle(self, t: float) -> int:
        c = (t - self.t_ref) / PERIOD
        assert abs(c - round(c)) < 1e-6, f"time {t} is not a ClockLow edge"
        return int(round(c))

    def now_cycle(self) -> int:
        t = get_sim_time("ns")
        return int((t - self.t_ref) // PERIOD)

    async def write(self, reg: int, inst: int, data: int) -> None:
        t = await self.bus.write(addr(reg, inst), data)
        self.writes.setdefault(self.cycle(t), []).append((reg, inst, data))

    async def read(self, reg: int, inst: int = 0) -> int:
        value, t = await self.bus.read_timed(addr(reg, inst))
        self.reads.append((self.cycle(t), reg, inst, value))
        return value

    async def wait(self, cycles: int) -> None:
        """Wait, then step off the clock edge so pin changes never coincide
        with one (the model could not tell which side the firmware saw)."""
        await ClockCycles(self.dut.clk, cycles)
        await Timer(7.321, unit="ns")

    def replay(self, qfilter_reset: int) -> EncoderBankModel:
        end = self.now_cycle()
        model = EncoderBankModel(self.num, qfilter_reset)
        reads: dict[int, list[tuple[int, int, int]]] = {}
        for c, reg, inst, v in self.reads:
            reads.setdefault(c, []).append((reg, inst, v))
        # walk the pin logs alongside the clock edges
        ptr = [0] * len(self.logs)
        level = [lg.v0 for lg in self.logs]
        for c in range(end + 1):
            t_edge = self.t_ref + c * PERIOD
            for n, lg in enumerate(self.logs):
                while ptr[n] < len(lg.changes) and lg.changes[ptr[n]][0] <= t_edge + 1e-4:
                    t_chg, v = lg.changes[ptr[n]]
                    assert abs(t_chg - t_edge) > 1e-4, f"pin change exactly on clock edge {c}"
                    level[n] = v
                    ptr[n] += 1
            pins = [tuple((level[n] >> i) & 1 for n in range(5)) for i in range(self.num)]
            for reg, inst, v in reads.get(c, []):
                want = model.read(reg, inst)
                assert v == want, (
                    f"cycle {c}: read reg {reg} inst {inst} = {v:#010x}, " f"model {want:#010x}"
                )
            model.clock(pins, self.writes.get(c, []))
        return model


class _Vec:
    """Python-side copy of a packed input vector, so several sources can
    change different bits in the same time step (a read of the handle would
    not yet show a write made earlier in that step)."""

    def __init__(self, handle: Any, init: int = 0) -> None:
        self.handle = handle
        self.shadow = init
        handle.value = init

    def set(self, i: int, v: int) -> None:
        self.shadow = (self.shadow & ~(1 << i)) | ((v & 1) << i)
        self.handle.value = self.shadow


class _Bit:
    """A one-bit view of a packed vector with the ``.value`` interface
    :class:`QuadSource` uses."""

    def __init__(self, vec: _Vec, i: int) -> None:
        self.vec, self.i = vec, i

    @property
    def value(self) -> int:
        return (self.vec.shadow >> self.i) & 1

    @value.setter
    def value(self, v: int) -> None:
        self.vec.set(self.i, v)


class _BitSource:
    """A QuadSource on bit i of the bank's packed pin vectors."""

    def __init__(self, vecs: list[_Vec], i: int) -> None:
        self.quad = QuadSource(*(_Bit(v, i) for v in vecs[:4]), seed=11 + i)
        self.probe = _Bit(vecs[4], i)


def qfilter_reset(dut: Any) -> int:
    hz = int(dut.CLOCK_LOW_HZ.value)
    div = (hz + 8_000_000) // 16_000_000
    return div - 2 if div >= 2 else 0xFFF


@cocotb.test()
async def bus_rules(dut: Any) -> None:
    """Register widths, read-only fields, unaddressed reads, the count clear."""
    h = Harness(dut)
    await h.start()
    assert await h.read(R_QFILTER) == qfilter_reset(dut)
    await h.write(R_TSDIV, 0, 0xFFFF1234)
    assert await h.read(R_TSDIV) == 0x1234
    await h.write(R_QFILTER, 0, 0xFFFFFABC)
    assert await h.read(R_QFILTER) == 0xABC
    # CCR: bits 14..3 R/W, 31..16 and 2..0 read-only, 15 write-1-to-clear
    await h.write(R_CCR, 1, 0xFFFF7FFF)
    assert await h.read(R_CCR, 1) == 0x7FF8
    await h.write(R_CCR, 1, 0)
    assert await h.read(R_CCR, 1) == 0
    # Shared registers exist only at instance 0; instances past NUM read 0
    await h.bus.read_expect_zero(addr(R_TSDIV, 1))
    await h.bus.read_expect_zero(addr(R_COUNT, h.num))
    await h.bus.read_expect_zero(addr(R_CCR, 63))
    await h.bus.read_expect_zero(addr(5, 0))
    await h.bus.read_expect_zero(BASE - 0x100)
    await h.bus.read_expect_zero(0x2100)
    await h.write(R_TSDIV, 1, 0x5555)  # alias write ignored
    assert await h.read(R_TSDIV) == 0x1234
    # TSCount runs at ClockLow/(TSDiv+2)
    await h.write(R_TSDIV, 0, 8)
    t0 = await h.read(R_TSCOUNT)
    await h.wait(1000)
    t1 = await h.read(R_TSCOUNT)
    assert abs(((t1 - t0) & 0xFFFF) - 1003 / 10) <= 1, (t0, t1)
    await h.write(R_TSDIV, 0, 0x8000)  # MSb: divide by 1
    t0 = await h.read(R_TSCOUNT)
    t1 = await h.read(R_TSCOUNT)
    assert (t1 - t0) & 0xFFFF == 2  # two clocks per read
    held = await h.bus.check_hold()
    assert held == t1
    h.replay(qfilter_reset(dut))


@cocotb.test()
async def power_up_with_idle_high_inputs(dut: Any) -> None:
    """Pulled-up inputs (A=B=Index=1) at power-up are not a quadrature
    error and not a count: the filter is primed from the pins."""
    h = Harness(dut)
    await h.start(idle=1)
    await h.wait(40)
    for inst in range(h.num):
        ccr = await h.read(R_CCR, inst)
        assert ccr & 0x8000 == 0, f"inst {inst}: QuadError set at power-up (CCR {ccr:#010x})"
        assert ccr & 0x7 == 0x7, f"inst {inst}: filtered A/B/Index not high (CCR {ccr:#010x})"
        assert await h.read(R_COUNT, inst) & 0xFFFF == 0
    # and it still counts afterwards: one forward quadrature cycle from 11
    for a, b in ((0, 1), (0, 0), (1, 0), (1, 1)):
        h.vecs[0].set(0, a)
        h.vecs[1].set(0, b)
        await h.wait(40)
    assert await h.read(R_COUNT, 0) & 0xFFFF == 4
    assert await h.read(R_CCR, 0) & 0x8000 == 0
    h.replay(qfilter_reset(dut))


async def _moves(
    h: Harness,
    inst: int,
    rng: random.Random,
    n: int,
    min_ns: float,
    glitch_ns: float = 0.0,
    glitch_prob: float = 0.0,
) -> None:
    for _ in range(n):
        counts = rng.choice([-1, 1]) * rng.randint(1, 40)
        edge = round(rng.uniform(min_ns, 4 * min_ns), 3)
        await h.src[inst].quad.move(counts, edge, glitch_ns, glitch_prob)


@cocotb.test()
async def model_random(dut: Any) -> None:
    """Random motion on every instance (filter off on 0, on on 1, noise
    shorter than the filter), reads interleaved; exact model match and the
    count equals the true position."""
    h = Harness(dut)
    await h.start()
    await h.write(R_QFILTER, 0, 0xFFF)  # sample every clock
    await h.write(R_TSDIV, 0, 3)
    await h.write(R_CCR, 0, 0)
    await h.write(R_CCR, 1, 1 << CCR_FILTER)
    rng = random.Random(5)
    # filter off: 3 samples; on: 15.  Edges well above that, glitches below.
    tasks = [
        cocotb.start_soon(_moves(h, 0, rng, 12, 8 * PERIOD, 1.5 * PERIOD, 0.3)),
        cocotb.start_soon(_moves(h, 1, rng, 8, 20 * PERIOD, 12 * PERIOD, 0.3)),
    ]
    while not all(t.done() for t in tasks):
        await h.read(R_COUNT, rng.randrange(h.num))
        await h.read(R_CCR, rng.randrange(h.num))
        await h.read(R_TSCOUNT)
        await h.wait(rng.randint(10, 200))
    await h.wait(40)
    counts = [await h.read(R_COUNT, i) for i in range(h.num)]
    ccrs = [await h.read(R_CCR, i) for i in range(h.num)]
    h.replay(qfilter_reset(dut))
    for i in range(h.num):
        src = h.src[i].quad
        assert (
            s16(counts[i]) == src.position
        ), f"instance {i}: count {s16(counts[i])} != {src.position}"
        assert not ccrs[i] & (1 << CCR_QERR), f"instance {i}: quadrature error from filtered noise"
    assert h.src[0].quad.glitches > 5 and h.src[1].quad.glitches > 5


@cocotb.test()
async def filter_rejects_glitches(dut: Any) -> None:
    """A pulse shorter than the filter never reaches the counter; one longer
    than it does.  Filter on: 15 samples, off: 3; with QFilterRate = 2 the
    sample period is 4 clocks."""
    h = Harness(dut)
    await h.start()
    await h.write(R_QFILTER, 0, 2)  # sample every 4 clocks
    sample_ns = 4 * PERIOD
    for filt, n in ((0, 3), (1, 15)):
        await h.write(R_CCR, 0, filt << CCR_FILTER)
        await h.write(R_COUNT, 0, 0)
        await h.wait(80)
        # shorter than n-1 samples: can never reach the end stop
        await h.src[0].quad.glitch("a", (n - 1.5) * sample_ns)
        await h.wait(20 * n)
        assert await h.read(R_COUNT, 0) & 0xFFFF == 0, f"filter {n}: glitch counted"
        # a held level longer than n+1 samples is taken: one count up
        h.src[0].quad.edge(1)
        await Timer((n + 1.5) * sample_ns, unit="ns")
        await h.wait(20)
        assert s16(await h.read(R_COUNT, 0)) == 1, f"filter {n}: real edge lost"
        h.src[0].quad.edge(-1)
        await h.wait(8 * n + 20)
    h.replay(qfilter_reset(dut))


@cocotb.test()
async def quad_error_and_updown(dut: Any) -> None:
    """A and B changing together sets the sticky bit 15 (write 0 keeps it,
    write 1 clears it); up/down mode counts A rising edges with B as
    direction and never flags an error."""
    h = Harness(dut)
    await h.start()
    await h.write(R_QFILTER, 0, 0xFFF)
    q = h.src[0].quad
    q.edge(1)
    await Timer(300, unit="ns")
    # jump two states at once: 10 -> 01
    q.state, q.position = 3, q.position
    q.a.value, q.b.value = 0, 1
    await Timer(300, unit="ns")
    ccr = await h.read(R_CCR, 0)
    assert ccr & (1 << CCR_QERR), f"{ccr:#x}"
    await h.write(R_CCR, 0, 0)
    assert await h.read(R_CCR, 0) & (1 << CCR_QERR), "write 0 cleared the error"
    await h.write(R_CCR, 0, 1 << CCR_QERR)
    assert not await h.read(R_CCR, 0) & (1 << CCR_QERR), "write 1 did not clear"
    # up/down mode
    await h.write(R_CCR, 0, 1 << CCR_UPDOWN)
    await h.write(R_COUNT, 0, 0)
    a, b = q.a, q.b
    for direction, pulses in ((1, 5), (0, 8)):
        b.value = direction
        await Timer(200, unit="ns")
        for _ in range(pulses):
            a.value = 1
            b.value = direction  # B follows A around: must not be an error
            await Timer(150, unit="ns")
            a.value = 0
            await Timer(150, unit="ns")
    await h.wait(10)
    assert s16(await h.read(R_COUNT, 0)) == 5 - 8
    assert not await h.read(R_CCR, 0) & (1 << CCR_QERR)
    # B changing in the same instant as A rises: the step counts with the
    # direction set up before it (B = 1: up), the new B from the next step
    # (spec §20 "up/down count mode": this is the case where two readings of
    # "B gives the direction" differ)
    await h.write(R_COUNT, 0, 0)
    b.value = 0
    await Timer(300, unit="ns")
    for new_b in (1, 1, 1):
        h.vecs[0].shadow = (h.vecs[0].shadow & ~1) | 1
        h.vecs[1].shadow = (h.vecs[1].shadow & ~1) | new_b
        d = h.dut
        d.enc_a.value, d.enc_b.value = h.vecs[0].shadow, h.vecs[1].shadow
        await Timer(300, unit="ns")
        a.value = 0
        await Timer(300, unit="ns")
    await h.wait(10)
    # B 0 -> 1 with the first step (down), then B = 1 (up, up): 1; taking the
    # B after the edge would count 3 -- the 1-vs-3 difference of issue 13
    assert s16(await h.read(R_COUNT, 0)) == -1 + 1 + 1
    h.replay(qfilter_reset(dut))


@cocotb.test()
async def index_features(dut: Any) -> None:
    """Latch on index, clear on index, just-once, index polarity, index
    mask with its polarity, A/B gating; realtime A/B/Index read-back."""
    h = Harness(dut)
    await h.start()
    await h.write(R_QFILTER, 0, 0xFFF)
    q = h.src[0].quad
    await q.move(10, 200)
    # 1. latch on rising index, just once
    await h.write(R_CCR, 0, (1 << CCR_LATCHIDX) | (1 << CCR_JUSTONCE) | (1 << CCR_IDXPOL))
    await q.index_pulse(300)
    await h.wait(10)
    ccr = await h.read(R_CCR, 0)
    assert ccr >> 16 == 10 and not ccr & (1 << CCR_LATCHIDX), f"{ccr:#x}"
    await q.move(5, 200)
    await q.index_pulse(300)  # second index: no latch any more
    await h.wait(10)
    assert await h.read(R_CCR, 0) >> 16 == 10
    # 2. clear on index, active-low index (event on the falling edge)
    q.idx.value = 1
    await Timer(300, unit="ns")
    await h.write(R_CCR, 0, (1 << CCR_CLRIDX) | (1 << CCR_JUSTONCE))
    await q.move(3, 200)
    await q.index_pulse(300, active=0)
    await h.wait(10)
    assert await h.read(R_COUNT, 0) & 0xFFFF == 0
    q.position = 0
    await q.move(-4, 200)
    assert s16(await h.read(R_COUNT, 0)) == -4  # counter wraps below 0
    # 3. index mask: active-high mask required
    q.idx.value = 0
    await h.write(
        R_CCR, 0, (1 << CCR_LATCHIDX) | (1 << CCR_IDXPOL) | (1 << CCR_USEMASK) | (1 << CCR_MASKPOL)
    )
    await q.index_pulse(300)  # mask low: ignored
    await h.wait(10)
    assert await h.read(R_CCR, 0) & (1 << CCR_LATCHIDX), "index passed a closed mask"
    q.mask.value = 1
    await Timer(100, unit="ns")
    await q.index_pulse(300)
    await h.wait(10)
    ccr = await h.read(R_CCR, 0)
    assert s16(ccr >> 16) == -4 and ccr & (1 << CCR_LATCHIDX)  # not just-once: stays set
    # 4. AB gate: index only while A and B are both high
    await q.move(1, 200)  # -3: state from the -4 position
    await h.write(
        R_CCR,
        0,
        (1 << CCR_LATCHIDX)
        | (1 << CCR_IDXPOL)
        | (1 << CCR_ABGATE)
        | (1 << CCR_ABMASKPOL)
        | (1 << CCR_JUSTONCE),
    )
    while q.levels() != (1, 1):
        await q.move(1, 200)
    pos_at = q.position
    await q.index_pulse(300)
    await h.wait(10)
    ccr = await h.read(R_CCR, 0)
    assert s16(ccr >> 16) == pos_at and not ccr & (1 << CCR_LATCHIDX)
    assert ccr & 0x7 == 0b011, f"realtime A/B/Index read-back {ccr & 7:#b}"
    h.replay(qfilter_reset(dut))


@cocotb.test()
async def probe_latch(dut: Any) -> None:
    """Version 0x83 probe input: LatchOnProbe latches the count on the
    filtered probe's active edge (bit 12: 1 rising, 0 falling), JustOnce
    clears bit 13 only; an index event leaves a pending probe latch alone and
    a probe event leaves a pending index latch alone; a probe glitch shorter
    than the filter latches nothing."""
    h = Harness(dut)
    await h.start()
    await h.write(R_QFILTER, 0, 0xFFF)
    q, probe = h.src[1].quad, h.src[1].probe
    once = 1 << CCR_JUSTONCE
    await q.move(7, 200)
    # 1. rising edge, just once
    await h.write(R_CCR, 1, (1 << CCR_PROBE) | (1 << CCR_PROBEPOL) | once)
    probe.value = 1
    await h.wait(20)
    ccr = await h.read(R_CCR, 1)
    assert ccr >> 16 == 7 and not ccr & (1 << CCR_PROBE), f"{ccr:#x}"
    assert ccr & (1 << CCR_PROBEPOL), "JustOnce cleared more than bit 13"
    await q.move(3, 200)
    probe.value = 0
    await h.wait(20)
    probe.value = 1  # second edge: latch already used up
    await h.wait(20)
    assert await h.read(R_CCR, 1) >> 16 == 7
    # 2. falling edge (bit 12 = 0); the rising edge before it does nothing
    await h.write(R_CCR, 1, (1 << CCR_PROBE) | once)
    probe.value = 0
    await h.wait(20)
    probe.value = 1
    await h.wait(20)
    ccr = await h.read(R_CCR, 1)
    assert ccr >> 16 == 10 and not ccr & (1 << CCR_PROBE), f"{ccr:#x}"
    # 3. probe filter: 15 samples with bit 11, a 10-clock low pulse is noise
    await h.write(R_CCR, 1, (1 << CCR_PROBE) | (1 << CCR_FILTER) | once)
    await q.move(-2, 800)
    probe.value = 0
    await Timer(10 * PERIOD, unit="ns")
    probe.value = 1
    await h.wait(40)
    ccr = await h.read(R_CCR, 1)
    assert ccr >> 16 == 10 and ccr & (1 << CCR_PROBE), f"glitch latched: {ccr:#x}"
    # 4. index and probe latches pending together: each event clears its own
    await h.write(R_CCR, 1, (1 << CCR_PROBE) | (1 << CCR_LATCHIDX) | (1 << CCR_IDXPOL) | once)
    await q.index_pulse(300)
    await h.wait(10)
    ccr = await h.read(R_CCR, 1)
    assert ccr >> 16 == 8 and not ccr & (1 << CCR_LATCHIDX) and ccr & (1 << CCR_PROBE)
    await q.move(4, 200)
    probe.value = 0
    await h.wait(40)
    ccr = await h.read(R_CCR, 1)
    assert ccr >> 16 == 12 and not ccr & (1 << CCR_PROBE), f"{ccr:#x}"
    # 5. instance 0 never saw a probe latch
    assert (await h.read(R_CCR, 0)) >> 16 == 0
    model = h.replay(qfilter_reset(dut))
    assert model.inst[1].probe_events == 3 and model.inst[0].probe_events == 0


@cocotb.test()
async def timestamp_and_driver_use(dut: Any) -> None:
    """The LinuxCNC driver's set-up (spec §10.2): TSDiv = floor(ClockLow/2e6)-2,
    QFilterRate for 25 MHz sampling (ClockLow/25e6 = 1 -> 0xFFF), filter on,
    index-enable (bits 4 and 6).  A 500 kHz-count encoder: the driver's
    velocity estimate from count and timestamp must match the true speed,
    and the index event must be signalled the way the driver detects it."""
    h = Harness(dut)
    await h.start()
    tsdiv = int(CLOCK_LOW / 2e6) - 2
    qf = int(CLOCK_LOW / 25e6)
    qf = 0xFFF if qf == 1 else qf - 2
    await h.write(R_TSDIV, 0, tsdiv)
    await h.write(R_QFILTER, 0, qf)
    await h.write(
        R_CCR, 0, (1 << CCR_FILTER) | (1 << CCR_LATCHIDX) | (1 << CCR_JUSTONCE) | (1 << CCR_IDXPOL)
    )
    tick_s = (tsdiv + 2) / CLOCK_LOW
    edge_ns = 2000.017  # 500 kcounts/s
    q = h.src[0].quad
    mover = cocotb.start_soon(q.move(400, edge_ns))
    await Timer(50_000, unit="ns")
    ts0 = await h.read(R_TSCOUNT)
    c0 = await h.read(R_COUNT, 0)
    await Timer(300_000, unit="ns")
    ts1 = await h.read(R_TSCOUNT)
    c1 = await h.read(R_COUNT, 0)
    ds = s16((c1 & 0xFFFF) - (c0 & 0xFFFF))
    dt = ((c1 >> 16) - (c0 >> 16)) & 0xFFFF
    vel = ds / (dt * tick_s)
    assert abs(vel - 1e9 / edge_ns) / (1e9 / edge_ns) < 0.01, vel
    # timestamps are never newer than TSCount at the read
    assert ((ts1 - (c1 >> 16)) & 0xFFFF) < 0x100
    del ts0
    pos_before = q.position
    await q.index_pulse(700)
    ccr = await h.read(R_CCR, 0)
    assert not ccr & (1 << CCR_LATCHIDX), "driver would not see the index event"
    assert abs(s16(ccr >> 16) - pos_before) <= 1
    await mover
    h.replay(qfilter_reset(dut))


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_encoder(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_encoder_bank",
        sources=[
            hdl("common", "sync_ff.v"),
            hdl("hostmot2", "hm2_encoder.v"),
            hdl("hostmot2", "hm2_encoder_bank.v"),
        ],
        test_module="test_hm2_encoder",
        test_dir=Path(__file__).parent,
        parameters={"NUM": 2, "CLOCK_LOW_HZ": 33333333},
    )
