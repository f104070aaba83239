// SPDX-License-Identifier: GPL-2.0-or-later
// updown: an up/down counter on rising edges, with optional clamping or
// wrapping at min/max, LinuxCNC 2.9's names and defaults (docs/updown.md).
component updown "Up/down counter with optional limits and wraparound";
pin in bit countup "A rising edge adds 1";
pin in bit countdown "A rising edge subtracts 1";
pin in bit reset "TRUE holds count at 0 (edges of countup/countdown are ignored)";
pin out s32 count "The count";
param rw bit clamp "TRUE: count stays within min..max";
param rw bit wrap "TRUE: count wraps around within min..max (implies clamp)";
param rw s32 max_ = 0x7FFFFFFF "Upper limit with clamp or wrap";
param rw s32 min_ "Lower limit with clamp or wrap";
variable int last_up;
variable int last_down;
variable int first = 1;
function _ nofp "Process the inputs and update count";
license "GPL";
;;
int up = countup, down = countdown;
if (first) {
    /* the first period only learns the inputs: a countup already TRUE at
     * start is not an edge */
    last_up = up;
    last_down = down;
    first = 0;
}
long long c = count;
if (reset) {
    c = 0;
} else {
    if (up && !last_up)
        c++;
    if (down && !last_down)
        c--;
}
last_up = up;
last_down = down;
if (wrap) {
    if (c > max_)
        c = min_;
    else if (c < min_)
        c = max_;
} else if (clamp) {
    if (c > max_)
        c = max_;
    else if (c < min_)
        c = min_;
}
/* without limits the s32 count wraps around like the integer it is */
count = (hal_s32_t)(uint32_t)(uint64_t)c;
