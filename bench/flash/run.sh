#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# What the JTAG MPSSE engine asks of a real FT2232H (stream bytes per TCK,
# commands per byte, load time of an LX9 bitstream), then hm2flash's flash
# write time on the virtual 5i25 with the flash part's own timing (board
# time per phase, and the wall time of the simulation).
# BENCH_FLASH_FULL=0 skips the full-size (342,816-byte) image and the
# --backup-flash of the whole 2 MiB M25P16, which take minutes of simulation
# (make test backs up a 128 KiB M25P10-A instead: tests/flash).  Runnable on its own.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${HM_BUILD:-$ROOT/build}"
for f in "$BUILD/bin/vboard" "$BUILD/bin/hm2flash" "$BUILD/bin/mpsse_bench"; do
    if [ ! -x "$f" ]; then
        echo "bench/flash: $f not built (make build)" >&2
        exit 1
    fi
done
"$BUILD/bin/mpsse_bench"
exec python3 "$ROOT/bench/flash/flash_bench.py" "$BUILD"
