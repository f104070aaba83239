# SPDX-License-Identifier: GPL-2.0-or-later
"""Clock-by-clock reference model of a HostMot2 QCounter bank (spec §9.5),
written from the register description, not from the Verilog.

One :meth:`EncoderBankModel.clock` call per ClockLow rising edge, given the
pin levels the edge samples and the register writes it takes.  A register
read sampled at edge k returns the state from before edge k.

Pin path: 2-FF synchronizer, then (A, B, Index, Probe) an integrator filter
sampled at ClockLow/(QFilterRate+2): it moves one step toward the input per
sample and flips the filtered level at its end stops (3 or 15, CCR bit 11).

Probe latch (version 0x83): with LatchOnProbe (bit 13), the filtered probe's
active edge (ProbePolarity bit 12: 1 rising, 0 falling) latches the count;
it wins over an index latch in the same clock.  JustOnce clears bit 13 on a
probe event and bits 5/4 on an index event."""

from __future__ import annotations

from dataclasses import dataclass, field

CCR_QERR, CCR_ABMASKPOL, CCR_PROBE, CCR_PROBEPOL = 15, 14, 13, 12
CCR_FILTER, CCR_UPDOWN, CCR_USEMASK, CCR_MASKPOL = 11, 10, 9, 8
CCR_ABGATE, CCR_JUSTONCE, CCR_CLRIDX, CCR_LATCHIDX, CCR_IDXPOL = 7, 6, 5, 4, 3


def bit(v: int, n: int) -> int:
    return (v >> n) & 1


@dataclass
class EncoderModel:
    # synchronizer stages: a, b, idx, mask, probe
    s1: list[int] = field(default_factory=lambda: [0, 0, 0, 0, 0])
    s2: list[int] = field(default_factory=lambda: [0, 0, 0, 0, 0])
    # filters: a, b, idx, probe
    fcnt: list[int] = field(default_factory=lambda: [0, 0, 0, 0])
    filt: list[int] = field(default_factory=lambda: [0, 0, 0, 0])
    prev: list[int] = field(default_factory=lambda: [0, 0])
    cond_prev: int = 0
    probe_prev: int = 0
    count: int = 0
    stamp: int = 0
    latch: int = 0
    ctrl: int = 0  # CCR bits 14..3 in place
    qerr: int = 0
    # power-up priming (see hm2_encoder.v): clocks since reset, filter loaded
    # from the pins, decoding enabled
    warm: int = 0
    primed: bool = False
    live: bool = False
    # bookkeeping for tests
    qerr_events: int = 0
    index_events: int = 0
    probe_events: int = 0

    def clock(
        self,
        pins: tuple[int, ...],
        sample: bool,
        tscount: int,
        we_count: bool,
        ccr_write: int | None,
    ) -> None:
        ctrl = self.ctrl
        fmax = 15 if bit(ctrl, CCR_FILTER) else 3
        was_primed = self.primed
        a, b, idx, prb = self.filt
        pa, pb = self.prev
        up = down = qerr_set = False
        if not self.live:
            pass  # no decoding until the filter is primed from the pins
        elif bit(ctrl, CCR_UPDOWN):
            if a and not pa:
                # direction = B before the edge (the level set up for it)
                up, down = bool(pb), not pb
        else:
            da, db = a != pa, b != pb
            if da and db:
                qerr_set = True
            elif da or db:
                # forward Gray order 00 -> 10 -> 11 -> 01 -> 00
                order = {(0, 0): 0, (1, 0): 1, (1, 1): 2, (0, 1): 3}
                step = (order[(a, b)] - order[(pa, pb)]) % 4
                up, down = step == 1, step == 3
        mask = self.s2[3]
        mask_ok = not bit(ctrl, CCR_USEMASK) or mask == bit(ctrl, CCR_MASKPOL)
        pol = bit(ctrl, CCR_ABMASKPOL)
        ab_ok = not bit(ctrl, CCR_ABGATE) or (a == pol and b == pol)
        cond = int(idx == bit(ctrl, CCR_IDXPOL) and mask_ok and ab_ok)
        event = bool(self.live and cond and not self.cond_prev)
        probe_edge = self.live and prb != self.probe_prev and prb == bit(ctrl, CCR_PROBEPOL)
        probe_latch = bool(probe_edge and bit(ctrl, CCR_PROBE))
        fin = [self.s2[0], self.s2[1], self.s2[2], self.s2[4]]

        # filters (use the synchronized levels from before this edge)
        new_fcnt, new_filt = list(self.fcnt), list(self.filt)
        if not self.primed:
            # wait until the synchronizer holds pin levels, then load the
            # filter from them instead of integrating up from 0
            if self.warm < 3:
                self.warm += 1
            else:
                new_filt = list(fin)
                new_fcnt = [fmax if fin[j] else 0 for j in range(4)]
                self.primed = True
        elif sample:
            for j in range(4):
                c = self.fcnt[j]
                if fin[j]:
                    c = min(c + 1, fmax) if c + 1 < fmax else fmax
                    if c == fmax:
                        new_filt[j] = 1
                else:
                    if c <= 1:
                        c = 0
                        new_filt[j] = 0
                    elif c > fmax:
                        c = fmax - 1
                    else:
                        c -= 1
                new_fcnt[j] = c

        if we_count or (event and bit(ctrl, CCR_CLRIDX)):
            self.count = 0
        elif up:
            self.count = (self.count + 1) & 0xFFFF
        elif down:
            self.count = (self.count - 1) & 0xFFFF
        if up or down:
            self.stamp = tscount
        if probe_latch or (event and bit(ctrl, CCR_LATCHIDX)):
            self.latch = self.count_before
        if ccr_write is not None:
            self.ctrl = ccr_write & 0x7FF8
        elif bit(ctrl, CCR_JUSTONCE):
            if event:
                self.ctrl &= ~((1 << CCR_CLRIDX) | (1 << CCR_LATCHIDX))
            if probe_latch:
                self.ctrl &= ~(1 << CCR_PROBE)
        if qerr_set:
            self.qerr = 1
            self.qerr_events += 1
        elif ccr_write is not None and bit(ccr_write, CCR_QERR):
            self.qerr = 0
        if event:
            self.index_events += 1
        if probe_latch:
            self.probe_events += 1

        if was_primed:
            self.live = True  # decoding starts the clock after priming
        self.prev = [a, b]
        self.cond_prev = cond
        self.probe_prev = prb
        self.fcnt, self.filt = new_fcnt, new_filt
        self.s2 = list(self.s1)
        self.s1 = list(pins)

    def pre_edge(self) -> None:
        self.count_before = self.count

    @property
    def count_reg(self) -> int:
        return (self.stamp << 16) | self.count

    @property
    def ccr_reg(self) -> int:
        return (
            (self.latch << 16)
            | (self.qerr << 15)
            | self.ctrl
            | (self.filt[2] << 2)
            | (self.filt[1] << 1)
            | self.filt[0]
        )


class EncoderBankModel:
    def __init__(self, num: int, qfilter_reset: int) -> None:
        self.num = num
        self.inst = [EncoderModel() for _ in range(num)]
        self.tsdiv = 0
        self.tspre = 0
        self.tscount = 0
        self.qfilter = qfilter_reset
        self.fpre = 0
        self.sample = False

    def read(self, reg: int, inst: int) -> int:
        """Value a read sampled at the next edge returns."""
        if not 0 <= inst < self.num:
            return 0
        if reg == 0:
            return self.inst[inst].count_reg
        if reg == 1:
            return self.inst[inst].ccr_reg
        if inst != 0:
            return 0
        return {2: self.tsdiv, 3: self.tscount, 4: self.qfilter}.get(reg, 0)

    def clock(self, pins: list[tuple[int, ...]], writes: list[tuple[int, int, int]] = ()) -> None:
        we_count = [False] * self.num
        ccr: list[int | None] = [None] * self.num
        new_tsdiv, new_qfilter = self.tsdiv, self.qfilter
        for reg, inst, data in writes:
            if reg == 0 and inst < self.num:
                we_count[inst] = True
            elif reg == 1 and inst < self.num:
                ccr[inst] = data
            elif reg == 2 and inst == 0:
                new_tsdiv = data & 0xFFFF
            elif reg == 4 and inst == 0:
                new_qfilter = data & 0xFFF
        for i, m in enumerate(self.inst):
            m.pre_edge()
            m.clock(pins[i], self.sample, self.tscount, we_count[i], ccr[i])
        # prescalers: divide by N+2 (count 0..N+1), MSb = divide by 1
        if self.tsdiv & 0x8000 or self.tspre >= self.tsdiv + 1:
            self.tspre = 0
            self.tscount = (self.tscount + 1) & 0xFFFF
        else:
            self.tspre += 1
        self.sample = bool(self.qfilter & 0x800 or self.fpre >= self.qfilter + 1)
        self.fpre = 0 if self.sample else self.fpre + 1
        self.tsdiv, self.qfilter = new_tsdiv, new_qfilter
