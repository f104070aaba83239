# SPDX-License-Identifier: GPL-2.0-or-later
"""Reusable pin-level sources and monitors for firmware tests.

Monitors are edge driven: :class:`VectorLog` wakes up only when a watched
signal changes and records ``(time_ns, value)``, so a 10 ms run at 33 MHz
costs a few thousand Python wake-ups instead of 333,000.  The analysis
functions then work on :class:`Trace` objects (one bit over time):

* :func:`check_stepdir` - step counter with a step/dir timing checker
  (pulse width, pulse idle, dir setup, dir hold, all in clock periods);
* :func:`check_updown` - up/down pulse counter with width/idle checks;
* :func:`decode_quadrature` - Gray-code position with illegal-transition
  and minimum-state-time checks (stepgen quadrature output);
* :class:`DutyMeter` - PWM/PDM duty, period and pulse counts of a trace.

Sources: :class:`QuadSource` drives an encoder's A/B/Index (and index mask)
pins asynchronously to any clock, with optional noise glitches.
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field

import cocotb
from cocotb.handle import SimHandleBase
from cocotb.triggers import Timer, ValueChange
from cocotb.utils import get_sim_time

# --------------------------------------------------------------------------
# recording


def _as_int(sig: SimHandleBase) -> int:
    v = sig.value
    if not v.is_resolvable:
        raise AssertionError(f"{sig._name} is not resolvable ({v})")
    return int(v)


class VectorLog:
    """Records every change of one signal (any width) as ``(t_ns, value)``."""

    def __init__(self, sig: SimHandleBase) -> None:
        self.sig = sig
        self.t0 = 0.0
        self.v0 = 0
        self.changes: list[tuple[float, int]] = []
        self._task: cocotb.Task | None = None

    def start(self) -> "VectorLog":
        """Start recording now (the signal must be resolvable)."""
        self.t0 = get_sim_time("ns")
        self.v0 = _as_int(self.sig)
        self.changes = []
        self._task = cocotb.start_soon(self._watch())
        return self

    def stop(self) -> None:
        if self._task is not None:
            self._task.cancel()
            self._task = None

    async def _watch(self) -> None:
        # Some simulators update a vector in pieces within one time step (one
        # piece per always block); keep only the last value of a time step.
        while True:
            await ValueChange(self.sig)
            v = _as_int(self.sig)
            t = get_sim_time("ns")
            if self.changes and self.changes[-1][0] == t:
                self.changes.pop()
            before = self.changes[-1][1] if self.changes else self.v0
            if v != before:
                self.changes.append((t, v))

    def bit(self, n: int) -> "Trace":
        """The trace of bit ``n`` of the recorded signal."""
        out: list[tuple[float, int]] = []
        last = (self.v0 >> n) & 1
        for t, v in self.changes:
            b = (v >> n) & 1
            if b != last:
                out.append((t, b))
                last = b
        return Trace(self.t0, (self.v0 >> n) & 1, out)


@dataclass
class Trace:
    """One bit over time: level ``v0`` at ``t0``, then ``changes``."""

    t0: float
    v0: int
    changes: list[tuple[float, int]] = field(default_factory=list)

    def level_at(self, t: float) -> int:
        level = self.v0
        for tc, v in self.changes:
            if tc > t:
                break
            level = v
        return level

    def rising(self) -> list[float]:
        return [t for t, v in self.changes if v == 1]

    def falling(self) -> list[float]:
        return [t for t, v in self.changes if v == 0]


# --------------------------------------------------------------------------
# step / dir


@dataclass
class StepLimits:
    """Minimum times in clock periods (the hm2 registers' N+1 values)."""

    width: int = 1
    idle: int = 1
    setup: int = 1
    hold: int = 1


@dataclass
class StepReport:
    up: int = 0
    down: int = 0
    rises: list[float] = field(default_factory=list)  # step rise times (ns)
    widths: list[int] = field(default_factory=list)  # pulse widths (clocks)
    idles: list[int] = field(default_factory=list)  # low time before each step (clocks)
    setups: list[int] = field(default_factory=list)  # dir change -> next step (clocks)
    holds: list[int] = field(default_factory=list)  # step fall -> dir change (clocks)
    violations: list[str] = field(default_factory=list)

    @property
    def position(self) -> int:
        return self.up - self.down


def _clocks(dt: float, period: float) -> int:
    return int(round(dt / period))


def check_stepdir(
    step: Trace, dirn: Trace, period: float, limits: StepLimits, negative_level: int = 1
) -> StepReport:
    """Count steps (direction sampled at the rising edge; DIR == negative_level
    counts down) and check every timing rule.  A DIR change and a step edge at
    the same instant count as 0 clocks apart."""
    rep = StepReport()
    events = sorted([(t, 0, v) for t, v in dirn.changes] + [(t, 1, v) for t, v in step.changes])
    s_level, d_level = step.v0, dirn.v0
    last_rise: float | None = None
    last_fall: float | None = None
    last_dir: float | None = None
    for t, kind, v in events:
        if kind == 0:  # dir
            if s_level:
                rep.violations.append(f"t={t}: DIR changed during a step pulse")
            if last_fall is not None:
                h = _clocks(t - last_fall, period)
                rep.holds.append(h)
                if h < limits.hold:
                    rep.violations.append(f"t={t}: dir hold {h} < {limits.hold} clocks")
            last_dir = t
            d_level = v
        elif v == 1:  # step rise
            if last_fall is not None:
                i = _clocks(t - last_fall, period)
                rep.idles.append(i)
                if i < limits.idle:
                    rep.violations.append(f"t={t}: pulse idle {i} < {limits.idle} clocks")
            if last_dir is not None:
                s = _clocks(t - last_dir, period)
                rep.setups.append(s)
                if s < limits.setup:
                    rep.violations.append(f"t={t}: dir setup {s} < {limits.setup} clocks")
                last_dir = None  # setup is measured to the first step only
            if d_level == negative_level:
                rep.down += 1
            else:
                rep.up += 1
            rep.rises.append(t)
            last_rise = t
            s_level = 1
        else:  # step fall
            if last_rise is not None:
                w = _clocks(t - last_rise, period)
                rep.widths.append(w)
                if w < limits.width:
                    rep.violations.append(f"t={t}: pulse width {w} < {limits.width} clocks")
            last_fall = t
            s_level = 0
    return rep


def check_updown(up: Trace, down: Trace, period: float, limits: StepLimits) -> StepReport:
    """Up/down outputs: count pulses on each, check width and the idle time
    between any two pulses, and that the two never pulse at once."""
    rep = StepReport()
    events = sorted([(t, 0, v) for t, v in up.changes] + [(t, 1, v) for t, v in down.changes])
    levels = [up.v0, down.v0]
    last_rise: float | None = None
    last_fall: float | None = None
    for t, which, v in events:
        if v == 1:
            if levels[1 - which]:
                rep.violations.append(f"t={t}: up and down pulse at once")
            if last_fall is not None:
                i = _clocks(t - last_fall, period)
                rep.idles.append(i)
                if i < limits.idle:
                    rep.violations.append(f"t={t}: pulse idle {i} < {limits.idle} clocks")
            if which == 0:
                rep.up += 1
            else:
                rep.down += 1
            rep.rises.append(t)
            last_rise = t
        else:
            if last_rise is not None:
                w = _clocks(t - last_rise, period)
                rep.widths.append(w)
                if w < limits.width:
                    rep.violations.append(f"t={t}: pulse width {w} < {limits.width} clocks")
            last_fall = t
        levels[which] = v
    return rep


# --------------------------------------------------------------------------
# quadrature decode (stepgen quadrature output, encoder loop-back)

# (A, B) -> Gray state index; counting up is 00 -> 10 -> 11 -> 01 -> 00.
_GRAY = {(0, 0): 0, (1, 0): 1, (1, 1): 2, (0, 1): 3}


@dataclass
class QuadReport:
    position: int = 0  # quarter states, signed
    changes: int = 0
    min_state: int | None = None  # shortest state duration seen (clocks)
    violations: list[str] = field(default_factory=list)


def decode_quadrature(a: Trace, b: Trace, period: float, min_state: int = 1) -> QuadReport:
    """Follow the Gray code on (a, b): +1 per forward state, -1 per reverse;
    a simultaneous change of both is illegal; every state must last at least
    ``min_state`` clock periods."""
    rep = QuadReport()
    times = sorted({t for t, _ in a.changes} | {t for t, _ in b.changes})
    state = _GRAY[(a.v0, b.v0)]
    last_t: float | None = None
    for t in times:
        new = _GRAY[(a.level_at(t), b.level_at(t))]
        d = (new - state) % 4
        if d == 0:
            continue
        if d == 2:
            rep.violations.append(f"t={t}: illegal quadrature transition (both phases changed)")
        else:
            rep.position += 1 if d == 1 else -1
        if last_t is not None:
            n = _clocks(t - last_t, period)
            rep.min_state = n if rep.min_state is None else min(rep.min_state, n)
            if n < min_state:
                rep.violations.append(f"t={t}: quadrature state lasted {n} < {min_state} clocks")
        rep.changes += 1
        state = new
        last_t = t
    return rep


# --------------------------------------------------------------------------
# PWM / PDM


class DutyMeter:
    """Duty cycle, period and pulse count of a :class:`Trace` in a window."""

    def __init__(self, trace: Trace) -> None:
        self.trace = trace

    def high_time(self, t_start: float, t_end: float) -> float:
        if t_end <= t_start:
            raise ValueError("empty measurement window")
        level = self.trace.level_at(t_start)
        t = t_start
        high = 0.0
        for tc, v in self.trace.changes:
            if tc <= t_start:
                continue
            if tc >= t_end:
                break
            if level:
                high += tc - t
            t, level = tc, v
        if level:
            high += t_end - t
        return high

    def duty(self, t_start: float, t_end: float) -> float:
        return self.high_time(t_start, t_end) / (t_end - t_start)

    def pulses(self, t_start: float, t_end: float) -> int:
        return sum(1 for t in self.trace.rising() if t_start <= t < t_end)

    def periods(self, t_start: float, t_end: float) -> list[float]:
        r = [t for t in self.trace.rising() if t_start <= t < t_end]
        return [b - a for a, b in zip(r, r[1:])]

    def high_widths(self, t_start: float, t_end: float) -> list[float]:
        out: list[float] = []
        rise: float | None = None
        for t, v in self.trace.changes:
            if t < t_start or t >= t_end:
                continue
            if v == 1:
                rise = t
            elif rise is not None:
                out.append(t - rise)
        return out


# --------------------------------------------------------------------------
# quadrature encoder source


def _ps(ns: float) -> float:
    """Round a time in ns to whole picoseconds (the usual sim precision)."""
    return round(ns * 1000) / 1000


class QuadSource:
    """Drives A/B (and optionally Index / IndexMask) like an encoder.

    ``position`` is the true x4 count (quarter states) the source has moved;
    ``index_level`` is the idle index level (0 unless told otherwise).
    Edges are timed in ns, independent of any FPGA clock."""

    def __init__(
        self,
        a: SimHandleBase,
        b: SimHandleBase,
        idx: SimHandleBase | None = None,
        mask: SimHandleBase | None = None,
        seed: int = 1,
    ) -> None:
        self.a, self.b, self.idx, self.mask = a, b, idx, mask
        self.state = 0
        self.position = 0
        self.rng = random.Random(seed)
        self.glitches = 0
        self._drive()
        if idx is not None:
            idx.value = 0
        if mask is not None:
            mask.value = 0

    def levels(self) -> tuple[int, int]:
        return [(0, 0), (1, 0), (1, 1), (0, 1)][self.state % 4]

    def _drive(self) -> None:
        av, bv = self.levels()
        self.a.value = av
        self.b.value = bv

    def edge(self, direction: int) -> None:
        """Move one quarter state now (+1 or -1)."""
        if direction not in (1, -1):
            raise ValueError("direction must be +1 or -1")
        self.state = (self.state + direction) % 4
        self.position += direction
        self._drive()

    async def move(
        self, counts: int, edge_ns: float, glitch_ns: float = 0.0, glitch_prob: float = 0.0
    ) -> None:
        """Move ``counts`` quarter states (sign = direction), one every
        ``edge_ns``.  With ``glitch_prob`` > 0, each interval may carry one
        glitch of ``glitch_ns`` on a random phase (noise the filter must
        reject when it is shorter than the filter time)."""
        if edge_ns <= 0:
            raise ValueError("edge spacing must be positive")
        step = 1 if counts >= 0 else -1
        edge_ns, glitch_ns = _ps(edge_ns), _ps(glitch_ns)
        for _ in range(abs(counts)):
            self.edge(step)
            if glitch_prob and self.rng.random() < glitch_prob and glitch_ns * 3 < edge_ns:
                pre = _ps(edge_ns / 3)
                await Timer(pre, unit="ns")
                await self.glitch(self.rng.choice(["a", "b"]), glitch_ns)
                await Timer(_ps(edge_ns - pre - glitch_ns), unit="ns")
            else:
                await Timer(edge_ns, unit="ns")

    async def glitch(self, which: str, width_ns: float) -> None:
        """Invert one input for ``width_ns`` and restore it."""
        sig = {"a": self.a, "b": self.b, "idx": self.idx, "mask": self.mask}[which]
        if sig is None:
            raise ValueError(f"no {which} pin on this source")
        old = int(sig.value)
        sig.value = 1 - old
        await Timer(_ps(width_ns), unit="ns")
        sig.value = old
        self.glitches += 1

    async def index_pulse(self, width_ns: float, active: int = 1) -> None:
        if self.idx is None:
            raise ValueError("no index pin on this source")
        self.idx.value = active
        await Timer(_ps(width_ns), unit="ns")
        self.idx.value = 1 - active
