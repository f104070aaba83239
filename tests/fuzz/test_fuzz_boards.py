# SPDX-License-Identifier: GPL-2.0-or-later
"""libFuzzer targets of the board side: the hostmot2 .BIT parser, the IDROM
probe, the virtual board's firmware image check (hm2 'e' chunks and Pluto-P
uploads) and its socket protocol (server framing and dispatch, the EPP port
model), the Ethernet boards' LBP16 engine and hm2_eth's LBP16 reply checks
and request builder.  Each is built with clang (-fsanitize=fuzzer,address,undefined, UB
aborts) and run from its seed corpus in tests/fuzz/corpus/<target> for
HM_FUZZ_SECONDS (5 in `make test`, 60 in `make fuzz`).  A crash, sanitizer
report, leak or a 5 s hang fails the test and prints the reproducer.

clang with its libFuzzer runtime is required (`apt-get install clang`):
without it these tests fail, they do not skip."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HERE = ROOT / "tests" / "fuzz"
CORPUS = HERE / "corpus"
SECONDS = int(os.environ.get("HM_FUZZ_SECONDS", "5"))
DRV = ROOT / "host" / "driver"
VB = ROOT / "sim" / "verilator"

HM2CORE = [
    DRV / "llio" / "llio.c",
    DRV / "llio" / "boards.c",
    DRV / "llio" / "llio_image.c",
    *(
        DRV / "hostmot2" / f"{n}.c"
        for n in (
            "msg",
            "names",
            "config",
            "idrom",
            "md",
            "pins",
            "bitfile",
            "probe",
            "math",
        )
    ),
]
C_FLAGS = ["-I", str(DRV / "include"), "-I", str(ROOT / "host" / "hal" / "include")]
CXX_FLAGS = [
    "-std=c++17",
    "-I",
    str(VB / "src"),
    "-I",
    str(VB / "include"),
    "-I",
    str(VB / "epp"),
]
# The server owns the machine models (sim/verilator/src/plant), which use Eigen
# (headers only; Debian's libeigen3-dev puts them in /usr/include/eigen3).
EIGEN = ["-I", "/usr/include/eigen3"]
PLANT = [
    VB / "src" / "plant" / f"{n}.cpp"
    for n in ("config", "drive_input", "encoder", "machine", "motor", "toml")
]
# The server also owns the Smart Serial remote models (vboard --sserial).
SSERIAL = [VB / "src" / "sserial" / f"{n}.cpp" for n in ("link", "r7i76", "r7i77", "remotes")]

TARGETS: dict[str, tuple[str, list[str], list[Path]]] = {
    "hm2_bitfile": ("clang", C_FLAGS, [HERE / "fuzz_hm2_bitfile.c", *HM2CORE]),
    "hm2_idrom": ("clang", C_FLAGS, [HERE / "fuzz_hm2_idrom.c", *HM2CORE]),
    "lbp16_host": (
        "clang",
        ["-I", str(DRV / "backends" / "eth")],
        [HERE / "fuzz_lbp16_host.c", DRV / "backends" / "eth" / "lbp16.c"],
    ),
    "lbp16_responder": (
        "clang++",
        ["-std=c++17", "-I", str(VB / "eth")],
        [HERE / "fuzz_lbp16_responder.cpp", VB / "eth" / "lbp16.cpp"],
    ),
    "vboard_fwimage": (
        "clang++",
        CXX_FLAGS,
        [HERE / "fuzz_vboard_fwimage.cpp", VB / "src" / "fwimage.cpp"],
    ),
    "vboard_server": (
        "clang++",
        CXX_FLAGS + EIGEN + ["-pthread"],
        [
            HERE / "fuzz_vboard_server.cpp",
            VB / "src" / "server.cpp",
            VB / "src" / "pins.cpp",
            VB / "src" / "fwimage.cpp",
            VB / "epp" / "epp_port_board.cpp",
            *PLANT,
            *SSERIAL,
        ],
    ),
}


@pytest.fixture(scope="module")
def bindir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("fuzzbin")


def build(name: str, out: Path) -> Path:
    compiler, flags, sources = TARGETS[name]
    cc = shutil.which(compiler)
    assert cc is not None, f"{compiler} is required for the fuzz tests (apt-get install clang)"
    exe = out / f"fuzz_{name}"
    cmd = [
        cc,
        "-g",
        "-O1",
        "-fsanitize=fuzzer,address,undefined",
        "-fno-sanitize-recover=all",
        *flags,
        *map(str, sources),
        "-lm",
        "-o",
        str(exe),
    ]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, f"fuzz target {name} did not build:\n{' '.join(cmd)}\n{r.stderr}"
    return exe


@pytest.mark.parametrize("name", sorted(TARGETS))
def test_fuzz_target(name: str, bindir: Path, tmp_path: Path) -> None:
    seeds = CORPUS / name
    assert seeds.is_dir() and any(seeds.iterdir()), f"no seed corpus in {seeds}"
    exe = build(name, bindir)
    work = tmp_path / "corpus"  # new inputs go here, the kept corpus stays as it is
    shutil.copytree(seeds, work)
    r = subprocess.run(
        [
            str(exe),
            f"-max_total_time={SECONDS}",
            "-timeout=5",
            "-max_len=4096",
            "-rss_limit_mb=2048",
            f"-artifact_prefix={tmp_path}/",
            str(work),
        ],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=SECONDS + 300,
    )
    assert r.returncode == 0, f"{name}: libFuzzer found a problem:\n{r.stderr[-6000:]}"
    assert "Done " in r.stderr, r.stderr[-2000:]
    runs = int(r.stderr.rsplit("Done ", 1)[1].split()[0])
    assert runs > len(list(seeds.iterdir())), f"{name}: only {runs} runs:\n{r.stderr[-2000:]}"
