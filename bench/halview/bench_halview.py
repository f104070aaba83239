# SPDX-License-Identifier: GPL-2.0-or-later
"""bench/halview, part 2: the live page's update rate and latency with 100
watched pins in headless chromium (see run.sh)."""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
import uuid
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("HM_BUILD", ROOT / "build"))
BIN = BUILD / "bin"
sys.path.insert(0, str(ROOT / "tools" / "halview"))
sys.path.insert(0, str(ROOT / "tests" / "halview"))
os.environ.setdefault("HAL_INSTANCE", "hvbench-" + uuid.uuid4().hex[:8])
os.environ.pop("HAL_SIMCLOCK", None)

from halview import halapi  # noqa: E402


def halcmd(*args: str) -> None:
    subprocess.run([str(BIN / "halcmd"), *args], check=True, capture_output=True, text=True)


def page_bench(tmp: Path) -> None:
    from cdp import Browser

    hal = tmp / "page.hal"
    hal.write_text(
        "loadrt threads name1=t period1=1000000\nloadrt siggen num_chan=16\n"
        + "".join(f"addf siggen.{i}.update t\n" for i in range(16))
        + "start\n"
    )
    halcmd("-f", str(hal))
    procs = []
    try:
        halapi.require_session()
        pins = [p for p in halapi.list_names(halapi.PIN, "siggen") if "update" not in p][:100]
        assert len(pins) == 100
        with Browser() as b:
            for rate in (20, 100):
                p = subprocess.Popen(
                    [
                        str(BIN / "halweb"),
                        "--page",
                        "meter",
                        "--rate",
                        str(rate),
                        "--port",
                        "0",
                        *[f"pin+{n}" for n in pins],
                    ],
                    stdout=subprocess.PIPE,
                    stderr=subprocess.PIPE,
                    text=True,
                )
                procs.append(p)
                assert p.stdout is not None
                url = p.stdout.readline().split()[1]
                page = b.new_page(url)
                page.wait_for("window.halweb.stats.updates > 10", 30)
                page.eval("window.halweb.stats.updates = 0; window.halweb.stats.latencies = []")
                t0 = time.monotonic()
                time.sleep(10)
                st = page.eval("window.halweb.stats")
                dt = time.monotonic() - t0
                lat = sorted(st["latencies"])
                med = statistics.median(lat) * 1e3
                p99 = lat[int(len(lat) * 0.99) - 1] * 1e3
                shown = page.eval("document.querySelectorAll('#watch-list tr').length")
                print(
                    f"page, {shown} watched pins, --rate {rate}: {st['updates'] / dt:.1f} "
                    f"updates/s drawn, latency HAL read -> next frame median {med:.1f} ms, "
                    f"99% {p99:.1f} ms"
                )
                page.close()
                p.terminate()
                p.wait(timeout=30)
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
        subprocess.run([str(BIN / "halrun"), "-U"], capture_output=True)


def main() -> int:
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        page_bench(Path(tmp))
    return 0


if __name__ == "__main__":
    sys.exit(main())
