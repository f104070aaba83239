// SPDX-License-Identifier: GPL-2.0-or-later
// estop_latch: software E-stop latch with two states, OK and faulted,
// LinuxCNC 2.9's names and defaults (docs/estop_latch.md).
component estop_latch "Software E-stop latch";
pin in bit ok_in = TRUE "FALSE faults the latch";
pin in bit fault_in = FALSE "TRUE faults the latch";
pin in bit reset "A rising edge leaves the faulted state if there is no fault";
pin out bit ok_out = FALSE "TRUE while OK";
pin out bit fault_out = TRUE "TRUE while faulted";
pin out bit watchdog "Toggles every period while OK";
variable int last_reset;
function _ nofp;
license "GPL";
;;
int r = reset;
int fault = fault_in || !ok_in;
if (fault) {
    ok_out = 0;
} else if (r && !last_reset) {
    ok_out = 1;
}
last_reset = r;
fault_out = !ok_out;
if (ok_out)
    watchdog = !watchdog;
