// SPDX-License-Identifier: GPL-2.0-or-later
// bin2gray: binary number to its Gray code, LinuxCNC 2.9's names
// (docs/bin2gray.md).
component bin2gray "Convert a number to its Gray code";
pin in u32 in "Binary number";
pin out u32 out "Its Gray code";
function _ nofp;
license "GPL";
;;
FUNCTION(_) {
    out = in ^ (in >> 1);
}
