# SPDX-License-Identifier: GPL-2.0-or-later
"""A virtual board killed under a running HAL session: the driver reports
the error once (not every cycle), HAL keeps running its threads, clearing
io_error retries once and fails fast, unloading works, nothing hangs."""

from __future__ import annotations

import time
from pathlib import Path

from hm2e2e import PFX, halrun, load, needs_vboard, num, processes_mentioning, tag, values, vboard

pytestmark = needs_vboard


def test_killed_board(tmp_path: Path) -> None:
    vb = vboard.VBoardProcess(tmp_path / "b.sock", "5i20", "SVST8_4")
    try:
        sock = Path(vb.socket_path)
        s = load(sock)
        s += "loadrt siggen\naddf siggen.0.update servo\n"  # something else in the thread
        s += "simrun 3ms\n"
        s += tag("before", f"{PFX}.io_error", "siggen.0.sine")
        s += f"loadusr -w kill -KILL {vb.proc.pid}\n"
        s += "loadusr -w echo @@killed\n"
        s += "simrun 20ms\n"  # 20 servo periods against a dead board
        s += tag("after", f"{PFX}.io_error", "siggen.0.sine")
        s += f"setp {PFX}.io_error 0\n"  # the user retries
        s += "simrun 5ms\n"
        s += tag("retried", f"{PFX}.io_error")
        t0 = time.monotonic()
        r = halrun(tmp_path, s, timeout=60)
        wall = time.monotonic() - t0
    finally:
        vb.kill()
    out = r.stdout + r.stderr
    assert r.returncode == 0, out  # HAL ran to the end and unloaded
    assert wall < 20, f"the session took {wall:.1f} s: something waited on the dead board"
    v = values(out)
    assert num(v, "before", 0) == 0
    assert num(v, "after", 0) == 1
    assert num(v, "retried", 0) == 1
    # siggen kept running in the same thread (its output moved on)
    assert num(v, "after", 1) != num(v, "before", 1)
    # (stdout and stderr are separate pipes: count in the whole output; a
    # healthy board logs none of these lines before the kill)
    after_kill = out
    # 25 servo periods against the dead board, one retry: the transport
    # failure is reported once, the driver's io_error once at the kill and
    # once for the retry (which fails at once), not once per period
    assert after_kill.count("the board is gone") == 1, after_kill
    assert after_kill.count("read failed, setting io_error") == 2, after_kill
    assert after_kill.count("error flushing queued reads") == 2, after_kill
    assert after_kill.count("write failed, setting io_error") == 0, after_kill
    assert f"{PFX}: dropping virtual board" in out
    assert "hm2_sim: driver unloaded" in out
    # nothing left behind: the killed board's socket file is removed at
    # unload (it refuses connections), no process still runs on it
    assert out.count(f"hm2_sim: removed the socket {sock} left by the dead board") == 1, out
    assert not sock.exists()
    assert vb.proc.poll() is not None
    assert processes_mentioning(str(sock)) == []


def test_hung_board_times_out_once(tmp_path: Path) -> None:
    """A board that stops answering (SIGSTOP) costs one client timeout (5 s),
    then the driver fails fast like for a dead board."""
    vb = vboard.VBoardProcess(tmp_path / "b.sock", "5i20", "SVST8_4")
    try:
        s = load(Path(vb.socket_path))
        s += "simrun 2ms\n"
        s += f"loadusr -w kill -STOP {vb.proc.pid}\n"
        s += "simrun 10ms\n"
        s += tag("after", f"{PFX}.io_error")
        t0 = time.monotonic()
        r = halrun(tmp_path, s, timeout=60)
        wall = time.monotonic() - t0
    finally:
        vb.proc.send_signal(18)  # SIGCONT, so that the kill below is clean
        vb.kill()
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert num(values(out), "after", 0) == 1
    assert out.count("no reply within the timeout") == 1, out
    assert 4.5 < wall < 15, wall
