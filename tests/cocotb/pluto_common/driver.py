# SPDX-License-Identifier: GPL-2.0-or-later
"""The LinuxCNC pluto_servo / pluto_step drivers' per-servo-cycle EPP
transactions (spec/pluto.md sections 4.1, 6.1, 11), replayed through the
pin-level EPP host model, with the drivers' read decoding (4.3, 6.3)."""

from __future__ import annotations

from dataclasses import dataclass, field

from common.epp import EppCycle, EppHost
from pluto_common.models import extend


@dataclass
class ServoDriver:
    """pluto_servo.read / .write as EPP cycles (epp_wide = 1)."""

    host: EppHost
    communication_error: int = 0
    last_count: list[int] = field(default_factory=lambda: [0] * 4)
    last_index: list[int] = field(default_factory=lambda: [0] * 4)
    indexed: list[bool] = field(default_factory=lambda: [False] * 4)
    raw: list[int] = field(default_factory=lambda: [0] * 5)

    async def write(self, pwm_words: list[int], ctrl: int) -> list[EppCycle]:
        if self.communication_error:
            return []
        n0 = len(self.host.cycles)
        await self.host.write_addr(0)
        await self.host.outl(pwm_words[0] | pwm_words[1] << 16)
        await self.host.outl(pwm_words[2] | pwm_words[3] << 16)
        await self.host.outw(ctrl)
        return self.host.cycles[n0:]

    async def read(self) -> list[EppCycle]:
        n0 = len(self.host.cycles)
        await self.host.write_addr(0)
        words = [await self.host.inl()]
        if self.host.status & 1:
            self.communication_error += 1
            self.host.clear_timeout()
        if self.communication_error:
            return self.host.cycles[n0:]
        for _ in range(4):
            words.append(await self.host.inl())
        self.raw = words
        for ch in range(4):
            w = words[ch]
            count = extend(self.last_count[ch], w & 0x3FFF, 14)
            self.indexed[ch] = bool(w >> 28 & 1)
            if self.indexed[ch]:
                self.last_index[ch] = extend(count, (w >> 14) & 0x3FFF, 14)
            self.last_count[ch] = count
        return self.host.cycles[n0:]

    @property
    def din(self) -> int:
        return self.raw[4] & 0xFFFFF


@dataclass
class StepDriver:
    """pluto_step.read / .write as EPP cycles (epp_wide = 1)."""

    host: EppHost
    communication_error: int = 0
    last_count: list[int] = field(default_factory=lambda: [0] * 4)
    raw: list[int] = field(default_factory=lambda: [0] * 5)

    async def write(self, rates: list[int], dout: int, timing: int) -> list[EppCycle]:
        if self.communication_error:
            return []
        n0 = len(self.host.cycles)
        await self.host.write_addr(0)
        for r in rates:
            await self.host.outw(r & 0xFFFF)
        await self.host.outw(dout & 0xFFFF)
        await self.host.outw(timing & 0xFFFF)
        return self.host.cycles[n0:]

    async def read(self) -> list[EppCycle]:
        n0 = len(self.host.cycles)
        await self.host.write_addr(0)
        words = [await self.host.inl()]
        if self.host.status & 1:
            self.communication_error += 1
            self.host.clear_timeout()
        if self.communication_error:
            return self.host.cycles[n0:]
        for _ in range(4):
            words.append(await self.host.inl())
        self.raw = words
        for ch in range(4):
            self.last_count[ch] = extend(self.last_count[ch], words[ch] & 0x1FFFFF, 21)
        return self.host.cycles[n0:]

    def position_steps(self, ch: int) -> float:
        return self.last_count[ch] / 2048.0

    @property
    def din(self) -> int:
        return self.raw[4] & 0xFFFF
