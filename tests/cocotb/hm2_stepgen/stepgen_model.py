# SPDX-License-Identifier: GPL-2.0-or-later
"""Clock-by-clock reference model of a HostMot2 StepGen bank (spec §9.4),
written from the register semantics, not from the Verilog.

Time base: one :meth:`StepgenBankModel.clock` call per ClockLow rising edge.
Writes are applied at the edge that samples them (the same edge as
:meth:`Hm2Bus.write` reports).  Pins are registered: the value after edge k
is the formatted state from before edge k.

Spec rules the model implements (and the tests hold the firmware to):
* master DDS: 32-bit phase += MasterDDS per clock; its carry, one clock
  later, is the basic-rate tick;
* per tick the sign-extended Rate is added to a 48-bit accumulator; a step
  is an integer-boundary crossing (quadrature: a quarter-step crossing, with
  |Rate| limited to 2^30 so the Gray code never skips);
* the add is dropped when the event it produces is not allowed yet:
  the pulse is PulseWidth+1 clocks, the next step waits PulseIdle+1 clocks
  after the fall, DIR follows the sign of Rate but changes only DirHold+1
  clocks after the last fall, a step needs DirSetup+1 clocks after a DIR
  change; quadrature/table states last PulseWidth+PulseIdle+2 clocks.
"""

from __future__ import annotations

from dataclasses import dataclass, field

MASK32 = 0xFFFFFFFF
MASK48 = (1 << 48) - 1


def s32(v: int) -> int:
    v &= MASK32
    return v - (1 << 32) if v & 0x80000000 else v


@dataclass
class StepgenModel:
    table_width: int
    rate: int = 0  # signed
    acc: int = 0  # 48-bit, unsigned representation
    mode: int = 0
    swap: int = 0  # Mode bit 2 (version 0x42): Step and Dir pins exchanged
    dirsetup: int = 0
    dirhold: int = 0
    pulsewidth: int = 0
    pulseidle: int = 0
    table: list[int] = field(default_factory=lambda: [0] * 16)
    tablelen: int = 0
    # motion state
    pulse: bool = False
    dirn: int = 0  # 1 = negative
    width_left: int = 0
    idle_left: int = 0
    hold_left: int = 0
    setup_left: int = 0
    ptr: int = 0
    out: int = 0

    def write(self, reg: int, data: int) -> None:
        data &= MASK32
        if reg == 0:
            self.rate = s32(data)
        elif reg == 1:
            self.pending_acc = data
        elif reg == 2:
            self.mode = data & 3
            self.swap = (data >> 2) & 1
        elif reg == 3:
            self.dirsetup = data & 0x3FFF
        elif reg == 4:
            self.dirhold = data & 0x3FFF
        elif reg == 5:
            self.pulsewidth = data & 0x3FFF
        elif reg == 6:
            self.pulseidle = data & 0x3FFF
        elif reg == 7:
            self.table = [data & ((1 << self.table_width) - 1)] + self.table[:15]
        elif reg == 8:
            self.tablelen = data & 0xF
            self.pending_ptr_reset = True
        else:
            raise ValueError(f"stepgen has no per-instance register {reg}")

    def _format(self) -> int:
        v = self._format_unswapped()
        if self.swap:
            v = (v & ~3) | ((v & 1) << 1) | ((v >> 1) & 1)
        return v

    def _format_unswapped(self) -> int:
        if self.mode == 0:
            return int(self.pulse) | (self.dirn << 1)
        if self.mode == 1:
            return (int(self.pulse and not self.dirn)) | (int(self.pulse and self.dirn) << 1)
        if self.mode == 2:
            quarter = (self.acc >> 30) & 3
            a, b = [(0, 0), (1, 0), (1, 1), (0, 1)][quarter]
            return a | (b << 1)
        return self.table[self.ptr]

    def clock(self, tick: bool, writes: list[tuple[int, int]]) -> None:
        """One rising edge: ``writes`` are (register, data) sampled at it."""
        out_next = self._format()
        neg = self.rate < 0
        rate = self.rate
        if self.mode == 2:
            rate = max(-(1 << 30), min(1 << 30, rate))
        new_acc = (self.acc + rate) & MASK48
        if self.mode == 2:
            event = (new_acc // (1 << 30)) != (self.acc // (1 << 30))
        else:
            event = (new_acc >> 32) != (self.acc >> 32)
        seq = self.mode >= 2
        allowed = (
            not self.pulse
            and self.idle_left == 0
            and (seq or (self.dirn == int(neg) and self.setup_left == 0))
        )
        do_event = tick and event and allowed
        do_add = tick and (not event or allowed)
        dir_change = int(neg) != self.dirn and not self.pulse and self.hold_left == 0

        # snapshot of the timing registers before this edge's writes
        pw, pi, dh, ds = self.pulsewidth, self.pulseidle, self.dirhold, self.dirsetup
        old_mode, old_len = self.mode, self.tablelen
        self.pending_acc: int | None = None
        self.pending_ptr_reset = False
        for reg, data in writes:
            self.write(reg, data)

        if self.pending_acc is not None:
            self.acc = (self.pending_acc << 16) & MASK48
        elif do_add:
            self.acc = new_acc

        if do_event:
            self.pulse = True
            self.width_left = pw
        elif self.pulse:
            if self.width_left == 0:
                self.pulse = False
                self.idle_left = pi
                self.hold_left = dh
            else:
                self.width_left -= 1
        else:
            self.idle_left = max(0, self.idle_left - 1)
            self.hold_left = max(0, self.hold_left - 1)

        if dir_change:
            self.dirn = int(neg)
            self.setup_left = ds
        elif self.setup_left:
            self.setup_left -= 1

        if self.pending_ptr_reset:
            self.ptr = 0
        elif do_event and old_mode == 3:
            if not neg:
                self.ptr = 0 if self.ptr == old_len else (self.ptr + 1) & 0xF
            else:
                self.ptr = old_len if self.ptr == 0 else self.ptr - 1
        self.out = out_next

    @property
    def acc_read(self) -> int:
        return (self.acc >> 16) & MASK32


class StepgenBankModel:
    """NUM instances plus the shared master DDS."""

    def __init__(self, num: int, table_width: int) -> None:
        self.num = num
        self.tw = table_width
        self.inst = [StepgenModel(table_width) for _ in range(num)]
        self.master = 0
        self.phase = 0
        self.tick = False
        self.cycle = 0

    def clock(self, writes: list[tuple[int, int, int]] = ()) -> None:
        """``writes``: (register, instance, data) taken at this edge."""
        per: list[list[tuple[int, int]]] = [[] for _ in range(self.num)]
        new_master = self.master
        for reg, inst, data in writes:
            if reg == 9:
                if inst == 0:
                    new_master = data & MASK32
            elif 0 <= reg < 9 and 0 <= inst < self.num:
                per[inst].append((reg, data))
        for m, w in zip(self.inst, per):
            m.clock(self.tick, w)
        total = self.phase + self.master
        self.tick = total > MASK32
        self.phase = total & MASK32
        self.master = new_master
        self.cycle += 1

    @property
    def out(self) -> int:
        v = 0
        for i, m in enumerate(self.inst):
            v |= m.out << (i * self.tw)
        return v
