# SPDX-License-Identifier: GPL-2.0-or-later
# A session whose processes died (here: rtapi_app killed with SIGKILL)
# leaves its segment behind; halrun must refuse to start on it and
# `halrun -U` must clean it up.
halcmd loadrt and2 || echo "setup failed"
pid=$(halcmd --session-rtapi-pid)
[ "$pid" -gt 0 ] && kill -9 "$pid"
sleep 0.2
echo "state: $(halcmd --session-state)"
halrun -f x.hal; echo "rc=$?"
halrun -U; echo "cleanup rc=$?"
echo "state: $(halcmd --session-state)"
halrun -f x.hal; echo "rc=$?"
echo "state: $(halcmd --session-state)"
