// SPDX-License-Identifier: GPL-2.0-or-later
// thc: torch height control for a Mesa THCAD voltage-to-frequency card on
// an encoder input, LinuxCNC 2.9's names and output (docs/thc.md).
component thc "Torch Height Control";
pin in float encoder_vel "Arc voltage as a frequency (the encoder's velocity)";
pin in float current_vel "Current tool velocity (motion.current-vel)";
pin in float requested_vel "Requested tool velocity (motion.requested-vel)";
pin in float volts_requested "Arc voltage to hold";
pin in float vel_tol "Velocity tolerance (corner lock); not used, as in 2.9";
pin in bit torch_on "Torch command (spindle.N.on)";
pin in bit arc_ok "Arc OK from the plasma source";
pin in bit enable "FALSE: Z passes through unchanged";
pin in float z_pos_in "Z position command from the planner";
pin out float z_pos_out "Z position command with the correction";
pin out float z_fb_out "Z position feedback to the planner (= z-pos-in)";
pin out float volts "Arc voltage: (encoder-vel - scale-offset) x vel-scale";
pin out bit vel_status "TRUE while the tool moves at (nearly) the requested velocity";
pin out float offset_value "The correction at the start of the period";
param rw float vel_scale "Volts per unit of encoder-vel";
param rw float scale_offset "encoder-vel at 0 V (the THCAD's zero frequency)";
param rw float velocity_tol "Percent below requested-vel still counted as at speed";
param rw float voltage_tol "Voltage error allowed before correcting";
param rw float correction_vel "Correction per period while the voltage is off";
variable float offset;
variable float last_z;
option singleton yes;
function _;
license "GPL";
;;
FUNCTION(_) {
    offset_value = offset;
    volts = (encoder_vel - scale_offset) * vel_scale;
    if (!enable) {
        z_pos_out = z_pos_in;
        z_fb_out = z_pos_in;
        return;
    }
    // at speed: moving forward, no slower than velocity-tol percent below
    vel_status = current_vel > 0 && current_vel >= requested_vel - requested_vel * velocity_tol / 100.0;
    if (torch_on) {
        // 2.9 tests the two tolerance edges independently: within the band
        // both apply and cancel (up to the float rounding of the offset)
        if (arc_ok && vel_status) {
            if (volts > volts_requested - voltage_tol)
                offset -= correction_vel;
            if (volts < volts_requested + voltage_tol)
                offset += correction_vel;
            last_z = 0;
        }
    } else {
        // torch off: take a positive correction out while Z moves up
        // (down to 0); a negative one follows Z (2.9); last_z is 0 after a
        // correcting period
        float dz = z_pos_in - last_z;
        if (offset > 0) {
            if (dz > 0)
                offset = offset - dz > 0 ? offset - dz : 0;
        } else if (offset < 0) {
            offset += dz;
        }
        last_z = z_pos_in;
    }
    z_pos_out = z_pos_in + offset;
    z_fb_out = z_pos_in;
}
