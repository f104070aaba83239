# SPDX-License-Identifier: GPL-2.0-or-later
"""Python reference models and helpers shared by the Pluto-P cocotb tests."""
