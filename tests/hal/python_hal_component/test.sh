#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Runs session.hal (a Python userspace component).  A test.sh rather than
# test.hal only so that a sanitized build (make test SANITIZE=1) can
# preload the ASan runtime for the uninstrumented Python interpreter.
cd "$(dirname "$0")"
build=${HM_BUILD:-$(cd ../../.. && pwd)/build}
ext=$(ls "$build"/lib/python/_hal*.so 2>/dev/null | head -1)
if [ -n "$ext" ]; then
    pre=$(ldd "$ext" | awk '/libasan|libubsan/ {print $3}' | tr '\n' ' ')
    if [ -n "$pre" ]; then
        export LD_PRELOAD="$pre" ASAN_OPTIONS=detect_leaks=0
    fi
fi
"$build/bin/halrun" -f session.hal 2>&1
