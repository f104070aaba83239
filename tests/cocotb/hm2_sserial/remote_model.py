# SPDX-License-Identifier: GPL-2.0-or-later
"""Pin-level reference model of a Smart Serial remote (spec/hostmot2.md
section 9.9), written from the frame description, not from the Verilog.

It watches the channel's TxData pin, decodes 8N1 bytes (bit time given in
clocks), checks each frame's CRC-8 and answers on the RxData pin.  Knobs
for the fault tests: ``plugged`` (False: never answers, like an unplugged
cable), ``corrupt_crc`` (answers with a wrong CRC)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cocotb.triggers import ClockCycles, RisingEdge


def crc8(data: bytes) -> int:
    """CRC-8, polynomial x^8 + x^2 + x + 1 (0x07), initial value 0, MSB first."""
    c = 0
    for b in data:
        c ^= b
        for _ in range(8):
            c = ((c << 1) ^ 0x07) & 0xFF if c & 0x80 else (c << 1) & 0xFF
    return c


@dataclass
class RemoteModel:
    name: bytes = b"7I76"
    unit: int = 0x12345678
    ptoc: int = 0x0100
    gtoc: int = 0x0200
    in_bits: int = 40
    out_bits: int = 24
    memory: dict[int, int] = field(default_factory=dict)
    inputs: int = 0  # process data to the host (in_bits)
    status: int = 0
    plugged: bool = True
    corrupt_crc: bool = False
    # what it saw
    frames: list[bytes] = field(default_factory=list)
    outputs: int = 0  # last process data from the host
    mode: int | None = None

    def answer(self, frame: bytes) -> bytes | None:
        """The reply to one complete host frame (CRC included), or None."""
        if len(frame) < 2 or crc8(frame[:-1]) != frame[-1]:
            return None
        body = frame[:-1]
        cmd = body[0]
        if cmd == 0x01 and len(body) == 2:
            self.mode = body[1]
            return (
                self.name
                + self.unit.to_bytes(4, "little")
                + self.ptoc.to_bytes(2, "little")
                + self.gtoc.to_bytes(2, "little")
                + bytes([self.in_bits, self.out_bits])
            )
        if cmd == 0x02 and len(body) == 4:
            addr, n = body[1] | body[2] << 8, body[3]
            return bytes(self.memory.get(addr + i, 0) for i in range(n))
        if cmd == 0x03 and len(body) >= 4 and len(body) == 4 + body[3]:
            addr, n = body[1] | body[2] << 8, body[3]
            for i in range(n):
                self.memory[addr + i] = body[4 + i]
            return bytes([self.status])
        if cmd == 0x04 and len(body) == 1 + (self.out_bits + 7) // 8:
            self.outputs = int.from_bytes(body[1:], "little")
            nin = (self.in_bits + 7) // 8
            return bytes([self.status]) + (self.inputs & ((1 << self.in_bits) - 1)).to_bytes(
                nin, "little"
            )
        return None

    def frame_length(self, head: bytes) -> int | None:
        """Length of the host frame (CRC included) that starts with head."""
        if not head:
            return None
        cmd = head[0]
        if cmd == 0x01:
            return 3
        if cmd == 0x02:
            return 5
        if cmd == 0x03:
            return 5 + head[3] if len(head) >= 4 else None
        if cmd == 0x04:
            return 2 + (self.out_bits + 7) // 8
        return 1  # unknown command: resynchronize on the next byte


async def uart_rx_byte(clk: Any, pin: Any, div: int) -> int:
    """Wait for a start bit on pin, return the byte (sampled mid-bit)."""
    while int(pin.value) == 1:
        await RisingEdge(clk)
    await ClockCycles(clk, div // 2)
    v = 0
    for k in range(8):
        await ClockCycles(clk, div)
        v |= int(pin.value) << k
    await ClockCycles(clk, div)  # stop bit
    return v


async def uart_tx_bytes(clk: Any, pin: Any, div: int, data: bytes) -> None:
    for b in data:
        bits = [0] + [(b >> k) & 1 for k in range(8)] + [1]
        for x in bits:
            pin.value = x
            await ClockCycles(clk, div)
    pin.value = 1


async def serve(clk: Any, tx_pin: Any, rx_pin: Any, div: int, remote: RemoteModel) -> None:
    """Run the remote on one channel forever."""
    rx_pin.value = 1
    buf = b""
    while True:
        buf += bytes([await uart_rx_byte(clk, tx_pin, div)])
        n = remote.frame_length(buf)
        if n is None or len(buf) < n:
            continue
        frame, buf = buf[:n], b""
        remote.frames.append(frame)
        reply = remote.answer(frame)
        if reply is None or not remote.plugged:
            continue
        await ClockCycles(clk, 2 * div)  # turnaround
        c = crc8(reply) ^ (0xFF if remote.corrupt_crc else 0)
        await uart_tx_bytes(clk, rx_pin, div, reply + bytes([c]))
