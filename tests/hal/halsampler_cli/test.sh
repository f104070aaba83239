#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
cd "$(dirname "$0")"
build=${HM_BUILD:-$(cd ../../.. && pwd)/build}
PATH=$build/bin:$PATH "$build/bin/halrun" -f cli.hal 2>&1
echo "exit $?"
