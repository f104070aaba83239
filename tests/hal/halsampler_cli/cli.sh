#!/bin/sh
# SPDX-License-Identifier: GPL-2.0-or-later
# Command-line and attach errors of halsampler/halstreamer, run inside a
# session that has sampler and streamer channel 0 (threads not started).
try() {
    echo "\$ $*"
    "$@" 2>&1
    echo "rc=$?"
}
try halsampler -c x
try halsampler -c -1
try halsampler -c 8
try halsampler -n abc
try halsampler -n -3
try halsampler -x
try halsampler -t a b
try halsampler -c 1 -n 1
try halsampler -n 1 /nonexistent/dir/out.txt
try halsampler -N
try halsampler -n 0
try halstreamer -c x
try halstreamer -n 3
try halstreamer a b
try halstreamer /nonexistent/in.txt
try halstreamer -c 2 in.txt
# a second reader of a channel that has one is refused
halsampler -N first > first.out 2>&1 &
pid=$!
sleep 0.5
try halsampler -n 1
kill -TERM $pid
wait $pid
echo "first reader killed: rc=$?"
rm -f first.out
