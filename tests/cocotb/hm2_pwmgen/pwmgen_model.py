# SPDX-License-Identifier: GPL-2.0-or-later
"""Reference model of the ClockHigh side of a HostMot2 PWMGen bank (spec
§9.6), clock by clock, written from the register description.

Input per ClockHigh edge: the configuration the ClockHigh domain holds
(values, modes, PWM rate, PDM rate).  The clock-domain crossing itself is
checked separately (every configuration seen on the ClockHigh side must be a
complete state the bus wrote, never a torn one).

Also the spec formulas the tests use as an independent reference:
:func:`pwm_duty`, :func:`pwm_frequency`, :func:`pdm_density`."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class Config:
    vals: list[int]  # per instance {DIR, value12} as 13 bits
    modes: list[int]  # per instance 6 bits
    pwm_rate: int
    pdm_rate: int

    @classmethod
    def unpack(cls, word: int, num: int) -> "Config":
        vals = [(word >> (13 * i)) & 0x1FFF for i in range(num)]
        base = 13 * num
        modes = [(word >> (base + 6 * i)) & 0x3F for i in range(num)]
        base += 6 * num
        return cls(vals, modes, (word >> base) & 0xFFFF, (word >> (base + 16)) & 0xFFFF)


def reg_value(dirn: int, value: int) -> int:
    """PWMVal register word: DIR at bit 31, value right-justified at bit 16."""
    return ((dirn & 1) << 31) | ((value & 0xFFF) << 16)


def bits_of(mode: int) -> int:
    return 9 + (mode & 3)


def pwm_duty(mode: int, value: int) -> float:
    """Spec: high while reference < value; value >= 2^bits is 100 %."""
    return min(value, 1 << bits_of(mode)) / (1 << bits_of(mode))


def pwm_frequency(clock_high: float, rate: int, mode: int) -> float:
    """Spec: PWMCLK = ClockHigh*rate/65536; / 2^bits sawtooth, 2^(bits+1) symmetric."""
    b = bits_of(mode) + (1 if mode & 4 else 0)
    return clock_high * rate / 65536 / (1 << b)


def pdm_density(value: int) -> float:
    return (value & 0xFFF) / 4096


@dataclass
class _Inst:
    act: int = 0
    pdm_acc: int = 0
    pdm: int = 0
    pwm: int = 0
    dirq: int = 0
    out0: int = 0
    out1: int = 0


@dataclass
class PwmBankModel:
    num: int
    phase_pwm: int = 0
    phase_pdm: int = 0
    tick_pwm: int = 0
    tick_pdm: int = 0
    ref: int = 0
    inst: list[_Inst] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.inst = [_Inst() for _ in range(self.num)]

    def clock(self, cfg: Config) -> None:
        for i, st in enumerate(self.inst):
            mode, val = cfg.modes[i], cfg.vals[i]
            b = bits_of(mode)
            sym = bool(mode & 4)
            period = 1 << (b + 1 if sym else b)
            ref_m = self.ref % period
            if sym:
                top = (1 << b) - 1
                cmp = ref_m if ref_m <= top else period - 1 - ref_m
            else:
                cmp = ref_m
            cycle_start = self.tick_pwm and ref_m == period - 1
            omode = (mode >> 3) & 3
            new_out = {
                0: (st.pwm, st.dirq),
                1: (st.dirq, st.pwm),
                2: (st.pwm & st.dirq, st.pwm & (1 - st.dirq)),
                3: (st.pdm, st.dirq),
            }[omode]
            new_pwm = int(cmp < (st.act & 0xFFF))
            new_dir = st.act >> 12
            if self.tick_pdm:
                s = st.pdm_acc + (st.act & 0xFFF)
                st.pdm_acc, st.pdm = s & 0xFFF, s >> 12
            if not (mode & 0x20) or cycle_start:
                st.act = val
            st.pwm, st.dirq = new_pwm, new_dir
            st.out0, st.out1 = new_out
        if self.tick_pwm:
            self.ref = (self.ref + 1) & 0x1FFF
        s = self.phase_pwm + cfg.pwm_rate
        self.phase_pwm, self.tick_pwm = s & 0xFFFF, s >> 16
        s = self.phase_pdm + cfg.pdm_rate
        self.phase_pdm, self.tick_pdm = s & 0xFFFF, s >> 16

    def outputs(self) -> tuple[int, int]:
        o0 = sum(st.out0 << i for i, st in enumerate(self.inst))
        o1 = sum(st.out1 << i for i, st in enumerate(self.inst))
        return o0, o1
