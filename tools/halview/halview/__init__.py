# SPDX-License-Identifier: GPL-2.0-or-later
"""halmeter, halscope, halshow and halweb: seeing inside a running HAL.

The front ends are Python; HAL is reached through libhalview.so (a small C
helper over libhal's public query API and scope_rt's shared memory), loaded
with ctypes by :mod:`halview.halapi`.
"""
