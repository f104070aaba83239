# SPDX-License-Identifier: GPL-2.0-or-later
# Sessions survive faults and leave nothing behind: a killed rtapi_app is
# detected and refused until `halrun -U`; halcmd outside halrun and
# loadusr failures leave no stale session; a killed halrun is cleaned by
# `halrun -U`; an interrupted halrun ends its session.  "leftovers" lists
# what remains of the session: segment, log, socket, processes.
exec 2>&1
t=$(mktemp -d)
trap 'halrun -U >/dev/null 2>&1; rm -rf "$t"' EXIT
cp ./*.hal "$t"/ && cd "$t" || exit 1
seg=/dev/shm/hm2hal-$(id -u)-$HAL_INSTANCE
leftovers() {
    local what=""
    [ -e "$seg" ] && what="$what segment"
    ls "${XDG_RUNTIME_DIR:-/nonexistent}/hm2hal/" "/tmp/hm2hal-$(id -u)/" 2>/dev/null |
        grep -q "^hm2hal-$(id -u)-$HAL_INSTANCE.log$" && what="$what log"
    grep -q "@hm2hal-$(id -u)-$HAL_INSTANCE.rtapi" /proc/net/unix && what="$what socket"
    # a process counts while it is not a zombie (init may reap late)
    for p in "$@"; do
        ps -o stat= -p "$p" 2>/dev/null | grep -qv Z && what="$what process"
    done
    echo "leftovers:${what:- none}"
}

echo "== halcmd outside halrun, then unload all"
halcmd loadrt and2; echo "loadrt rc=$?"
rt=$(halcmd --session-rtapi-pid)
halcmd unload all; echo "unload rc=$?"
echo "state $(halcmd --session-state)"; leftovers "$rt"
halrun -f show.hal; echo "halrun rc=$?"

echo "== rtapi_app killed mid-run"
halcmd loadrt threads name1=t period1=1000000
halcmd loadrt and2
halcmd addf and2.0 t
halcmd start
rt=$(halcmd --session-rtapi-pid)
kill -9 "$rt"; sleep 0.2
halcmd show comp; echo "show rc=$?"
halcmd loadrt or2; echo "loadrt rc=$?"
echo "rtapi pid after: $(halcmd --session-rtapi-pid)"
echo "state $(halcmd --session-state)"
halrun -f show.hal; echo "halrun rc=$?"
halrun -U; echo "-U rc=$?"
echo "state $(halcmd --session-state)"; leftovers "$rt"
halrun -f show.hal; echo "halrun rc=$?"

echo "== halrun killed mid-run"
halrun -f long.hal > /dev/null 2>&1 &
hr=$!
for _ in $(seq 100); do [ "$(halcmd --session-state)" = running ] && break; sleep 0.05; done
sleep 0.3
rt=$(halcmd --session-rtapi-pid)
kill -9 "$hr"; wait "$hr" 2>/dev/null
halrun -f show.hal; echo "halrun rc=$?"
halrun -U; echo "-U rc=$?"
echo "state $(halcmd --session-state)"; leftovers "$rt"
pgrep -f "^sleep 7.5" > /dev/null && echo "the loadusr program survived"

echo "== halrun interrupted while loadusr -W waits for a program that never gets ready"
halrun -f never.hal > out 2>&1 &
hr=$!
for _ in $(seq 100); do pgrep -f "^sleep 8.25" > /dev/null && break; sleep 0.05; done
rt=$(halcmd --session-rtapi-pid)
kill -TERM "$hr"; wait "$hr"; echo "halrun rc=$?"
grep -o "interrupted.*" out
echo "state $(halcmd --session-state)"; leftovers "$rt"
pgrep -f "^sleep 8.25" > /dev/null && echo "the loadusr program survived"

echo "== loadusr -W of a program that exits without becoming ready"
halrun -f exits.hal; echo "halrun rc=$?"
echo "state $(halcmd --session-state)"; leftovers
halrun -f show.hal; echo "halrun rc=$?"
