# SPDX-License-Identifier: GPL-2.0-or-later
"""loadrt's search path with components installed by halcompile: the user
folder (`halcompile --install --user`) after $HAL_RTLIB_PATH and before the
build's lib/rtlib (docs/halcompile.md, docs/rtapi.md)."""

from __future__ import annotations

from pathlib import Path

from hcomp_util import hal_env, halcompile, halrun, pins
from test_features import COUNTED


def test_loadrt_finds_user_installed(tmp_path: Path) -> None:
    """`halcompile --install --user` then `loadrt` with no path settings:
    the user folder is searched (after $HAL_RTLIB_PATH, before the build's
    lib/rtlib), so a user's and2 replaces the built one, and a
    $HAL_RTLIB_PATH one replaces the user's (docs/halcompile.md)."""
    home = tmp_path / "home"
    home.mkdir()
    (tmp_path / "counted.comp").write_text(COUNTED)
    mine = 'component and2 "mine";\npin out s32 mine = 7;\nfunction _ nofp;\nlicense "GPL";\n;;\n'
    (tmp_path / "and2.comp").write_text(mine + "mine = 8;\n")
    env = hal_env(home=home)
    for k in ("HAL_RTLIB_DIR", "HAL_RTLIB_PATH"):
        env.pop(k, None)
    p = halcompile("--install", "--user", "counted.comp", "and2.comp", cwd=tmp_path, env=env)
    assert p.returncode == 0, p.stderr
    p = halrun("loadrt counted count=1\nloadrt and2\nshow pin\n", tmp_path, env)
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    assert "counted.0.id" in v
    assert v["and2.0.mine"] == ("s32", "OUT", "7") and "and2.0.in0" not in v
    first = tmp_path / "first"
    first.mkdir()
    (tmp_path / "x").mkdir()
    (tmp_path / "x" / "and2.comp").write_text(mine.replace("= 7", "= 9") + "mine = 8;\n")
    assert (
        halcompile(
            "--compile", "-o", str(first / "and2.so"), "and2.comp", cwd=tmp_path / "x"
        ).returncode
        == 0
    )
    env["HAL_RTLIB_PATH"] = str(first)
    p = halrun("loadrt and2\nshow pin\n", tmp_path, env)
    assert pins(p.stdout)["and2.0.mine"] == ("s32", "OUT", "9")
