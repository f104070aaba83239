# SPDX-License-Identifier: GPL-2.0-or-later
"""Pin-level model of a PC parallel port in EPP mode (the host side).

It drives the host's EPP pins of a design under test (8-bit data bus,
nWrite, nDataStr, nAddrStr, optional nReset/nInit) and follows the
peripheral's nWait handshake the way a PC's EPP hardware does:

1. wait until nWait shows "ready" (the peripheral is idle),
2. set nWrite and (for writes) drive the data bus, wait the setup time,
3. assert the strobe (nAddrStr or nDataStr low),
4. wait for nWait to show "acknowledge"; give up after the port timeout
   (~10 us on PCs): the cycle is aborted (strobe released) and the status
   register's timeout bit (bit 0 of ioaddr+1) is set,
5. hold the strobe, sample the bus for reads, release the strobe,
6. wait for nWait to return to "ready" (the peripheral ends the cycle).

The same model serves every EPP firmware of the project (Pluto-P front end,
hostmot2 7i43 bridge), so nothing in it knows about a register map.

Handshake polarity: IEEE 1284 EPP acknowledges with the nWait *pin high*
(``ack_level=1``, the default).  ``ack_level=0`` models a peripheral that
acknowledges by pulling the pin low (see spec/pluto.md section 12).

Bus model: the data bus is three signals on the design, ``d_in`` (what the
design sees, driven by this model), ``d_out`` and ``d_oe`` (what the design
drives and whether it drives).  A bus that nobody drives reads 0xFF (the
board's pull-ups).  ``d_oe`` may be 1 bit or 8 bits wide.

Checks ("handshake timing"), each recorded in :attr:`EppHost.violations` and
raised as :class:`EppProtocolError` when ``strict`` is true:

* the peripheral acknowledges a cycle that was never strobed (nWait at the
  acknowledge level before the strobe, or changing while the bus is idle),
* the peripheral acknowledges faster than ``timing.min_ack_ns``,
* on a read the peripheral acknowledges without driving the bus, or the byte
  it drives changes while the strobe is still held after the acknowledge,
* the peripheral drives the bus while the host does (bus contention),
* the peripheral does not leave the acknowledge state within
  ``timing.release_timeout_ns`` after the strobe ends.

A missing acknowledge is not a violation: it is what the PC port reports as an
EPP timeout (status bit 0), and the caller sees it exactly as a driver would.
"""

from __future__ import annotations

import enum
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

import cocotb
from cocotb.triggers import First, Timer
from cocotb.utils import get_sim_time


class EppProtocolError(AssertionError):
    """The peripheral broke the EPP handshake (see the module doc)."""


class CycleKind(enum.Enum):
    ADDR_WRITE = "A"
    ADDR_READ = "a"
    DATA_WRITE = "W"
    DATA_READ = "R"


@dataclass(frozen=True)
class EppTiming:
    """Host-side timing, in ns.  Defaults are a fast but legal host; see
    :meth:`pc_isa` for the pace of a PC's ISA-era parallel port."""

    setup_ns: float = 20.0  # nWrite/data valid before the strobe
    hold_ns: float = 20.0  # strobe still held after the acknowledge is seen
    data_hold_ns: float = 10.0  # write data still driven after the strobe ends
    ack_timeout_ns: float = 10_000.0  # PC port EPP timeout (from strobe start)
    ready_timeout_ns: float = 10_000.0  # waiting for "ready" before a cycle
    release_timeout_ns: float = 10_000.0  # peripheral must end the cycle by then
    min_ack_ns: float = 0.0  # an acknowledge faster than this is a violation
    min_cycle_ns: float = 0.0  # a cycle takes at least this long (PC bus pace)
    recovery_ns: float = 0.0  # idle time after each cycle

    @staticmethod
    def pc_isa() -> "EppTiming":
        """About 1 us per cycle, the pace of a PC EPP port behind an ISA or
        LPC bridge (the figure LinuxCNC's docs use for EPP cycles)."""
        return EppTiming(setup_ns=100.0, hold_ns=100.0, data_hold_ns=50.0, min_cycle_ns=1000.0)


@dataclass
class EppCycle:
    """One bus cycle as it happened (times in ns of simulated time)."""

    kind: CycleKind
    value: int | None  # byte written, or byte read (None if timed out)
    t_start: float
    t_strobe: float = 0.0
    t_ack: float | None = None
    t_release: float = 0.0
    t_end: float = 0.0
    timeout: bool = False

    @property
    def ack_latency_ns(self) -> float | None:
        return None if self.t_ack is None else self.t_ack - self.t_strobe

    @property
    def duration_ns(self) -> float:
        return self.t_end - self.t_start

    def __str__(self) -> str:
        v = "--" if self.value is None else f"{self.value:02x}"
        return f"{self.kind.value}({v}){'!T' if self.timeout else ''}"


def _now_ns() -> float:
    return float(get_sim_time("ns"))


def _int_or_none(sig: Any) -> int | None:
    try:
        return int(sig.value)
    except ValueError:  # X or Z before reset
        return None


async def _delay(ns: float) -> None:
    ps = int(round(ns * 1000))
    if ps > 0:
        await Timer(ps, unit="ps")


class EppHost:
    """The host side of an EPP link.

    Signal handles (design ports): ``d_in`` (8 bit, host -> design),
    ``d_out`` (8 bit, design -> host), ``d_oe`` (1 or 8 bit), ``nwrite``,
    ``ndatastr``, ``naddrstr``, ``nwait`` and optionally ``nreset`` (the
    nInit line).  Call :meth:`start` once the handles exist; it sets the
    idle levels and starts the bus monitors.
    """

    def __init__(
        self,
        *,
        d_in: Any,
        d_out: Any,
        d_oe: Any,
        nwrite: Any,
        ndatastr: Any,
        naddrstr: Any,
        nwait: Any,
        nreset: Any | None = None,
        ack_level: int = 1,
        timing: EppTiming | None = None,
        strict: bool = True,
        log_cycles: bool = True,
    ) -> None:
        if ack_level not in (0, 1):
            raise ValueError(f"ack_level must be 0 or 1, not {ack_level!r}")
        self.d_in = d_in
        self.d_out = d_out
        self.d_oe = d_oe
        self.nwrite = nwrite
        self.ndatastr = ndatastr
        self.naddrstr = naddrstr
        self.nwait = nwait
        self.nreset = nreset
        self.ack_level = ack_level
        self.timing = timing or EppTiming()
        self.strict = strict
        self.log_cycles = log_cycles
        self.cycles: list[EppCycle] = []
        self.violations: list[str] = []
        self.timeout_count = 0
        self._status_timeout = False
        self._host_drives = False
        self._in_cycle = False  # strobe asserted or waiting for the release
        # After an aborted cycle a slow peripheral may still answer; nWait
        # activity until then is a consequence of the timeout, not a fault.
        self._grace_until = 0.0
        self._started = False
        self._monitors: list[Any] = []

    # ------------------------------------------------------------------ setup
    def start(self) -> None:
        """Drive idle levels and start the contention / spurious-wait monitors."""
        self.nwrite.value = 1
        self.ndatastr.value = 1
        self.naddrstr.value = 1
        self.d_in.value = 0xFF
        if self.nreset is not None:
            self.nreset.value = 1
        if not self._started:
            self._monitors.append(cocotb.start_soon(self._watch_oe()))
            self._monitors.append(cocotb.start_soon(self._watch_wait()))
            self._started = True

    def stop(self) -> None:
        for m in self._monitors:
            m.cancel()
        self._monitors.clear()
        self._started = False

    async def pulse_reset(self, low_ns: float = 2000.0) -> None:
        """Pulse nReset/nInit low (needs the ``nreset`` handle)."""
        if self.nreset is None:
            raise ValueError("this EPP host has no nReset/nInit line")
        self.nreset.value = 0
        await _delay(low_ns)
        self.nreset.value = 1
        await _delay(low_ns)

    # --------------------------------------------------------------- checks
    def _violation(self, text: str) -> None:
        msg = f"EPP @{_now_ns():.1f} ns: {text}"
        self.violations.append(msg)
        if self.strict:
            raise EppProtocolError(msg)

    def _oe_active(self) -> bool:
        v = _int_or_none(self.d_oe)
        return bool(v)

    def _ready(self) -> bool:
        return _int_or_none(self.nwait) == 1 - self.ack_level

    def _acked(self) -> bool:
        return _int_or_none(self.nwait) == self.ack_level

    async def _watch_oe(self) -> None:
        while True:
            await self.d_oe.value_change
            if self._host_drives and self._oe_active():
                # Recorded only: raising inside a monitor task would not reach
                # the caller; the next cycle re-checks and raises.
                self.violations.append(
                    f"EPP @{_now_ns():.1f} ns: bus contention, the peripheral drives "
                    "d while the host drives it"
                )

    async def _watch_wait(self) -> None:
        while True:
            await self.nwait.value_change
            if not self._in_cycle and self._acked() and _now_ns() > self._grace_until:
                self.violations.append(
                    f"EPP @{_now_ns():.1f} ns: nWait shows acknowledge while no cycle is running"
                )

    def _raise_pending(self) -> None:
        """Re-raise monitor findings in the caller's context."""
        if self.strict and self.violations:
            raise EppProtocolError("; ".join(self.violations))

    # -------------------------------------------------------------- one cycle
    async def _wait_for(self, want_ack: bool, timeout_ns: float) -> bool:
        deadline = _now_ns() + timeout_ns
        pred = self._acked if want_ack else self._ready
        while not pred():
            rem = deadline - _now_ns()
            if rem <= 0:
                return False
            await First(self.nwait.value_change, Timer(max(1, int(rem * 1000)), unit="ps"))
        return True

    async def _cycle(self, kind: CycleKind, value: int = 0) -> EppCycle:
        self._raise_pending()
        t = self.timing
        is_write = kind in (CycleKind.ADDR_WRITE, CycleKind.DATA_WRITE)
        is_addr = kind in (CycleKind.ADDR_WRITE, CycleKind.ADDR_READ)
        if is_write and not 0 <= value <= 0xFF:
            raise ValueError(f"EPP byte out of range: {value!r}")
        cyc = EppCycle(kind=kind, value=value if is_write else None, t_start=_now_ns())
        strobe = self.naddrstr if is_addr else self.ndatastr

        # 1. The port starts a cycle only while the peripheral is ready.
        if not await self._wait_for(False, t.ready_timeout_ns):
            self._set_timeout(cyc)
            cyc.t_end = _now_ns()
            return self._log(cyc)

        # 2. Direction and data, setup time.
        self.nwrite.value = 0 if is_write else 1
        if is_write:
            if self._oe_active():
                self._violation("peripheral drives d at the start of a write cycle")
            self._host_drives = True
            self.d_in.value = value
        else:
            self._host_drives = False
            self.d_in.value = 0xFF
        await _delay(t.setup_ns)
        if self._acked():
            self._violation("nWait shows acknowledge before the strobe")

        # 3. Strobe, 4. acknowledge or port timeout.
        self._in_cycle = True
        strobe.value = 0
        cyc.t_strobe = _now_ns()
        acked = await self._wait_for(True, t.ack_timeout_ns)
        if acked:
            cyc.t_ack = _now_ns()
            lat = cyc.t_ack - cyc.t_strobe
            if lat < t.min_ack_ns:
                self._violation(f"acknowledge after {lat:.1f} ns, faster than {t.min_ack_ns} ns")
            if not is_write:
                first = self._sample_bus(after_ack=True)
            await _delay(t.hold_ns)
            if not is_write:
                again = self._sample_bus(after_ack=True)
                if first != again:
                    self._violation(
                        f"read data changed while acknowledged: {first:#04x} -> {again:#04x}"
                    )
                cyc.value = again
        else:
            self._set_timeout(cyc)

        # 5. End of strobe; write data held a little longer.
        strobe.value = 1
        cyc.t_release = _now_ns()
        if is_write:
            await _delay(t.data_hold_ns)
            self._host_drives = False
            self.d_in.value = 0xFF

        # 6. The peripheral must end its acknowledge.
        if acked:
            if not await self._wait_for(False, t.release_timeout_ns):
                self._in_cycle = False
                self._violation("peripheral holds the acknowledge after the strobe ended")
                self._set_timeout(cyc)
        self._in_cycle = False
        self.nwrite.value = 1
        rest = t.min_cycle_ns - (_now_ns() - cyc.t_start)
        await _delay(max(rest, 0.0) + t.recovery_ns)
        cyc.t_end = _now_ns()
        self._raise_pending()
        return self._log(cyc)

    def _sample_bus(self, *, after_ack: bool) -> int:
        oe = _int_or_none(self.d_oe)
        if not oe:
            if after_ack:
                self._violation("read acknowledged but the peripheral does not drive d")
            return 0xFF
        width = len(self.d_oe)
        out = _int_or_none(self.d_out)
        if out is None:
            self._violation("peripheral drives an unknown (X/Z) value on d")
            return 0xFF
        if width == 1:
            return out & 0xFF
        # Per-bit enables: undriven bits read high (pull-ups).
        return ((out & oe) | (~oe & 0xFF)) & 0xFF

    def _set_timeout(self, cyc: EppCycle) -> None:
        cyc.timeout = True
        self._grace_until = _now_ns() + self.timing.release_timeout_ns
        self._status_timeout = True
        self.timeout_count += 1

    def _log(self, cyc: EppCycle) -> EppCycle:
        if self.log_cycles:
            self.cycles.append(cyc)
        return cyc

    # ------------------------------------------------------- the port's API
    @property
    def status(self) -> int:
        """Status register (ioaddr+1) as far as the model knows it: bit 0 =
        EPP timeout (sticky until cleared)."""
        return 1 if self._status_timeout else 0

    @property
    def timed_out(self) -> bool:
        return self._status_timeout

    def clear_timeout(self) -> None:
        """What pluto_clear_error_register / hm2_7i43's clear does."""
        self._status_timeout = False

    async def write_addr(self, value: int) -> EppCycle:
        return await self._cycle(CycleKind.ADDR_WRITE, value)

    async def read_addr(self) -> int | None:
        return (await self._cycle(CycleKind.ADDR_READ)).value

    async def write_data(self, data: int | Iterable[int]) -> list[EppCycle]:
        """One data write cycle per byte (a burst for a sequence)."""
        seq = [data] if isinstance(data, int) else list(data)
        return [await self._cycle(CycleKind.DATA_WRITE, b) for b in seq]

    async def read_data(self, n: int = 1) -> list[int | None]:
        """``n`` data read cycles; a timed-out cycle yields None."""
        if n < 0:
            raise ValueError(f"negative read length {n}")
        return [(await self._cycle(CycleKind.DATA_READ)).value for _ in range(n)]

    # x86 port I/O on ioaddr+4: wide accesses are byte cycles, LSB first.
    async def outb(self, value: int) -> None:
        await self.write_data(value & 0xFF)

    async def outw(self, value: int) -> None:
        await self.write_data(_le_bytes(value, 2))

    async def outl(self, value: int) -> None:
        await self.write_data(_le_bytes(value, 4))

    async def inb(self) -> int:
        return _le_int(await self.read_data(1))

    async def inw(self) -> int:
        return _le_int(await self.read_data(2))

    async def inl(self) -> int:
        """32-bit read; a timed-out byte reads 0xFF (floating bus)."""
        return _le_int(await self.read_data(4))

    # --------------------------------------------- deliberately bad host cycles
    async def abandoned_strobe(
        self,
        *,
        addr: bool = False,
        write: bool = True,
        value: int = 0,
        hold_ns: float | None = None,
    ) -> None:
        """Assert a strobe and ignore the handshake: keep it for ``hold_ns``
        (None = forever, i.e. return with the strobe still asserted; call
        :meth:`release_all` later).  Models a host that dies mid-cycle."""
        self.nwrite.value = 0 if write else 1
        self._host_drives = write
        self.d_in.value = value if write else 0xFF
        await _delay(self.timing.setup_ns)
        self._in_cycle = True
        (self.naddrstr if addr else self.ndatastr).value = 0
        if hold_ns is not None:
            await _delay(hold_ns)
            await self.release_all()

    async def strobe_glitch(self, width_ns: float, *, addr: bool = False, value: int = 0) -> None:
        """A write strobe pulse of ``width_ns`` that ignores nWait."""
        self.nwrite.value = 0
        self._host_drives = True
        self.d_in.value = value
        await _delay(self.timing.setup_ns)
        self._in_cycle = True
        strobe = self.naddrstr if addr else self.ndatastr
        strobe.value = 0
        await _delay(width_ns)
        strobe.value = 1
        await self.release_all()

    async def release_all(self, settle_ns: float = 1000.0) -> None:
        """Put every host line back to idle and let the peripheral settle."""
        self.ndatastr.value = 1
        self.naddrstr.value = 1
        await _delay(self.timing.data_hold_ns)
        self._host_drives = False
        self.d_in.value = 0xFF
        self.nwrite.value = 1
        self._grace_until = _now_ns() + settle_ns
        await _delay(settle_ns)
        self._in_cycle = False

    # ----------------------------------------------------------- reporting
    def trace(self, cycles: Sequence[EppCycle] | None = None) -> str:
        """Cycles as ``A(00) W(12) R(34) ...`` (spec/pluto.md section 11 style)."""
        return " ".join(str(c) for c in (self.cycles if cycles is None else cycles))

    def bus_time_ns(self, cycles: Sequence[EppCycle] | None = None) -> float:
        cs = self.cycles if cycles is None else cycles
        return sum(c.duration_ns for c in cs)


def _le_bytes(value: int, n: int) -> list[int]:
    if not 0 <= value < 1 << (8 * n):
        raise ValueError(f"value {value:#x} does not fit in {n} bytes")
    return [(value >> (8 * i)) & 0xFF for i in range(n)]


def _le_int(data: Sequence[int | None]) -> int:
    v = 0
    for i, b in enumerate(data):
        v |= (0xFF if b is None else b) << (8 * i)
    return v


@dataclass
class EppStats:
    """Summary of a list of cycles, for benches."""

    cycles: int = 0
    timeouts: int = 0
    bus_ns: float = 0.0
    ack_latency_ns: list[float] = field(default_factory=list)

    @staticmethod
    def of(cycles: Sequence[EppCycle]) -> "EppStats":
        s = EppStats(cycles=len(cycles))
        for c in cycles:
            s.timeouts += int(c.timeout)
            s.bus_ns += c.duration_ns
            if c.ack_latency_ns is not None:
                s.ack_latency_ns.append(c.ack_latency_ns)
        return s
