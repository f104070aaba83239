// SPDX-License-Identifier: GPL-2.0-or-later
// sim_home_switch: a home switch for simulated machines, LinuxCNC 2.9's
// names and behaviour (docs/sim_home_switch.md).
component sim_home_switch "Home switch simulator";
pin in float cur_pos "Current position (typically joint.N.motor-pos-fb)";
pin in float home_pos = 1.0 "Where the switch trips: at and beyond it, in the direction of its sign";
pin in float hysteresis = 0.1 "Travel back from home-pos needed to release the switch";
pin out bit home_sw "TRUE while the switch is tripped";
pin io bit index_enable "Connect to joint.N.index-enable: cleared index-delay-ms after it is set";
pin in float index_delay_ms = 10 "Delay in ms before index-enable is cleared (0 or less: never)";
variable int index_running;
variable double index_left;
function _;
license "GPL";
;;
FUNCTION(_) {
    if (home_pos < 0) {
        if (cur_pos <= home_pos)
            home_sw = 1;
        else if (cur_pos >= home_pos + hysteresis)
            home_sw = 0;
    } else {
        if (cur_pos >= home_pos)
            home_sw = 1;
        else if (cur_pos <= home_pos - hysteresis)
            home_sw = 0;
    }
    if (!index_enable) {
        index_running = 0;
    } else if (!index_running) {
        if (index_delay_ms > 0) {
            index_running = 1;
            index_left = index_delay_ms;
        }
    } else {
        index_left -= period * 1e-6; /* ms */
        if (index_left <= 0) {
            index_enable = 0;
            index_running = 0;
        }
    }
}
