# SPDX-License-Identifier: GPL-2.0-or-later
"""Shared cocotb infrastructure: the runner wrapper, bus models, pin monitors."""
