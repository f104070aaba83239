# SPDX-License-Identifier: GPL-2.0-or-later
"""`make memcheck`: valgrind memcheck over our C code, where ASan does not look.

1. Every ctest test (the C unit tests) runs under valgrind with its own
   command line, environment and working directory as ctest lists them
   (``ctest --show-only=json-v1``).
2. A HAL core session: ``halrun -f`` on the wall clock with two threads,
   and2/or2/siggen/sampler, nets, aliases, show/save/status/list, delf,
   unloadrt and unload all (halcmd and rtapi_app under valgrind).
3. One HAL session: ``halrun -S`` (the HAL file on stdin) with hostmot2 +
   hm2_sim on a virtual 5i20 running SVST8_4 (bin/vboard, not under
   valgrind: it is Verilated C++ and the board, not the host code under
   test), a servo thread with the
   driver's read/write functions, 20 ms of simulated time, then unload.
   halcmd and rtapi_app (where hostmot2 and hm2_sim run) are both under
   valgrind: halrun finds halcmd next to itself, so a copy of halrun sits in
   a private bin/ beside a halcmd wrapper, and HAL_RTAPI_APP names an
   rtapi_app wrapper.
4. The same session with the board inside rtapi_app (hm2_sim inproc=1,
   lib/libvboard_inproc.so, 10 ms), rtapi_app under valgrind.

Errors and leaks (definite and indirect) fail the run; the logs stay in
BUILD/memcheck/.  Suppressions: scripts/valgrind.supp, each with the reason
it is not ours to fix.  Needs the non-sanitized build (valgrind and ASan do
not mix): the Makefile runs it on build/.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import re
import shutil
import subprocess
import sys
import time
import uuid
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SUPP = ROOT / "scripts" / "valgrind.supp"
ERRORS = re.compile(r"ERROR SUMMARY: (\d+) errors")
VALGRIND_RC = 99


def valgrind_cmd(log: str) -> list[str]:
    return [
        "valgrind",
        "--tool=memcheck",
        f"--error-exitcode={VALGRIND_RC}",
        "--leak-check=full",
        "--show-leak-kinds=definite,indirect",
        "--errors-for-leak-kinds=definite,indirect",
        "--num-callers=30",
        "--child-silent-after-fork=yes",
        f"--suppressions={SUPP}",
        f"--log-file={log}",
    ]


def ctest_tests(build: Path) -> list[dict[str, object]]:
    """The tests ctest knows, with command, environment and directory."""
    r = subprocess.run(
        ["ctest", "--show-only=json-v1"], cwd=build, capture_output=True, text=True, check=True
    )
    out = []
    for t in json.loads(r.stdout)["tests"]:
        env: dict[str, str] = {}
        cwd = str(build)
        for p in t.get("properties", []):
            if p["name"] == "ENVIRONMENT":
                env.update(v.split("=", 1) for v in p["value"])  # type: ignore[misc]
            elif p["name"] == "WORKING_DIRECTORY":
                cwd = p["value"]
        out.append({"name": t["name"], "command": t["command"], "env": env, "cwd": cwd})
    return out


def errors_in(log: Path) -> int:
    m = ERRORS.findall(log.read_text(errors="replace"))
    return int(m[-1]) if m else -1


def run_units(build: Path, out: Path) -> list[str]:
    failed = []
    for t in ctest_tests(build):
        name = str(t["name"])
        log = out / f"unit-{name}.log"
        env = dict(os.environ, **t["env"])  # type: ignore[arg-type]
        start = time.monotonic()
        r = subprocess.run(
            valgrind_cmd(str(log)) + list(t["command"]),  # type: ignore[call-overload]
            cwd=str(t["cwd"]),
            env=env,
            capture_output=True,
            text=True,
            timeout=1800,
        )
        n = errors_in(log)
        verdict = "ok" if r.returncode == 0 and n == 0 else "FAILED"
        print(f"  {name:<28s} {verdict:<7s} {n:3d} errors  {time.monotonic() - start:6.1f} s")
        if verdict != "ok":
            failed.append(f"unit {name}: exit {r.returncode}, {n} valgrind errors (log {log})")
            if r.returncode not in (0, VALGRIND_RC):
                sys.stdout.write(r.stdout[-3000:] + r.stderr[-3000:])
    return failed


SESSION = """\
loadrt hostmot2
loadrt hm2_sim socket={sock} board=5i20 config="firmware=hm2/5i20/SVST8_4.BIT num_encoders=1 num_pwmgens=1 num_stepgens=3"
loadrt threads name1=servo period1=1000000
addf hm2_5i20.0.read servo
addf hm2_5i20.0.write servo
setp hm2_5i20.0.stepgen.00.position-scale 1000
setp hm2_5i20.0.stepgen.00.steplen 5000
setp hm2_5i20.0.stepgen.00.stepspace 5000
setp hm2_5i20.0.stepgen.00.maxvel 25
setp hm2_5i20.0.stepgen.00.maxaccel 1000
setp hm2_5i20.0.stepgen.00.enable 1
setp hm2_5i20.0.stepgen.00.position-cmd 0.01
setp hm2_5i20.0.pwmgen.00.enable 1
setp hm2_5i20.0.pwmgen.00.value 0.5
setp hm2_5i20.0.gpio.000.is_output 1
setp hm2_5i20.0.gpio.000.out 1
simrun 20ms
getp hm2_5i20.0.stepgen.00.counts
show pin hm2_5i20.0.encoder.00
"""


def wrapper(path: Path, target: Path, logs: Path, tag: str) -> None:
    path.write_text(
        "#!/bin/sh\n"
        f"exec {' '.join(valgrind_cmd(str(logs / (tag + '.%p.log'))))} {target} \"$@\"\n"
    )
    path.chmod(0o755)


def run_session(build: Path, out: Path, inproc: bool = False) -> list[str]:
    sys.path.insert(0, str(ROOT / "tests" / "common"))
    import vboard  # noqa: PLC0415

    tag = "inproc" if inproc else "session"
    work = out / tag
    bindir = work / "bin"
    bindir.mkdir(parents=True)
    shutil.copy(build / "bin" / "halrun", bindir / "halrun")
    wrapper(bindir / "halcmd", build / "bin" / "halcmd", out, f"{tag}-halcmd")
    wrapper(bindir / "rtapi_app", build / "bin" / "rtapi_app", out, f"{tag}-rtapi_app")
    sock = Path("/tmp") / f"mc{uuid.uuid4().hex[:8]}.sock"
    hal = SESSION.format(sock=sock)
    if inproc:
        hal = hal.replace(f"socket={sock}", "inproc=1").replace("simrun 20ms", "simrun 10ms")
    (work / "session.hal").write_text(hal)
    env = dict(os.environ)
    env.pop("HAL_SIMCLOCK", None)
    env.update(
        HAL_INSTANCE=f"memcheck-{uuid.uuid4().hex[:8]}",
        HAL_RTAPI_APP=str(bindir / "rtapi_app"),
        HM_BUILD=str(build),
        PATH=f"{build / 'bin'}:{env.get('PATH', '')}",
    )
    start = time.monotonic()
    # The file goes in on stdin (the core session reads its file with -f).
    board = contextlib.nullcontext() if inproc else vboard.VBoardProcess(sock, "5i20")
    with board, open(work / "session.hal") as hal:
        r = subprocess.run(
            [str(bindir / "halrun"), "-S"],
            stdin=hal,
            env=env,
            capture_output=True,
            text=True,
            timeout=1800,
        )
    subprocess.run([str(build / "bin" / "halrun"), "-U"], env=env, capture_output=True)
    (work / "halrun.out").write_text(r.stdout + r.stderr)
    failed = []
    if r.returncode != 0:
        failed.append(f"HAL session: halrun exit {r.returncode} (output {work / 'halrun.out'})")
    logs = sorted(out.glob(f"{tag}-*.log"))
    for kind in ("halcmd", "rtapi_app"):
        if not any(p.name.startswith(f"{tag}-{kind}.") for p in logs):
            failed.append(f"HAL session: no valgrind log of {kind}: it did not run under valgrind")
    for log in logs:
        n = errors_in(log)
        if n != 0:
            failed.append(f"HAL session: {n} valgrind errors in {log}")
    name = "hostmot2 + hm2_sim inproc=1" if inproc else "hostmot2 + hm2_sim session"
    print(
        f"  {name:<30s} {'ok' if not failed else 'FAILED':<7s}"
        f" {len(logs)} processes  {time.monotonic() - start:6.1f} s"
    )
    if "hm2_5i20.0: initialized virtual AnyIO board" not in r.stdout + r.stderr:
        failed.append(f"HAL session: the board did not initialize (output {work / 'halrun.out'})")
    return failed


CORE_SESSION = """\
loadrt threads name1=fast period1=1000000 name2=slow period2=2000000
loadrt and2 count=3
loadrt or2 names=o1,o2
loadrt siggen
loadrt sampler depth=100 cfg=ff
addf and2.0 fast
addf and2.1 fast
addf o1 slow
addf siggen.0.update slow
addf sampler.0 slow
net a and2.0.out => o1.in0 and2.1.in0
net s siggen.0.sine => sampler.0.pin.0
net t siggen.0.cosine => sampler.0.pin.1
newsig x float
alias pin and2.2.in0 myin
setp myin 1
start
loadusr -w sleep 0.3
stop
show
save all
status
list pin -tbit
delf and2.1 fast
unalias pin and2.2.in0
unloadrt or2
delsig all
unload all
"""


def run_core_session(build: Path, out: Path) -> list[str]:
    work = out / "core"
    bindir = work / "bin"
    bindir.mkdir(parents=True)
    shutil.copy(build / "bin" / "halrun", bindir / "halrun")
    wrapper(bindir / "halcmd", build / "bin" / "halcmd", out, "core-halcmd")
    wrapper(bindir / "rtapi_app", build / "bin" / "rtapi_app", out, "core-rtapi_app")
    (work / "core.hal").write_text(CORE_SESSION)
    env = dict(os.environ)
    env.pop("HAL_SIMCLOCK", None)
    env.update(
        HAL_INSTANCE=f"memcheck-core-{uuid.uuid4().hex[:8]}",
        HAL_RTAPI_APP=str(bindir / "rtapi_app"),
        HM_BUILD=str(build),
        PATH=f"{build / 'bin'}:{env.get('PATH', '')}",
    )
    start = time.monotonic()
    r = subprocess.run(
        [str(bindir / "halrun"), "-f", str(work / "core.hal")],
        env=env,
        capture_output=True,
        text=True,
        timeout=1800,
    )
    subprocess.run([str(build / "bin" / "halrun"), "-U"], env=env, capture_output=True)
    (work / "halrun.out").write_text(r.stdout + r.stderr)
    failed = []
    if r.returncode != 0:
        failed.append(
            f"HAL core session: halrun exit {r.returncode} (output {work / 'halrun.out'})"
        )
    if r.stdout.count("Loaded HAL Components:") != 1:
        failed.append(f"HAL core session: the file did not run once (output {work / 'halrun.out'})")
    logs = sorted(out.glob("core-*.log"))
    rtapi_logs = [p for p in logs if p.name.startswith("core-rtapi_app.")]
    if len(rtapi_logs) != 1:
        failed.append(f"HAL core session: {len(rtapi_logs)} rtapi_app runs, expected 1")
    for log in logs:
        n = errors_in(log)
        if n != 0:
            failed.append(f"HAL core session: {n} valgrind errors in {log}")
    print(
        f"  HAL core session               {'ok' if not failed else 'FAILED':<7s}"
        f" {len(logs)} processes  {time.monotonic() - start:6.1f} s"
    )
    return failed


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--build", type=Path, default=Path(os.environ.get("HM_BUILD", ROOT / "build")))
    args = ap.parse_args()
    build: Path = args.build.resolve()
    cache = (build / "CMakeCache.txt").read_text()
    if re.search(r"^SANITIZE:BOOL=ON$", cache, re.M):
        print(f"memcheck: {build} is a sanitized build; valgrind needs build/ (no SANITIZE)")
        return 2
    out = build / "memcheck"
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir()
    start = time.monotonic()
    print(f"memcheck: C unit tests under valgrind (logs in {out})")
    failed = run_units(build, out)
    print("memcheck: a HAL core session under valgrind")
    failed += run_core_session(build, out)
    print("memcheck: a HAL session with hostmot2 + hm2_sim under valgrind")
    failed += run_session(build, out)
    print("memcheck: the same with the board inside rtapi_app (hm2_sim inproc=1) under valgrind")
    failed += run_session(build, out, inproc=True)
    for f in failed:
        print(f"  FAIL: {f}")
    took = time.monotonic() - start
    print(f"memcheck: {'FAILED' if failed else 'ok'} ({took:.0f} s)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
