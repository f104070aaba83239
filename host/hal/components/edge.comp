// SPDX-License-Identifier: GPL-2.0-or-later
// edge: a pulse of out-width-ns on the chosen edge(s) of in, LinuxCNC
// 2.9's names and defaults (docs/edge.md).
component edge "Edge detector";
pin in bit in;
pin out bit out "TRUE during the pulse that follows a selected edge";
pin out bit out_invert "FALSE during the pulse that follows a selected edge";
param rw bit both = FALSE "TRUE: both edges; FALSE: the edge chosen by in-edge";
param rw bit in_edge = TRUE "With both FALSE: TRUE selects falling edges, FALSE rising";
param rw s32 out_width_ns = 0 "Pulse length in ns (the pulse lasts at least one period)";
param r s32 time_left_ns "Time left in the current pulse";
param r bit last_in "The input of the previous period";
variable int first = 1;
function _ nofp "Produce output pulses from input edges";
license "GPL";
;;
int now = in;
int before = first ? now : last_in;
int hit;
first = 0;
if (both)
    hit = now != before;
else if (in_edge)
    hit = before && !now;
else
    hit = now && !before;
if (hit) {
    time_left_ns = out_width_ns;
    out = 1;
} else if (time_left_ns > 0) {
    out = 1;
} else {
    out = 0;
}
if (time_left_ns > 0)
    time_left_ns = time_left_ns > period ? time_left_ns - period : 0;
out_invert = !out;
last_in = now;
