# SPDX-License-Identifier: GPL-2.0-or-later
"""Reference models of the Pluto-P firmware blocks, written from
spec/pluto.md (sections 2, 3, 5) independently of the Verilog, plus the
LinuxCNC driver arithmetic (sections 4.2, 4.3, 6.2, 6.3) used to build and
decode the driver's EPP transactions.

Cycle-level models advance with :meth:`clock` (one 40 MHz clock) and expose
the registered outputs as they are after that clock edge.
"""

from __future__ import annotations

from dataclasses import dataclass, field

CLK_NS = 25.0  # 40 MHz


# --------------------------------------------------------------- EPP regs
@dataclass
class EppRegModel:
    """Address register, 16-bit write assembly, 32-bit read buffer.

    ``shared_lo``: the write low byte is kept in byte 0 of the read buffer
    (so a later stale read returns it there), as pluto_epp with
    SHARED_LO = 1 does."""

    shared_lo: bool = False
    addr: int = 0
    lo: int = 0
    buf: int = 0
    writes: list[tuple[int, int]] = field(default_factory=list)  # (addr & 15, word)
    snapshots: list[int] = field(default_factory=list)  # selectors snapshotted

    def addr_write(self, value: int) -> None:
        self.addr = value & 0x1F

    def addr_read(self) -> int:
        return self.addr

    def data_write(self, value: int) -> None:
        if self.addr & 1:
            self.writes.append((self.addr & 0xF, (value << 8) | self.lo))
        else:
            self.lo = value
            if self.shared_lo:
                self.buf = (self.buf & ~0xFF) | value
        self.addr = (self.addr + 1) & 0x1F

    def data_read(self, regs: dict[int, int]) -> int:
        """regs: selector -> 32-bit value for the selectors that exist."""
        lane = self.addr & 3
        if lane == 0:
            sel = self.addr >> 2
            if sel in regs:
                self.buf = regs[sel] & 0xFFFFFFFF
                self.snapshots.append(sel)
        self.addr = (self.addr + 1) & 0x1F
        return (self.buf >> (8 * lane)) & 0xFF


# ------------------------------------------------------------- quadrature
@dataclass
class QuadModel:
    """One encoder channel, inputs already synchronized (module level)."""

    width: int = 14
    a_prev: int = 0
    b_prev: int = 0
    count: int = 0
    latch: int = 0
    seen: int = 0
    integ: int = 0
    zf: int = 0

    def reset(self, a: int, b: int) -> None:
        self.a_prev, self.b_prev = a, b
        self.count = self.latch = self.seen = self.integ = self.zf = 0

    def clock(self, a: int, b: int, z: int, clr: int) -> None:
        mask = (1 << self.width) - 1
        da, db = a != self.a_prev, b != self.b_prev
        new_count = self.count
        if da != db:  # exactly one of A, B changed
            # A leading B: A's new level differs from B's old one.
            new_count = (self.count + (1 if a != self.b_prev else -1)) & mask
        # Filtered index follows the integrator's state before this clock.
        zf_next = 1 if self.integ == 7 else 0 if self.integ == 0 else self.zf
        if zf_next and not self.zf:
            self.latch = self.count
            self.seen = 1
        elif clr:
            self.seen = 0
        if z and self.integ < 7:
            self.integ += 1
        elif not z and self.integ > 0:
            self.integ -= 1
        self.zf = zf_next
        self.count = new_count
        self.a_prev, self.b_prev = a, b

    @property
    def word(self) -> int:
        return (self.seen << 28) | (self.latch << 14) | self.count


# -------------------------------------------------------------------- PWM
PWM_PERIOD = 2047


def pdm_compare(cnt: int) -> int:
    """Counter with bits 10..4 reversed (bits 3..0 kept)."""
    hi = (cnt >> 4) & 0x7F
    rev = int(f"{hi:07b}"[::-1], 2)
    return (rev << 4) | (cnt & 0xF)


def pwm_outputs(word: int, cnt: int, pdm: bool) -> tuple[int, int]:
    """(UP, DN) for PWM word ``word`` at period counter ``cnt``."""
    cmp = pdm_compare(cnt) if pdm else cnt
    active = int((word & 0x7FF) > cmp)
    sign = (word >> 15) & 1
    up = ((word >> 12) & 1) ^ (0 if sign else active)
    dn = ((word >> 13) & 1) ^ (active if sign else 0)
    return up, dn


# --------------------------------------------------------------- watchdog
@dataclass
class WdtModel:
    width: int = 7
    cnt: int = 0
    en: int = 0

    def clock(self, tick: int, pet: int) -> None:
        full = (1 << self.width) - 1
        if pet:
            self.cnt, self.en = 0, 1
        elif tick and self.cnt != full:
            self.cnt += 1

    @property
    def trip(self) -> int:
        return int(self.en and self.cnt == (1 << self.width) - 1)


# ---------------------------------------------------------------- stepgen
@dataclass
class StepgenModel:
    """One step generator, advanced once per tick (64 clocks)."""

    w: int = 10
    f: int = 11
    pos: int = 0
    step: int = 0
    dir: int = 0
    last: int = 0
    timer: int = 0
    dtimer: int = 0
    phase: str = "run"  # run | hold | setup

    def tick(self, vel: int, steptime: int, dirtime: int, tap: int) -> None:
        bits = self.w + self.f
        vel &= (1 << (self.f + 1)) - 1
        vsign = vel >> self.f
        vs = vel - (1 << (self.f + 1)) if vsign else vel
        sel = (self.pos >> (self.f + tap)) & 1
        due = sel != self.last
        turn = vsign != self.dir
        run = self.phase == "run" or (self.phase == "setup" and self.dtimer == 0)
        if run:
            self.phase = "run"
            if self.timer:
                self.timer -= 1
            elif self.step:
                self.step = 0
                if turn and not due:
                    self.phase, self.dtimer = "hold", dirtime
            elif due:
                self.step, self.timer, self.last = 1, steptime, sel
            elif turn:
                self.phase, self.dtimer = "hold", dirtime
            if not turn:
                self.pos = (self.pos + vs) & ((1 << bits) - 1)
        elif self.dtimer:
            self.dtimer -= 1
        elif self.phase == "hold":
            if turn:
                self.dir, self.phase, self.dtimer = vsign, "setup", dirtime
            else:
                self.phase = "run"


# ------------------------------------------------------- driver arithmetic
def extend(old: int, low: int, n: int) -> int:
    """pluto_common.h extend(): widen an n-bit wrapping counter."""
    mask = (1 << n) - 1
    c1 = (old & ~mask) | low
    c2 = c1 - (1 << n) if (old & mask) < low else c1 + (1 << n)
    return c2 if abs(old - c1) > (mask // 2) else c1


def servo_pwm_word(
    value: float,
    enable: bool = True,
    *,
    scale: float = 1.0,
    offset: float = 0.0,
    max_dc: float = 1.0,
    min_dc: float = 0.0,
    pwmdir: bool = False,
    is_pdm: bool = False,
    dout_up: bool = False,
    dout_dn: bool = False,
) -> int:
    """pluto_servo.write's PWM word (spec 4.2), dout bits already XORed
    with their invert parameters."""
    if not enable:
        return 0
    max_dc = min(max(max_dc, 0.0), 1.0)
    min_dc = min(max(min_dc, 0.0), max_dc)
    v = value / scale + offset
    v = max(-max_dc, min(max_dc, v))
    if v != 0 and abs(v) < min_dc:
        v = min_dc if v > 0 else -min_dc
    v = max(-2047.0, min(2047.0, 2047.0 * v))
    m = int(abs(v))
    word = m
    if v < 0:
        word |= (1 << 13) if pwmdir else (1 << 15)
    if is_pdm:
        word |= 1 << 14
    if dout_up:
        word ^= 1 << 12
    if dout_dn:
        word ^= 1 << 13
    return word


def servo_ctrl_word(douts: int, z_polarity: bool, watchdog: bool, test_encoder: bool) -> int:
    return (douts & 0x3FF) | (z_polarity << 15) | (watchdog << 14) | (test_encoder << 13)


def step_timing_word(steplen_ns: int, dirtime_ns: int, step_polarity: bool) -> int:
    """pluto_step.write's timing word (spec 6.2), with the driver's clamp."""
    steplen_t = min(steplen_ns // 1600, 31)
    dirtime_t = min(dirtime_ns // 1600, 31)
    return steplen_t | (dirtime_t << 8) | (0x8000 if step_polarity else 0)


def step_rate(v_steps_per_s: float, scale: float = 1.0, speedrange: int = 0) -> int:
    """rate register value for a velocity in position units per second."""
    r = int(v_steps_per_s * scale * 2048 * 1.6e-6 / (1 << speedrange))
    return max(-1024, min(1024, r))
