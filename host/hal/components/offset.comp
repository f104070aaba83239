// SPDX-License-Identifier: GPL-2.0-or-later
// offset: add an offset to a command and remove it from its feedback,
// LinuxCNC 2.9's names and output (docs/offset.md).
component offset "Adds an offset to an input, and subtracts it from the feedback value.";
pin in float offset "The offset";
pin in float in "The input";
pin out float out "in + offset";
pin in float fb_in "The feedback";
pin out float fb_out "fb-in - offset";
function update_output "out = in + offset";
function update_feedback "fb-out = fb-in - offset";
license "GPL";
;;
FUNCTION(update_output) {
    out = in + offset;
}
FUNCTION(update_feedback) {
    fb_out = fb_in - offset;
}
