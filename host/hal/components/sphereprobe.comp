// SPDX-License-Identifier: GPL-2.0-or-later
// sphereprobe: probe input from a pretend hemisphere on a plane, LinuxCNC
// 2.9's names and output (docs/sphereprobe.md).
component sphereprobe "Probe a pretend hemisphere";
pin in s32 px;
pin in s32 py;
pin in s32 pz "Position in counts (rawcounts of software encoders)";
pin in s32 cx;
pin in s32 cy;
pin in s32 cz "Centre of the sphere in counts";
pin in s32 r "Radius of the hemisphere in counts";
pin out bit probe_out "TRUE inside the sphere, or below the plane through its centre outside the sphere's footprint";
function _ nofp "Update probe-out from the position";
license "GPL";
;;
// 32-bit arithmetic that wraps around, as 2.9's (int) arithmetic does
rtapi_u32 dx = (rtapi_u32)px - (rtapi_u32)cx;
rtapi_u32 dy = (rtapi_u32)py - (rtapi_u32)cy;
rtapi_u32 dz = (rtapi_u32)pz - (rtapi_u32)cz;
rtapi_s32 rr = (rtapi_s32)((rtapi_u32)r * (rtapi_u32)r);
rtapi_s32 dxy = (rtapi_s32)(dx * dx + dy * dy);
if (dxy <= rr)
    probe_out = (rtapi_s32)(dx * dx + dy * dy + dz * dz) <= rr;
else
    probe_out = (rtapi_s32)dz < 0;
