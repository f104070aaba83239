# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_sim end to end: loading the real driver onto a virtual 5i20 (blank
FPGA -> firmware= through VB_CONFIG), the pinout report against the seed's
printout and the CSV-derived expectation, hm2pinout's sim: source, bad
firmware files and bad module arguments (clear error, board stays blank)."""

from __future__ import annotations

from collections.abc import Iterator
import re
import subprocess
from pathlib import Path

import pytest

from hm2e2e import BUILD, PFX, halrun, load, needs_vboard, num, tag, values, vboard

from hm2image import expected_pin_lines  # noqa: E402  (tests/driver, put on sys.path by hm2e2e)

pytestmark = needs_vboard

SVST8_4 = BUILD / "lib" / "firmware" / "hm2" / "5i20" / "SVST8_4.BIT"

# The seed's LinuxCNC printout for this config (head and tail of it; the
# full expectation comes from the .PIN CSV).
SEED = """\
hm2/hm2_5i20.0: 72 I/O Pins used:
hm2/hm2_5i20.0: IO Pin 000 (P2-01): IOPort
hm2/hm2_5i20.0: IO Pin 002 (P2-05): Encoder #0, pin B (Input)
hm2/hm2_5i20.0: IO Pin 003 (P2-07): Encoder #0, pin A (Input)
hm2/hm2_5i20.0: IO Pin 005 (P2-11): Encoder #0, pin Index (Input)
hm2/hm2_5i20.0: IO Pin 007 (P2-15): PWMGen #0, pin Out0 (PWM or Up) (Output)
hm2/hm2_5i20.0: IO Pin 009 (P2-19): PWMGen #0, pin Out1 (Dir or Down) (Output)
hm2/hm2_5i20.0: IO Pin 011 (P2-23): PWMGen #0, pin Not-Enable (Output)
hm2/hm2_5i20.0: IO Pin 060 (P4-25): StepGen #2, pin Step (Output)
hm2/hm2_5i20.0: IO Pin 061 (P4-27): StepGen #2, pin Direction (Output)
hm2/hm2_5i20.0: IO Pin 065 (P4-35): StepGen #2, pin (unused) (Output)
hm2/hm2_5i20.0: IO Pin 071 (P4-47): IOPort
"""


def squeeze(s: str) -> str:
    return re.sub(r" +", " ", s).strip()


def pin_lines(out: str) -> list[str]:
    return [squeeze(line) for line in out.splitlines() if "IO Pin " in line]


def hello(sock: Path) -> vboard.Hello:
    with vboard.VBoardClient(sock) as c:
        return c.hello()


@pytest.fixture
def blank(tmp_path: Path) -> Iterator[vboard.VBoardProcess]:
    with vboard.VBoardProcess(tmp_path / "b.sock", "5i20") as vb:
        yield vb


def test_firmware_load_and_seed_pinout(tmp_path: Path, blank: vboard.VBoardProcess) -> None:
    sock = Path(blank.socket_path)
    assert hello(sock).state == vboard.STATE_BLANK
    r = halrun(tmp_path, load(sock))
    assert r.returncode == 0, r.stdout + r.stderr
    out = r.stdout + r.stderr
    got = pin_lines(out)
    want = [
        squeeze(s) for s in expected_pin_lines("5i20", "PIN_SVST8_4_72.csv", {4: 1, 6: 1, 5: 3})
    ]
    assert got == want
    lines = {squeeze(line) for line in out.splitlines()}
    for line in SEED.splitlines():
        assert squeeze(line) in lines, line
    assert f"{PFX}: initialized virtual AnyIO board at {sock} (SVST8_4)" in out
    h = hello(sock)
    assert (h.state, h.firmware) == (vboard.STATE_CONFIGURED, "SVST8_4")


def test_firmware_found_without_environment(tmp_path: Path, blank: vboard.VBoardProcess) -> None:
    """After `make`, firmware=hm2/5i20/SVST8_4.BIT is found in the build's
    lib/firmware with neither $HM_BUILD nor $HM2_FIRMWARE_PATH set."""
    sock = Path(blank.socket_path)
    r = halrun(tmp_path, load(sock), drop_env=("HM_BUILD", "HM2_FIRMWARE_PATH"))
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert f"{PFX}: initialized virtual AnyIO board at {sock} (SVST8_4)" in out
    assert hello(sock).state == vboard.STATE_CONFIGURED


def test_hm2pinout_sim_source(tmp_path: Path) -> None:
    tool = BUILD / "bin" / "hm2pinout"
    with vboard.VBoardProcess(tmp_path / "b.sock", "5i20", "SVST8_4") as vb:
        cfg = "num_encoders=1 num_pwmgens=1 num_stepgens=3"
        r = subprocess.run(
            [str(tool), "-c", cfg, f"sim:{vb.socket_path}"],
            capture_output=True,
            text=True,
            timeout=60,
        )
        assert r.returncode == 0, r.stderr
        want = [
            squeeze(s) for s in expected_pin_lines("5i20", "PIN_SVST8_4_72.csv", {4: 1, 6: 1, 5: 3})
        ]
        assert pin_lines(r.stdout) == want
        p = subprocess.run(
            [str(tool), "-p", f"sim:{vb.socket_path}"], capture_output=True, text=True, timeout=60
        )
        assert p.returncode == 0, p.stderr
        assert "IO Connections for P4" in p.stdout
        assert re.search(
            r"^P4-01\s+48\s+IOPort\s+StepGen\s+0\s+Step/Table1\s+\(Out\)", p.stdout, re.M
        ), p.stdout
    # a blank board and a missing socket: clear errors
    with vboard.VBoardProcess(tmp_path / "c.sock", "5i20") as vb:
        r = subprocess.run(
            [str(tool), f"sim:{vb.socket_path}"], capture_output=True, text=True, timeout=60
        )
        assert r.returncode != 0 and "blank" in r.stderr
    r = subprocess.run(
        [str(tool), f"sim:{tmp_path}/none.sock"], capture_output=True, text=True, timeout=60
    )
    assert r.returncode != 0 and "cannot connect" in r.stderr


def _bit_chunks(bit: bytes) -> tuple[bytes, bytes]:
    """(everything before the 'e' payload, the payload)."""
    payload = vboard.bit_payload(bit)
    head = bit[: len(bit) - len(payload)]
    return head, payload


def bad_firmware(kind: str, fwdir: Path) -> str:
    """Write a bad firmware file under fwdir; return its name for firmware=."""
    good = SVST8_4.read_bytes()
    d = fwdir / "hm2" / "5i20"
    d.mkdir(parents=True, exist_ok=True)
    head, payload = _bit_chunks(good)
    if kind == "truncated":
        data = good[: len(good) - 10]
    elif kind == "corrupt":
        p = bytearray(payload)
        p[20] ^= 0x5A  # inside the image's board/firmware fields: CRC fails
        data = head + bytes(p)
    elif kind == "other-board":
        # 5i25 firmware whose .BIT claims the 5i20's part: the board itself refuses it
        other = (BUILD / "lib" / "firmware" / "hm2" / "5i25" / "7I76x2.BIT").read_bytes()
        _, opayload = _bit_chunks(other)
        data = head + opayload
    elif kind == "garbage":
        data = b"\x00" * 200
    else:
        raise AssertionError(kind)
    (d / f"{kind}.BIT").write_bytes(data)
    return f"hm2/5i20/{kind}.BIT"


@pytest.mark.parametrize(
    "kind,message",
    [
        ("missing", r"firmware hm2/5i20/missing\.BIT not found"),
        (
            "wrong-part",
            r"board has FPGA '2s200pq208', but the firmware in hm2/7i43/SV8\.BIT is for FPGA",
        ),
        ("truncated", r"bitfile|too short|truncated"),
        ("garbage", r"bitfile"),
        ("corrupt", r"refused the \d+-byte bitstream: .*"),
        ("other-board", r"refused the \d+-byte bitstream: .*5i25"),
    ],
)
def test_bad_firmware_board_stays_blank(
    tmp_path: Path, blank: vboard.VBoardProcess, kind: str, message: str
) -> None:
    sock = Path(blank.socket_path)
    env: dict[str, str] = {}
    if kind == "missing":
        name = "hm2/5i20/missing.BIT"
    elif kind == "wrong-part":
        name = "hm2/7i43/SV8.BIT"
    else:
        name = bad_firmware(kind, tmp_path / "fw")
        env["HM2_FIRMWARE_PATH"] = str(tmp_path / "fw")
    r = halrun(tmp_path, load(sock, config=f"firmware={name} num_encoders=1"), extra_env=env)
    out = r.stdout + r.stderr
    assert r.returncode != 0, out
    assert re.search(message, out), out
    assert "registered" not in [line.split(": ")[-1] for line in out.splitlines()]
    h = hello(sock)
    assert h.state == vboard.STATE_BLANK, out
    assert blank.proc.poll() is None  # the board survived


def test_blank_board_without_firmware(tmp_path: Path, blank: vboard.VBoardProcess) -> None:
    r = halrun(tmp_path, load(Path(blank.socket_path), config="num_encoders=1"))
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert "not configured" in out, out
    assert hello(Path(blank.socket_path)).state == vboard.STATE_BLANK


def test_bad_module_arguments(tmp_path: Path, blank: vboard.VBoardProcess) -> None:
    sock = Path(blank.socket_path)
    r = halrun(tmp_path, load(sock, board="7i43"))
    assert r.returncode != 0
    assert f"virtual board at {sock} is a 5i20, but board=7i43 was given" in r.stdout + r.stderr
    r = halrun(tmp_path, load(tmp_path / "nothing.sock"))
    assert r.returncode != 0
    assert (
        "cannot connect" in r.stdout + r.stderr and "is bin/vboard running?" in r.stdout + r.stderr
    )
    r = halrun(tmp_path, "loadrt hostmot2\nloadrt hm2_sim\n")
    assert r.returncode != 0 and "no board given" in r.stdout + r.stderr


def test_two_boards(tmp_path: Path) -> None:
    """socket=a,b config="...,...": two boards, hm2_5i20.0 and hm2_5i20.1, each
    with its own config string, as hm2_pci numbers boards of one type."""
    with vboard.VBoardProcess(tmp_path / "a.sock", "5i20") as a, vboard.VBoardProcess(
        tmp_path / "b.sock", "5i20", "SV12"
    ) as b:
        cfg0 = "firmware=hm2/5i20/SVST8_4.BIT num_encoders=1 num_pwmgens=0 num_stepgens=2"
        cfg1 = "num_encoders=3 num_pwmgens=2"
        s = (
            "loadrt hostmot2\n"
            f'loadrt hm2_sim socket={a.socket_path},{b.socket_path} board=5i20,5i20 config="{cfg0},{cfg1}"\n'
            "loadrt threads name1=servo period1=1000000\n"
            "addf hm2_5i20.0.read servo\naddf hm2_5i20.1.read servo\n"
            "addf hm2_5i20.0.write servo\naddf hm2_5i20.1.write servo\n"
            "simrun 2ms\n"
            "show pin hm2_5i20.0.stepgen\nshow pin hm2_5i20.1.encoder\n"
        )
        r = halrun(tmp_path, s)
        out = r.stdout + r.stderr
        assert r.returncode == 0, out
        assert f"hm2_5i20.0: initialized virtual AnyIO board at {a.socket_path} (SVST8_4)" in out
        assert f"hm2_5i20.1: initialized virtual AnyIO board at {b.socket_path} (SV12)" in out
        assert "hm2_5i20.0.stepgen.01.position-cmd" in out and "hm2_5i20.0.stepgen.02" not in out
        assert "hm2_5i20.1.encoder.02.count" in out and "hm2_5i20.1.encoder.03" not in out
        assert hello(Path(a.socket_path)).firmware == "SVST8_4"


def test_async_writes_real_board(tmp_path: Path) -> None:
    """async_writes=1 against the real board: the same steps come out."""
    with vboard.VBoardProcess(tmp_path / "b.sock", "5i20", "SVST8_4") as vb:
        sock = Path(vb.socket_path)
        sg = f"{PFX}.stepgen.00"
        s = load(sock, extra="async_writes=1")
        for k, val in [
            ("steplen", 5000),
            ("stepspace", 5000),
            ("dirsetup", 20000),
            ("dirhold", 20000),
            ("position-scale", 1000),
            ("maxvel", 40),
            ("maxaccel", 2000),
            ("enable", 1),
            ("position-cmd", 0.05),
        ]:
            s += f"setp {sg}.{k} {val}\n"
        s += "simrun 30ms\n"
        s += f"getp {sg}.position-fb\n"
        r = halrun(tmp_path, s)
        out = r.stdout + r.stderr
        assert r.returncode == 0 and "failed" not in out, out
        fb = [float(x) for x in r.stdout.split() if re.fullmatch(r"-?\d+\.\d+(e-?\d+)?", x)]
        assert fb and abs(fb[-1] - 0.05) < 0.0011, out
    assert vb.proc.returncode == 0


def test_lockstep_board_in_wall_clock_session(tmp_path: Path, blank: vboard.VBoardProcess) -> None:
    """A lockstep board (the default) in a wall-clock session is refused at
    once with what is wrong and what to do, instead of timing out as if the
    board were gone; the board is left untouched and still answers."""
    sock = Path(blank.socket_path)
    r = halrun(tmp_path, load(sock) + "show comp\n", simclock=False)
    out = r.stdout + r.stderr
    assert r.returncode != 0, out
    assert (
        f"hm2_sim: the virtual board at {sock} runs in lockstep (the vboard default) but this HAL "
        "session runs on the wall clock, so the board would fall behind real time; run the "
        "session on the simulated clock (halrun -S) or start the board with vboard --freerun"
    ) in out
    assert "the board is gone" not in out
    assert "no reply within the timeout" not in out
    h = hello(sock)
    assert (h.state, h.lockstep) == (vboard.STATE_BLANK, 1)


def test_freerun_board_in_wall_clock_session(tmp_path: Path) -> None:
    """A free-running board is the one for a wall-clock session: it loads and
    the servo thread runs against it."""
    with vboard.VBoardProcess(tmp_path / "f.sock", "5i20", args=["--freerun"]) as vb:
        sock = Path(vb.socket_path)
        script = load(sock) + "start\nloadusr -w sleep 0.3\nstop\n" + tag("err", f"{PFX}.io_error")
        r = halrun(tmp_path, script, simclock=False)
        out = r.stdout + r.stderr
        assert r.returncode == 0, out
        assert f"{PFX}: initialized virtual AnyIO board at {sock} (SVST8_4)" in out
        assert "runs in lockstep" not in out
        assert num(values(out), "err", 0) == 0, out
