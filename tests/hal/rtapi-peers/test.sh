# SPDX-License-Identifier: GPL-2.0-or-later
# rtapi_app's socket: peers are checked (SO_PEERCRED), a HAL group opens
# the session to its members, stalled or malformed clients block nobody
# and are dropped.  The other user is `nobody` (needs root to become it).
exec 2>&1
export HAL_RTAPI_CLIENT_TIMEOUT_MS=1000
py=/usr/bin/python3
uid=$(id -u)
if [ "$uid" != 0 ]; then echo "this test runs a client as another user: run it as root"; exit 1; fi
as_nobody() { setpriv --reuid=65534 --regid=65534 --clear-groups "$@"; }
trap 'halrun -U >/dev/null 2>&1' EXIT
here=$(pwd)
cd / || exit 1

echo "== private session"
halcmd loadrt and2
ls -l "/dev/shm/hm2hal-0-$HAL_INSTANCE" | cut -d' ' -f1,3,4
$py "$here/client.py" 0 list
as_nobody $py "$here/client.py" 0 list
as_nobody env HAL_OWNER=0 "$(command -v halcmd)" show comp; echo "nobody's halcmd rc=$?"
echo "== stalled, half and huge requests block nobody"
$py "$here/client.py" 0 stall > stall.out &
s1=$!
$py "$here/client.py" 0 half > half.out &
s2=$!
sleep 0.3
halcmd loadrt or2; echo "loadrt while stalled rc=$?"
$py "$here/client.py" 0 huge
wait $s1 $s2
cat stall.out half.out; rm -f stall.out half.out
halcmd unload all
echo "state $(halcmd --session-state)"

echo "== group session (HAL_GROUP=nogroup)"
HAL_GROUP=nogroup halcmd loadrt and2
ls -l "/dev/shm/hm2hal-0-$HAL_INSTANCE" | cut -d' ' -f1,3,4
as_nobody $py "$here/client.py" 0 list
as_nobody env HAL_OWNER=root "$(command -v halcmd)" loadrt or2; echo "nobody's loadrt rc=$?"
halcmd list comp
halcmd unload all
echo "state $(halcmd --session-state)"
HAL_GROUP=no_such_group_hm2 halcmd show comp; echo "bad group rc=$?"
