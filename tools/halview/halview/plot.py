# SPDX-License-Identifier: GPL-2.0-or-later
"""PNG and SVG pictures of a capture (matplotlib, no display needed).

One strip per channel, sharing the time axis (ms relative to the trigger);
bits and integers drawn as steps, floats as lines; the trigger as a dashed
vertical line.  A channel's scale/offset from the setup are applied.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import halapi  # noqa: E402
from .capture import Capture  # noqa: E402


def write_plot(cap: Capture, path: str, title: str = "") -> None:
    n = max(1, len(cap.channels))
    fig, axes = plt.subplots(n, 1, sharex=True, figsize=(10, 1.2 + 1.3 * n), squeeze=False)
    ref = cap.trigger if cap.trigger is not None else 0
    t_ms = (cap.index() - ref) * cap.interval / 1e6
    for ax, ch, col in zip(axes[:, 0], cap.channels, cap.columns):
        y = col * ch.scale + ch.offset
        if ch.type == halapi.HAL_FLOAT:
            ax.plot(t_ms, y, linewidth=1.0)
        else:
            ax.step(t_ms, y, where="post", linewidth=1.0)
        ax.set_ylabel(ch.name, rotation=0, ha="right", va="center", fontsize=8)
        ax.grid(True, alpha=0.3)
        if cap.trigger is not None:
            ax.axvline(0.0, color="red", linestyle="--", linewidth=0.8)
    axes[-1, 0].set_xlabel("time (ms) from the trigger" if cap.trigger is not None else "time (ms)")
    if title:
        fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, format="svg" if path.lower().endswith(".svg") else "png", dpi=100)
    plt.close(fig)
