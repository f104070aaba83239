// SPDX-License-Identifier: GPL-2.0-or-later
// invert: 1/in with a dead band around 0, LinuxCNC 2.9's names and output
// (docs/invert.md).
component invert "Compute the inverse of the input signal";
pin in float in "Input";
pin out float out "1 / in, or 0 within the dead band";
param rw float deadband "Within +-deadband (at least 1e-12) out is +-1/deadband";
function _;
license "GPL";
;;
double db = deadband < 1e-12 ? 1e-12 : deadband;
if (in > -db && in < db)
    out = in >= 0.0 ? 1.0 / db : -1.0 / db;
else
    out = 1.0 / in;
