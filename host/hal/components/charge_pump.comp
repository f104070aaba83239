// SPDX-License-Identifier: GPL-2.0-or-later
// charge_pump: square wave for the charge-pump input of controller boards
// (out toggles every call; out-2 and out-4 at 1/2 and 1/4 of its
// frequency), LinuxCNC 2.9's names (docs/charge_pump.md).
component charge_pump "Square wave for the charge pump input of controller boards";
pin out bit out "Toggles every period while enable is TRUE";
pin out bit out_2 "Half the frequency of out";
pin out bit out_4 "A quarter of the frequency of out";
pin in bit enable = TRUE "FALSE holds every output low";
variable unsigned phase;
option singleton yes;
function _ nofp "Toggle the outputs (if enabled)";
license "GPL";
;;
if (enable) {
    phase = (phase + 1) & 7u;
    out = phase & 1u;
    out_2 = (phase >> 1) & 1u;
    out_4 = (phase >> 2) & 1u;
} else {
    out = 0;
    out_2 = 0;
    out_4 = 0;
}
