# SPDX-License-Identifier: GPL-2.0-or-later
# A 1 ms wall-clock thread runs about 300 times in 0.3 s, not at all
# while stopped, and measures its function's time.
halrun -f wall.hal
