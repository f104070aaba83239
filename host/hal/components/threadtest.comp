// SPDX-License-Identifier: GPL-2.0-or-later
// threadtest: a counter for testing how threads call functions, LinuxCNC
// 2.9's names (docs/threadtest.md).
component threadtest "LinuxCNC HAL component for testing thread behavior";
pin out u32 count "Calls of increment since the last reset";
function increment nofp "count + 1";
function reset nofp "count = 0";
license "GPL";
;;
FUNCTION(increment) {
    count++;
}
FUNCTION(reset) {
    count = 0;
}
