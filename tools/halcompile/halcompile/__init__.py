# SPDX-License-Identifier: GPL-2.0-or-later
"""halcompile: the HAL component generator (.comp files), docs/halcompile.md."""
