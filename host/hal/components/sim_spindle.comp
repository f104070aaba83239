// SPDX-License-Identifier: GPL-2.0-or-later
// sim_spindle: simulated spindle with an index pulse, LinuxCNC 2.9's names
// and output (docs/sim_spindle.md).
component sim_spindle "Simulated spindle with index pulse";
pin in float velocity_cmd "Commanded speed (rev/s after scale)";
pin out float position_fb "Position in revolutions";
pin io bit index_enable "Set TRUE to have position-fb wrap to 0..1 at the next whole revolution; cleared then";
param rw float scale = 1.0 "Factor from velocity-cmd to revolutions per second (1/60 for RPM)";
variable double pos;
function _;
license "GPL";
;;
#include <rtapi_math.h>
FUNCTION(_) {
    double old = pos;
    pos += velocity_cmd * scale * fperiod;
    if (index_enable && floor(pos) != floor(old)) {
        pos -= floor(pos);
        index_enable = 0;
    }
    position_fb = pos;
}
