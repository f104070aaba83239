// SPDX-License-Identifier: GPL-2.0-or-later
// The motion controller's joint position pins for `make compat` (docs/compat.md).
// Loaded as `loadrt compat_joint names=joint.0,joint.1,...`: each instance has
// joint.N.motor-pos-cmd (out) and joint.N.motor-pos-fb (in), so the
// configurations' nets of those pins stay as written.  Its function is never
// added to a thread: the command stays 0.
component compat_joint "stand-in for the motion controller's joint position pins (make compat only)";
pin out float motor_pos_cmd "the joint's commanded position (stays 0)";
pin in float motor_pos_fb "the joint's position feedback (not read)";
function _ "copies nothing: keeps motor-pos-cmd at 0";
license "GPL";
;;
FUNCTION(_) { motor_pos_cmd = 0.0; }
