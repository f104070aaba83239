# SPDX-License-Identifier: GPL-2.0-or-later
"""Pins of the virtual 5i20 SVST8_4: ioport registers vs probes, external drive,
loops, quadrature source into the encoders, stepgen timing on the pins, dumps.

References: the ioport rule of hm2_ioport_bank (spec §9.1), the stepgen rate
formula (spec §9.4: steps/s = ClockLow * DDS/2^32 * Rate/2^32, pulse high
(PulseWidth+1) ClockLow periods) and the encoder's count (spec §9.5)."""

from __future__ import annotations

from pathlib import Path

import pytest
import vbhelpers  # noqa: F401  (puts tests/common and tools/vbfw on sys.path)
from vboard import (
    DRIVE_HIGH,
    DRIVE_LOW,
    DRIVE_RELEASE,
    EXT_HIGH,
    EXT_LOOP,
    EXT_LOW,
    EXT_NONE,
    EXT_QUAD,
    NEVER,
    NO_PIN,
    VBoardClient,
    VBoardError,
    VBoardProcess,
)

IO_DATA, IO_DDR, IO_ALT = 0x1000, 0x1100, 0x1200
SG_RATE, SG_MODE, SG_DIRSETUP, SG_DIRHOLD, SG_PW, SG_PI, SG_DDS = (
    0x2000,
    0x2200,
    0x2300,
    0x2400,
    0x2500,
    0x2600,
    0x2900,
)
ENC_COUNT = 0x3000
T_LOW = 30  # ns, ClockLow = 100/3 MHz


def test_outputs_follow_ddr_and_data(client: VBoardClient) -> None:
    client.write(IO_DATA, 0x000050)
    client.write(IO_DDR, 0x0000F0)
    pins = client.probe(0, 24)
    for i, p in enumerate(pins):
        if 4 <= i <= 7:
            assert (p.oe, p.level) == (1, (0x50 >> i) & 1), i
        else:
            assert (p.oe, p.level) == (0, 1), i  # input: pulled up
    # Port 1 untouched, and reading back the pins gives the same levels.
    assert all(p.oe == 0 and p.level == 1 for p in client.probe(24, 24))
    assert client.read32(IO_DATA) & 0xF0 == 0x50


def test_driving_inputs_is_seen_by_the_ioport(client: VBoardClient) -> None:
    client.drive([(10, DRIVE_LOW), (11, DRIVE_HIGH)])
    client.advance(200)  # the input synchronizers
    v = client.read32(IO_DATA)
    assert (v >> 10) & 1 == 0 and (v >> 11) & 1 == 1 and (v >> 12) & 1 == 1
    assert [client.pin(i).ext for i in (10, 11, 12)] == [EXT_LOW, EXT_HIGH, EXT_NONE]
    client.drive(10, DRIVE_RELEASE)
    client.advance(200)
    assert (client.read32(IO_DATA) >> 10) & 1 == 1
    assert client.pin(10).rising == 1 and client.pin(10).falling == 1


def test_fpga_output_wins_over_external_drive(client: VBoardClient) -> None:
    client.drive(4, DRIVE_LOW)
    client.write(IO_DATA, 0x10)
    client.write(IO_DDR, 0x10)
    assert client.pin(4).level == 1
    client.write(IO_DDR, 0)
    assert client.pin(4).level == 0


def test_loops_wire_outputs_into_inputs(client: VBoardClient) -> None:
    client.write(IO_DDR, 0x10)
    client.loop([(4, 10), (4, 11, True)])
    for v in (0, 1, 0):
        client.write(IO_DATA, v << 4)
        client.advance(200)
        assert (client.pin(10).level, client.pin(11).level) == (v, 1 - v)
        assert (client.read32(IO_DATA) >> 10) & 3 == (v | (1 - v) << 1)
    assert client.pin(10).ext == EXT_LOOP
    client.loop([(4, NO_PIN)])
    assert (client.pin(10).ext, client.pin(10).level, client.pin(11).level) == (EXT_NONE, 1, 1)


def test_loop_file_and_command_line_loops(sockdir: Path) -> None:
    f = sockdir / "loops.txt"
    f.write_text("# stepgen 0 step/dir into encoder 0 A/B\n48:3   49:2:inv\n\n")
    with VBoardProcess(
        sockdir / "b.sock", "5i20", "SVST8_4", ["--loop-file", str(f), "--loop", "4:10"]
    ) as p:
        with p.client() as c:
            assert [c.pin(i).ext for i in (3, 2, 10)] == [EXT_LOOP] * 3
            c.write(IO_DDR, 0x10)
            c.write(IO_DATA, 0x0)
            assert c.pin(10).level == 0
    f.write_text("48:3\n49-2\n")
    with pytest.raises(RuntimeError, match=r"loops.txt:2: bad loop '49-2'"):
        VBoardProcess(sockdir / "c.sock", "5i20", "SVST8_4", ["--loop-file", str(f)])


def _setup_stepgen0(c: VBoardClient, rate: int, pw: int = 3, pi: int = 3) -> None:
    c.write(IO_ALT + 8, 0x3)  # port 2 bits 0,1 = pins 48,49: StepGen 0 Step/Dir
    c.write(IO_DDR + 8, 0x3)
    c.write_bursts(
        [
            (SG_MODE, [0]),
            (SG_DIRSETUP, [3]),
            (SG_DIRHOLD, [3]),
            (SG_PW, [pw]),
            (SG_PI, [pi]),
            (SG_RATE, [rate]),
        ]
    )
    c.write(SG_DDS, 1 << 31)  # a basic-rate tick every 2nd ClockLow cycle


def test_stepgen_rate_and_pulse_timing_on_the_pins(client: VBoardClient) -> None:
    rate = 1 << 28  # 1/16 step per tick -> one step per 32 ClockLow periods
    _setup_stepgen0(client, rate)
    client.advance(20_000)
    client.probe_reset(48, 1)
    ns = 1_000_000
    client.advance(ns)
    p = client.pin(48)
    period = T_LOW * 2 * (1 << 32) // rate
    assert p.period_ns == period == 960
    assert p.last_high_ns == p.min_high_ns == (3 + 1) * T_LOW
    assert p.last_low_ns == period - 4 * T_LOW
    assert abs(p.rising - ns / period) <= 1
    assert p.duty == pytest.approx(4 * T_LOW / period, abs=0.01)
    assert client.pin(49).level == 0  # positive rate: DIR low (spec: 0 = forward)


def test_lockstep_host_time_runs_the_stepgen(client: VBoardClient) -> None:
    """The same 1 ms as above, but driven by host times on requests (lockstep)."""
    _setup_stepgen0(client, 1 << 28)
    client.hello(time_ns=10_000_000)
    client.advance(20_000)
    client.probe_reset(48, 1)
    t0 = client.board_time_ns
    for k in range(1, 11):  # ten 100 us servo periods
        client.read32(0x2100, time_ns=10_000_000 + k * 100_000)
    elapsed = client.board_time_ns - t0
    assert elapsed == pytest.approx(1_000_000 - 20_000, abs=200)
    assert abs(client.pin(48).rising - elapsed / 960) <= 1


def test_quadrature_source_counts_in_the_encoder(client: VBoardClient) -> None:
    # Encoder 0: A = pin 3, B = pin 2, index = pin 5 (SVST8_4 pin-out).
    client.quad(3, 2, 200_000.0, index=5, index_every=40)
    assert [client.pin(i).ext for i in (3, 2, 5)] == [EXT_QUAD] * 3
    client.advance(1_000_000)
    count = client.read32(ENC_COUNT) & 0xFFFF
    assert abs(count - 200) <= 2
    a = client.pin(3)
    assert a.rising in (49, 50, 51)
    assert a.period_ns == pytest.approx(4 * 5_000, abs=10)
    assert client.pin(5).rising == pytest.approx(200 / 40, abs=1)
    # Reverse: the count goes back down.
    client.quad(3, 2, -400_000.0, index=5, index_every=40)
    client.advance(1_000_000)
    back = client.read32(ENC_COUNT) & 0xFFFF
    assert (count - 400 - back) % 0x10000 <= 2 or (back - (count - 400)) % 0x10000 <= 2
    # Rate 0 stops it.
    client.quad(3, 2, 0.0, index=5, index_every=40)
    client.advance(2_000)  # the last edge through the encoder's input filter
    held = client.read32(ENC_COUNT) & 0xFFFF
    client.advance(200_000)
    assert client.read32(ENC_COUNT) & 0xFFFF == held


def test_quadrature_source_from_the_command_line(sockdir: Path) -> None:
    with VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4", ["--quad", "3:2:100000"]) as p:
        with p.client() as c:
            c.advance(500_000)
            assert abs((c.read32(ENC_COUNT) & 0xFFFF) - 50) <= 2


def test_stepgen_looped_into_an_encoder(sockdir: Path) -> None:
    with VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4", ["--loop", "48:3"]) as p:
        with p.client() as c:
            _setup_stepgen0(c, 1 << 28)
            c.advance(1_000_000)
            steps = c.pin(48).rising
            assert steps > 1000
            assert c.pin(3).rising == steps


def test_bad_pin_requests(client: VBoardClient) -> None:
    cases = [
        (lambda: client.probe(70, 5), "outside this board's pins 0..71"),
        (lambda: client.probe_reset(72, 1), "outside this board's pins"),
        (lambda: client.quad(3, 3, 1000.0), "must be different"),
        (lambda: client.quad(3, 99, 1000.0), "I/O pin 99 does not exist"),
        (lambda: client.quad(3, 2, float("inf")), "finite"),
        (lambda: client.loop([(99, 1)]), "does not exist"),
    ]
    for call, text in cases:
        with pytest.raises(VBoardError, match=text):
            call()
    # All-or-nothing: a bad entry in a list applies none of it.
    with pytest.raises(VBoardError):
        client.drive([(1, DRIVE_LOW), (500, DRIVE_LOW)])
    assert client.pin(1).ext == EXT_NONE
    p = client.pin(1)
    assert p.min_high_ns == NEVER and p.min_low_ns == NEVER


def test_dump_writes_a_vcd(rtl_client: VBoardClient, sockdir: Path) -> None:
    client = rtl_client
    vcd = sockdir / "w.vcd"
    client.dump(vcd)
    with pytest.raises(VBoardError, match="already running"):
        client.dump(sockdir / "x.vcd")
    client.write(IO_DDR, 0x1)
    client.advance(1_000)
    client.dump(None)
    text = vcd.read_text()
    assert "$enddefinitions" in text and "clk_low" in text and "io_oe" in text
    # ClockLow toggles every 15 ns on average: at least 2*(1000/30) value changes.
    assert text.count("\n#") >= 2 * 1000 // 30
    with pytest.raises(VBoardError, match="cannot open"):
        client.dump("/nonexistent/dir/w.vcd")


def test_watchdog_bites_while_the_host_is_silent(client: VBoardClient) -> None:
    """Lockstep: a probe client's advance is time passing for the watchdog too
    (spec §9.2: a Timer value V bites V+1 ClockLow clocks after it is written;
    the bite makes every pin an input).  The dog bites once at power-up (the
    Timer powers up at 0, like Mesa's firmware): clear that first."""
    client.write(0x0C00, 0x80000000)
    client.write(0x0D00, 0)
    client.write(IO_DATA, 0x0)
    client.write(IO_DDR, 0x1)
    assert client.pin(0).oe == 1
    client.write(0x0C00, 3000)  # 3001 clocks = 90.03 us
    client.advance(85_000)
    assert client.read32(0x0D00) & 1 == 0 and client.pin(0).oe == 1
    client.advance(10_000)
    assert client.read32(0x0D00) & 1 == 1
    p = client.pin(0)
    assert (p.oe, p.level) == (0, 1)


def test_dump_from_the_command_line(sockdir: Path) -> None:
    vcd = sockdir / "start.vcd"
    p = VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4", ["--dump", str(vcd)])
    with p.client() as c:
        c.advance(300)
    assert p.stop() == 0
    text = vcd.read_text()
    assert "$enddefinitions" in text and "lb_rvalid" in text
    assert text.count("\n#") >= 2 * 300 // 30


def test_loop_chains_and_precedence(client: VBoardClient) -> None:
    client.write(IO_DDR, 0x10)
    client.loop([(4, 10), (10, 11, True), (11, 12)])  # 4 -> 10 -> !11 -> 12
    for v in (0, 1):
        client.write(IO_DATA, v << 4)
        assert [client.pin(i).level for i in (10, 11, 12)] == [v, 1 - v, 1 - v]
    # An external drive beats a loop; releasing it gives the loop back.
    client.drive(11, DRIVE_HIGH)
    client.write(IO_DATA, 1 << 4)
    assert (client.pin(11).ext, client.pin(11).level, client.pin(12).level) == (EXT_HIGH, 1, 1)
    client.drive(11, DRIVE_RELEASE)
    assert (client.pin(11).ext, client.pin(11).level, client.pin(12).level) == (EXT_LOOP, 0, 0)
    # A new loop into a pin replaces its old source.
    client.loop([(5, 11)])
    assert client.pin(11).level == 1  # pin 5 is an undriven input: pulled up


def test_quadrature_source_replacement_keeps_position(client: VBoardClient) -> None:
    client.quad(3, 2, 1e6)
    client.advance(10_000)  # 10 counts: state 10 % 4 = 2 -> A=1, B=1
    assert (client.pin(3).level, client.pin(2).level) == (1, 1)
    client.quad(3, 2, 0.0)
    assert (client.pin(3).level, client.pin(2).level) == (1, 1)  # stopped where it was
    client.quad(3, 4, 1e6)  # B moves to pin 4: pin 2 is released
    assert (client.pin(2).ext, client.pin(4).ext) == (EXT_NONE, EXT_QUAD)
    client.probe_reset(3)
    client.advance(1_000)  # count 11: state 3 -> A=0, B=1
    assert (client.pin(3).level, client.pin(4).level) == (0, 1)
    assert client.pin(3).falling == 1


def _scripted_run(sock: Path) -> list[object]:
    with VBoardProcess(sock, "5i20", "SVST8_4") as p, p.client() as c:
        _setup_stepgen0(c, 0x0A3D70A)
        c.quad(3, 2, 123_457.0, index=5, index_every=17)
        out: list[object] = []
        for k in range(1, 30):
            out.append(c.read(0x3000, 8, time_ns=10**9 + k * 7_919))
            c.write(SG_RATE, [k * 0x100000], time_ns=10**9 + k * 7_919 + 3_000)
        out.append(c.probe(0, 72))
        out.append(c.board_time_ns)
        return out


def test_lockstep_runs_are_deterministic(sockdir: Path) -> None:
    a = _scripted_run(sockdir / "a.sock")
    b = _scripted_run(sockdir / "b.sock")
    assert a == b
    assert any(p.rising for p in a[-2])  # type: ignore[union-attr]


def test_dump_writes_an_fst(rtl_client: VBoardClient, sockdir: Path) -> None:
    """FST header fields (block 0, big-endian, per the FST format) against the
    same signals traced as VCD."""
    client = rtl_client
    import struct

    fst = sockdir / "w.fst"
    client.dump(fst)
    t0 = client.board_time_ns
    client.write(IO_DDR, 0x1)
    client.advance(2_000)
    t1 = client.board_time_ns
    client.dump(None)
    assert not (sockdir / "w.fst.tmp.vcd").exists()
    client.dump(sockdir / "w.vcd")
    client.advance(100)
    client.dump(None)
    vcd = (sockdir / "w.vcd").read_text()
    d = fst.read_bytes()
    btype, length, start, end = struct.unpack_from(">BQQQ", d, 0)
    scopes, hier_vars = struct.unpack_from(">QQ", d, 41)
    assert (btype, length) == (0, 329)
    assert t0 * 1000 <= start <= (t0 + 30) * 1000 and end >= t1 * 1000 - 10_000  # ps
    assert struct.unpack_from("b", d, 73)[0] == -12
    assert (scopes, hier_vars) == (vcd.count("$scope"), vcd.count("$var"))
