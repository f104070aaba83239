// SPDX-License-Identifier: GPL-2.0-or-later
// corexy_by_hal: CoreXY's motor/joint transformations as a HAL component,
// LinuxCNC 2.9's names (docs/corexy_by_hal.md).
component corexy_by_hal "CoreXY kinematics in HAL";
pin in float j0_motor_pos_cmd "From joint.0.motor-pos-cmd (X)";
pin in float j1_motor_pos_cmd "From joint.1.motor-pos-cmd (Y)";
pin in float alpha_fb "Feedback of the alpha motor";
pin in float beta_fb "Feedback of the beta motor";
pin out float j0_motor_pos_fb "To joint.0.motor-pos-fb";
pin out float j1_motor_pos_fb "To joint.1.motor-pos-fb";
pin out float alpha_cmd "Command of the alpha motor: (j0 + j1) / 2";
pin out float beta_cmd "Command of the beta motor: (j0 - j1) / 2";
function _;
license "GPL";
;;
FUNCTION(_) {
    alpha_cmd = 0.5 * (j0_motor_pos_cmd + j1_motor_pos_cmd);
    beta_cmd = 0.5 * (j0_motor_pos_cmd - j1_motor_pos_cmd);
    j0_motor_pos_fb = alpha_fb + beta_fb;
    j1_motor_pos_fb = alpha_fb - beta_fb;
}
