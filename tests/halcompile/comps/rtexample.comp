// SPDX-License-Identifier: GPL-2.0-or-later
// The seed's "rtexample.comp" (its content is not shown there): a realtime
// component named "example", so that, as the seed says, `comp --compile
// rtexample.comp` leaves example.so and `comp --document` example's page.
component example "out follows in, scaled by gain";
pin in float in;
pin out float out "in * gain";
param rw float gain = 2.0;
function _;
license "GPL";
;;
out = in * gain;
