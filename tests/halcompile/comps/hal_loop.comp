// SPDX-License-Identifier: GPL-2.0-or-later
component hal_loop;
pin out float example;
function _;
license "GPL";
;;
FUNCTION(_) { example = 1; }
