# SPDX-License-Identifier: GPL-2.0-or-later
# rtapi_sim_yield(): a function waiting for a userspace peer holds virtual
# time still, and is released by the peer, by `stop`, or by unloading.
timeout 60 halrun -S -f yield.hal; echo "rc=$?"
