// SPDX-License-Identifier: GPL-2.0-or-later
// sim_axis_hardware: simulated home and limit switches for the axes X,
// tandem X, Y, tandem Y, Z, A, U and V, LinuxCNC 2.9's names and
// behaviour (docs/sim_axis_hardware.md).
component sim_axis_hardware "Simulated home and limit switches";
pin in float Xcurrent_pos "X: the position (joint.N.motor-pos-fb)";
pin in float Xhomesw_pos = 1 "X: where the home switch is";
pin in float Xmaxsw_upper "X: the maximum limit switch is on below this";
pin in float Xmaxsw_lower "X: ... and above this plus limit-offset";
pin in float Xminsw_upper "X: the minimum limit switch is on below this minus limit-offset";
pin in float Xminsw_lower "X: ... and above this";
pin in float Xhomesw_hyst = .025 "X: width of the home switch (home-pos +- half of it)";
pin in bit Xhoming "X: homing in progress (joint.N.homing)";
pin out bit Xhomesw_out "X: home switch";
pin out bit Xmaxsw_out "X: maximum limit switch";
pin out bit Xminsw_out "X: minimum limit switch";
pin out bit Xbothsw_out "X: either limit switch (FALSE while any axis homes)";
pin out bit Xmaxsw_homesw_out "X: maximum limit or home switch";
pin out bit Xminsw_homesw_out "X: minimum limit or home switch";
pin out bit Xbothsw_homesw_out "X: home switch, or either limit switch while no axis homes";
pin in float X2current_pos "X2: the position (joint.N.motor-pos-fb)";
pin in float X2homesw_pos = 1 "X2: where the home switch is";
pin in float X2maxsw_upper "X2: the maximum limit switch is on below this";
pin in float X2maxsw_lower "X2: ... and above this plus limit-offset";
pin in float X2minsw_upper "X2: the minimum limit switch is on below this minus limit-offset";
pin in float X2minsw_lower "X2: ... and above this";
pin in float X2homesw_hyst = .025 "X2: width of the home switch (home-pos +- half of it)";
pin in bit X2homing "X2: homing in progress (joint.N.homing)";
pin out bit X2homesw_out "X2: home switch";
pin out bit X2maxsw_out "X2: maximum limit switch";
pin out bit X2minsw_out "X2: minimum limit switch";
pin out bit X2bothsw_out "X2: either limit switch (FALSE while any axis homes)";
pin out bit X2maxsw_homesw_out "X2: maximum limit or home switch";
pin out bit X2minsw_homesw_out "X2: minimum limit or home switch";
pin out bit X2bothsw_homesw_out "X2: home switch, or either limit switch while no axis homes";
pin in float Ycurrent_pos "Y: the position (joint.N.motor-pos-fb)";
pin in float Yhomesw_pos = 1 "Y: where the home switch is";
pin in float Ymaxsw_upper "Y: the maximum limit switch is on below this";
pin in float Ymaxsw_lower "Y: ... and above this plus limit-offset";
pin in float Yminsw_upper "Y: the minimum limit switch is on below this minus limit-offset";
pin in float Yminsw_lower "Y: ... and above this";
pin in float Yhomesw_hyst = .025 "Y: width of the home switch (home-pos +- half of it)";
pin in bit Yhoming "Y: homing in progress (joint.N.homing)";
pin out bit Yhomesw_out "Y: home switch";
pin out bit Ymaxsw_out "Y: maximum limit switch";
pin out bit Yminsw_out "Y: minimum limit switch";
pin out bit Ybothsw_out "Y: either limit switch (FALSE while any axis homes)";
pin out bit Ymaxsw_homesw_out "Y: maximum limit or home switch";
pin out bit Yminsw_homesw_out "Y: minimum limit or home switch";
pin out bit Ybothsw_homesw_out "Y: home switch, or either limit switch while no axis homes";
pin in float Y2current_pos "Y2: the position (joint.N.motor-pos-fb)";
pin in float Y2homesw_pos = 1 "Y2: where the home switch is";
pin in float Y2maxsw_upper "Y2: the maximum limit switch is on below this";
pin in float Y2maxsw_lower "Y2: ... and above this plus limit-offset";
pin in float Y2minsw_upper "Y2: the minimum limit switch is on below this minus limit-offset";
pin in float Y2minsw_lower "Y2: ... and above this";
pin in float Y2homesw_hyst = .025 "Y2: width of the home switch (home-pos +- half of it)";
pin in bit Y2homing "Y2: homing in progress (joint.N.homing)";
pin out bit Y2homesw_out "Y2: home switch";
pin out bit Y2maxsw_out "Y2: maximum limit switch";
pin out bit Y2minsw_out "Y2: minimum limit switch";
pin out bit Y2bothsw_out "Y2: either limit switch (FALSE while any axis homes)";
pin out bit Y2maxsw_homesw_out "Y2: maximum limit or home switch";
pin out bit Y2minsw_homesw_out "Y2: minimum limit or home switch";
pin out bit Y2bothsw_homesw_out "Y2: home switch, or either limit switch while no axis homes";
pin in float Zcurrent_pos "Z: the position (joint.N.motor-pos-fb)";
pin in float Zhomesw_pos = 1 "Z: where the home switch is";
pin in float Zmaxsw_upper "Z: the maximum limit switch is on below this";
pin in float Zmaxsw_lower "Z: ... and above this plus limit-offset";
pin in float Zminsw_upper "Z: the minimum limit switch is on below this minus limit-offset";
pin in float Zminsw_lower "Z: ... and above this";
pin in float Zhomesw_hyst = .025 "Z: width of the home switch (home-pos +- half of it)";
pin in bit Zhoming "Z: homing in progress (joint.N.homing)";
pin out bit Zhomesw_out "Z: home switch";
pin out bit Zmaxsw_out "Z: maximum limit switch";
pin out bit Zminsw_out "Z: minimum limit switch";
pin out bit Zbothsw_out "Z: either limit switch (FALSE while any axis homes)";
pin out bit Zmaxsw_homesw_out "Z: maximum limit or home switch";
pin out bit Zminsw_homesw_out "Z: minimum limit or home switch";
pin out bit Zbothsw_homesw_out "Z: home switch, or either limit switch while no axis homes";
pin in float Acurrent_pos "A: the position (joint.N.motor-pos-fb)";
pin in float Ahomesw_pos = 1 "A: where the home switch is";
pin in float Amaxsw_upper "A: the maximum limit switch is on below this";
pin in float Amaxsw_lower "A: ... and above this plus limit-offset";
pin in float Aminsw_upper "A: the minimum limit switch is on below this minus limit-offset";
pin in float Aminsw_lower "A: ... and above this";
pin in float Ahomesw_hyst = .025 "A: width of the home switch (home-pos +- half of it)";
pin in bit Ahoming "A: homing in progress (joint.N.homing)";
pin out bit Ahomesw_out "A: home switch";
pin out bit Amaxsw_out "A: maximum limit switch";
pin out bit Aminsw_out "A: minimum limit switch";
pin out bit Abothsw_out "A: either limit switch (FALSE while any axis homes)";
pin out bit Amaxsw_homesw_out "A: stays FALSE (as in LinuxCNC 2.9)";
pin out bit Aminsw_homesw_out "A: stays FALSE (as in LinuxCNC 2.9)";
pin out bit Abothsw_homesw_out "A: stays FALSE (as in LinuxCNC 2.9)";
pin in float Ucurrent_pos "U: the position (joint.N.motor-pos-fb)";
pin in float Uhomesw_pos = 1 "U: where the home switch is";
pin in float Umaxsw_upper "U: the maximum limit switch is on below this";
pin in float Umaxsw_lower "U: ... and above this plus limit-offset";
pin in float Uminsw_upper "U: the minimum limit switch is on below this minus limit-offset";
pin in float Uminsw_lower "U: ... and above this";
pin in float Uhomesw_hyst = .025 "U: width of the home switch (home-pos +- half of it)";
pin in bit Uhoming "U: homing in progress (joint.N.homing)";
pin out bit Uhomesw_out "U: home switch";
pin out bit Umaxsw_out "U: maximum limit switch";
pin out bit Uminsw_out "U: minimum limit switch";
pin out bit Ubothsw_out "U: either limit switch (FALSE while any axis homes)";
pin out bit Umaxsw_homesw_out "U: maximum limit or home switch";
pin out bit Uminsw_homesw_out "U: minimum limit or home switch";
pin out bit Ubothsw_homesw_out "U: home switch, or either limit switch while no axis homes";
pin in float Vcurrent_pos "V: the position (joint.N.motor-pos-fb)";
pin in float Vhomesw_pos = 1 "V: where the home switch is";
pin in float Vmaxsw_upper "V: the maximum limit switch is on below this";
pin in float Vmaxsw_lower "V: ... and above this plus limit-offset";
pin in float Vminsw_upper "V: the minimum limit switch is on below this minus limit-offset";
pin in float Vminsw_lower "V: ... and above this";
pin in float Vhomesw_hyst = .025 "V: width of the home switch (home-pos +- half of it)";
pin in bit Vhoming "V: homing in progress (joint.N.homing)";
pin out bit Vhomesw_out "V: home switch";
pin out bit Vmaxsw_out "V: maximum limit switch";
pin out bit Vminsw_out "V: minimum limit switch";
pin out bit Vbothsw_out "V: either limit switch (FALSE while any axis homes)";
pin out bit Vmaxsw_homesw_out "V: maximum limit or home switch";
pin out bit Vminsw_homesw_out "V: minimum limit or home switch";
pin out bit Vbothsw_homesw_out "V: home switch, or either limit switch while no axis homes";
pin out bit homesw_all "Some home switch is on while some axis homes";
pin out bit limitsw_all "Some limit switch is on while no axis homes";
pin out bit limitsw_homesw_all "homesw-all or limitsw-all";
pin in float limit_offset = .01 "Added to maxsw-lower, taken off minsw-upper";
function update;
license "GPL";
;;
#include <rtapi_math.h>

typedef struct {
    int home, max, min;
} sah_switches_t;

/* The switches of one axis.  Written as the negation of "outside" so that
 * a NaN position (or bound) turns every switch on, as in LinuxCNC 2.9. */
static sah_switches_t sah_axis(double pos, double home_pos, double hyst, double max_lo,
                               double max_hi, double min_lo, double min_hi, double offset)
{
    sah_switches_t s;
    s.home = !(fabs(pos - home_pos) > hyst / 2.0);
    s.max = !(pos <= max_lo + offset || pos >= max_hi);
    s.min = !(pos <= min_lo || pos >= min_hi - offset);
    return s;
}

FUNCTION(update) {
    int homing = Xhoming || X2homing || Yhoming || Y2homing || Zhoming || Ahoming || Uhoming || Vhoming;
    int any_home = 0, any_limit = 0;
    sah_switches_t s;
    s = sah_axis(Xcurrent_pos, Xhomesw_pos, Xhomesw_hyst, Xmaxsw_lower,
                 Xmaxsw_upper, Xminsw_lower, Xminsw_upper, limit_offset);
    Xhomesw_out = s.home;
    Xmaxsw_out = s.max;
    Xminsw_out = s.min;
    Xbothsw_out = !homing && (s.max || s.min);
    Xmaxsw_homesw_out = s.max || s.home;
    Xminsw_homesw_out = s.min || s.home;
    Xbothsw_homesw_out = s.home || (!homing && (s.max || s.min));
    any_home |= s.home;
    any_limit |= s.max || s.min;
    s = sah_axis(X2current_pos, X2homesw_pos, X2homesw_hyst, X2maxsw_lower,
                 X2maxsw_upper, X2minsw_lower, X2minsw_upper, limit_offset);
    X2homesw_out = s.home;
    X2maxsw_out = s.max;
    X2minsw_out = s.min;
    X2bothsw_out = !homing && (s.max || s.min);
    X2maxsw_homesw_out = s.max || s.home;
    X2minsw_homesw_out = s.min || s.home;
    X2bothsw_homesw_out = s.home || (!homing && (s.max || s.min));
    any_home |= s.home;
    any_limit |= s.max || s.min;
    s = sah_axis(Ycurrent_pos, Yhomesw_pos, Yhomesw_hyst, Ymaxsw_lower,
                 Ymaxsw_upper, Yminsw_lower, Yminsw_upper, limit_offset);
    Yhomesw_out = s.home;
    Ymaxsw_out = s.max;
    Yminsw_out = s.min;
    Ybothsw_out = !homing && (s.max || s.min);
    Ymaxsw_homesw_out = s.max || s.home;
    Yminsw_homesw_out = s.min || s.home;
    Ybothsw_homesw_out = s.home || (!homing && (s.max || s.min));
    any_home |= s.home;
    any_limit |= s.max || s.min;
    s = sah_axis(Y2current_pos, Y2homesw_pos, Y2homesw_hyst, Y2maxsw_lower,
                 Y2maxsw_upper, Y2minsw_lower, Y2minsw_upper, limit_offset);
    Y2homesw_out = s.home;
    Y2maxsw_out = s.max;
    Y2minsw_out = s.min;
    Y2bothsw_out = !homing && (s.max || s.min);
    Y2maxsw_homesw_out = s.max || s.home;
    Y2minsw_homesw_out = s.min || s.home;
    Y2bothsw_homesw_out = s.home || (!homing && (s.max || s.min));
    any_home |= s.home;
    any_limit |= s.max || s.min;
    s = sah_axis(Zcurrent_pos, Zhomesw_pos, Zhomesw_hyst, Zmaxsw_lower,
                 Zmaxsw_upper, Zminsw_lower, Zminsw_upper, limit_offset);
    Zhomesw_out = s.home;
    Zmaxsw_out = s.max;
    Zminsw_out = s.min;
    Zbothsw_out = !homing && (s.max || s.min);
    Zmaxsw_homesw_out = s.max || s.home;
    Zminsw_homesw_out = s.min || s.home;
    Zbothsw_homesw_out = s.home || (!homing && (s.max || s.min));
    any_home |= s.home;
    any_limit |= s.max || s.min;
    s = sah_axis(Acurrent_pos, Ahomesw_pos, Ahomesw_hyst, Amaxsw_lower,
                 Amaxsw_upper, Aminsw_lower, Aminsw_upper, limit_offset);
    Ahomesw_out = s.home;
    Amaxsw_out = s.max;
    Aminsw_out = s.min;
    Abothsw_out = !homing && (s.max || s.min);
    /* As in LinuxCNC 2.9, A's three -homesw-out pins are never set. */
    any_home |= s.home;
    any_limit |= s.max || s.min;
    s = sah_axis(Ucurrent_pos, Uhomesw_pos, Uhomesw_hyst, Umaxsw_lower,
                 Umaxsw_upper, Uminsw_lower, Uminsw_upper, limit_offset);
    Uhomesw_out = s.home;
    Umaxsw_out = s.max;
    Uminsw_out = s.min;
    Ubothsw_out = !homing && (s.max || s.min);
    Umaxsw_homesw_out = s.max || s.home;
    Uminsw_homesw_out = s.min || s.home;
    Ubothsw_homesw_out = s.home || (!homing && (s.max || s.min));
    any_home |= s.home;
    any_limit |= s.max || s.min;
    s = sah_axis(Vcurrent_pos, Vhomesw_pos, Vhomesw_hyst, Vmaxsw_lower,
                 Vmaxsw_upper, Vminsw_lower, Vminsw_upper, limit_offset);
    Vhomesw_out = s.home;
    Vmaxsw_out = s.max;
    Vminsw_out = s.min;
    Vbothsw_out = !homing && (s.max || s.min);
    Vmaxsw_homesw_out = s.max || s.home;
    Vminsw_homesw_out = s.min || s.home;
    Vbothsw_homesw_out = s.home || (!homing && (s.max || s.min));
    any_home |= s.home;
    any_limit |= s.max || s.min;
    homesw_all = homing && any_home;
    limitsw_all = !homing && any_limit;
    limitsw_homesw_all = homesw_all || limitsw_all;
}
