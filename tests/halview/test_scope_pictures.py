# SPDX-License-Identifier: GPL-2.0-or-later
"""halscope's pictures (--out .svg / .png) show the captured data: in the
SVG, each channel's trace has one point per sample (two per sample for
steps), its x evenly spaced, its y an exact affine image of the CSV's
values, the trigger line at the trigger sample; the PNG has a trace in
each channel's strip."""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib.image
import numpy as np
import pytest

from hvutil import BUILT, halrun, read_csv

pytestmark = pytest.mark.requires_build(*BUILT)

SAMPLES, POSITION = 50, 20
HAL = f"""\
loadrt threads name1=fast period1=100000
loadrt siggen
addf siggen.0.update fast
setp siggen.0.frequency 100
loadusr -Wn halscope halscope --thread fast -c siggen.0.sine,siggen.0.clock --trigger siggen.0.clock --samples {SAMPLES} --position {POSITION} -o p.svg -o p.png -o p.csv -q
simrun 50ms
waitusr halscope
"""
TRACE = "#1f77b4"  # the trace colour
MARK = "#ff0000"  # the trigger line


def paths(svg: str, colour: str) -> list[np.ndarray]:
    """The (x, y) points of every path drawn in that colour, in order."""
    out = []
    for m in re.finditer(r'<path d="([^"]*)"[^>]*?stroke: ' + colour, svg, re.S):
        nums = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", m.group(1))]
        out.append(np.array(nums).reshape(-1, 2))
    return out


def test_svg_and_png_show_the_capture(tmp_path: Path) -> None:
    r = halrun(tmp_path, HAL)
    assert r.returncode == 0, r.stderr
    _, rows = read_csv(tmp_path / "p.csv")
    sine = np.array([float(r[2]) for r in rows])
    clock = np.array([int(r[3]) for r in rows])
    trig = SAMPLES * POSITION // 100
    assert len(rows) == SAMPLES and clock[trig - 1] == 0 and clock[trig] == 1

    svg = (tmp_path / "p.svg").read_text()
    traces = paths(svg, TRACE)
    assert len(traces) == 2, "one trace per channel"
    xs = traces[0][:, 0]
    dx = np.diff(xs)
    assert len(xs) == SAMPLES and np.allclose(dx, dx[0], atol=0.02) and dx[0] > 0
    # y = a * value + b for one a < 0 (SVG's y grows downwards)
    a, b = np.polyfit(sine, traces[0][:, 1], 1)
    assert a < 0 and np.abs(a * sine + b - traces[0][:, 1]).max() < 0.02
    # the bit as steps: the value holds until the next sample
    steps = traces[1]
    assert len(steps) == 2 * SAMPLES - 1
    assert np.allclose(steps[::2, 0], xs, atol=0.02)
    assert np.allclose(steps[1::2, 0], xs[1:], atol=0.02)
    ys = steps[::2, 1]
    low, high = ys.max(), ys.min()
    assert low > high and np.array_equal(ys == high, clock == 1)
    assert np.array_equal(steps[1::2, 1], ys[:-1])
    # the trigger line (one per strip) at the trigger sample's x
    marks = paths(svg, MARK)
    assert len(marks) == 2 and all(np.allclose(m[:, 0], xs[trig], atol=0.02) for m in marks)

    png = matplotlib.image.imread(tmp_path / "p.png")
    assert png.shape[1] == 1000 and png.shape[0] > 200, png.shape
    blue = np.all(np.abs(png[:, :, :3] - np.array([0x1F, 0x77, 0xB4]) / 255) < 0.02, axis=2)
    rows_with_trace = np.nonzero(blue.any(axis=1))[0]
    half = png.shape[0] // 2
    assert (rows_with_trace < half).any() and (rows_with_trace >= half).any()
