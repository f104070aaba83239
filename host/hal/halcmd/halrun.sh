#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# halrun - run a HAL session: start it, run a .hal file with halcmd or a
# .tcl file with haltcl (or an interactive halcmd or haltcl), then stop the
# threads, unload everything and remove the session.  See docs/halrun.md.
#
#   halrun [-I] [-S] [halcmd options] [[-f] file.hal]
#   halrun [-T] [-S] [-i INI] [[-f] file.tcl]
#   halrun -U        clean up a session left behind by a crash
#   halrun -h
#
# The session is the one named by HAL_INSTANCE (default 0).

THIS=$(basename "$0")
BINDIR=$(cd "$(dirname "$(readlink -f "$0")")" && pwd)
HALCMD="$BINDIR/halcmd"
HALTCL="$BINDIR/haltcl"

help() {
    "$HALCMD" -h
    cat <<EOF

$THIS usage:
  $THIS [-I] [-S] [halcmd options] [filename.hal]
  $THIS [-T] [-S] [-i INI] [filename.tcl]
  $THIS -f filename          same as giving the file name
  $THIS -I                   interactive halcmd (after the file, if any)
  $THIS -T                   interactive haltcl (after the file, if any)
  $THIS -S                   simulated clock (same as HAL_SIMCLOCK=1)
  $THIS -U                   clean up after a crashed session
  $THIS -h                   this help
halcmd options passed on: -e -i INI -k -q -Q -R -s -v -V
A .tcl file runs with haltcl, which takes only -i INI.
Session: HAL_INSTANCE=${HAL_INSTANCE:-0}
EOF
}

INTERACTIVE=false
TCL_INTERACTIVE=false
filename=""
inifile=""
args=()
while getopts "ef:hi:kqsvIRQSTUV" opt; do
    case $opt in
    h) help; exit 0 ;;
    U) "$HALCMD" --session-kill >/dev/null 2>&1
       "$HALCMD" --session-destroy
       exit 0 ;;
    f) filename=$OPTARG ;;
    i) inifile=$OPTARG ;;
    I) INTERACTIVE=true ;;
    T) TCL_INTERACTIVE=true ;;
    S) export HAL_SIMCLOCK=1 ;;
    e|k|q|s|v|R|Q|V) args+=("-$opt") ;;
    \?) echo ""; echo "For usage try: $THIS -h"; exit 1 ;;
    esac
done
shift $((OPTIND - 1))

if [ $# -gt 1 ]; then
    echo "$THIS: too many arguments <$*>"
    exit 1
fi
if [ $# -gt 0 ]; then
    if [ -z "$filename" ]; then
        filename=$1
    else
        echo "$THIS: Error: Specified '-f $1' and also <$filename>"
        exit 1
    fi
fi
tclargs=()
if [ -n "$inifile" ]; then
    args+=(-i "$inifile")
    tclargs+=(-i "$inifile")
fi
IS_TCL=false
case "$filename" in
*.tcl) IS_TCL=true ;;
esac

# rtapi_app (started by halcmd on demand) shares this terminal; halrun
# waits for it at the end.  The halcmds run here leave the session to
# halrun's end (HAL_HALRUN).
export HAL_RTAPI_STDIO=inherit HAL_HALRUN=1

state=$("$HALCMD" --session-state 2>/dev/null)
case "$state" in
running)
    echo "$THIS: Realtime already running.  Use 'halrun -U' to stop existing realtime session." 1>&2
    exit 1 ;;
stale)
    echo "$THIS: found a stale HAL session (instance ${HAL_INSTANCE:-0}) left by a crashed run.  Use 'halrun -U' to clean it up." 1>&2
    exit 1 ;;
idle)
    echo "$THIS: HAL session (instance ${HAL_INSTANCE:-0}) is in use by halcmd outside halrun (signals or a lock left in it).  Use 'halrun -U' to remove it." 1>&2
    exit 1 ;;
esac

# Interrupted (Ctrl-C, SIGTERM, SIGHUP): stop the running halcmd, then
# still end the session, so nothing is left behind.  halcmd runs in the
# background with `wait`, which a signal interrupts at once.
child=
ending=false
end_session() {
    $ending && return
    ending=true
    if [ -n "$child" ]; then
        kill -TERM "$child" 2>/dev/null
        wait "$child" 2>/dev/null
    fi
    "$HALCMD" --session-end
}
trap 'end_session; exit 130' INT
trap 'end_session; exit 143' TERM
trap 'end_session; exit 129' HUP

run_halcmd() {
    "$@" <&0 &
    child=$!
    wait "$child"
    local rc=$?
    child=
    return $rc
}

result=0
if [ -n "$filename" ]; then
    if $IS_TCL; then
        run_halcmd "$HALTCL" "${tclargs[@]}" "$filename"; result=$?
    else
        run_halcmd "$HALCMD" "${args[@]}" -f "$filename"; result=$?
    fi
elif ! $TCL_INTERACTIVE; then
    INTERACTIVE=true
fi
if $TCL_INTERACTIVE; then
    run_halcmd "$HALTCL" "${tclargs[@]}"
elif $INTERACTIVE; then
    run_halcmd "$HALCMD" "${args[@]}" -kf
fi

# stop, unload all, wait for rtapi_app, remove the session
ending=true
"$HALCMD" --session-end || result=$?
exit $result
