// SPDX-License-Identifier: GPL-2.0-or-later
//
// bldc: commutation of three-phase motors from Hall sensors, absolute or
// incremental encoders or Fanuc 4-bit codes, to sinusoidal or trapezoidal
// drive signals, LinuxCNC 2.9's names, personalities (cfg=) and output
// (docs/bldc.md).  Written from the man page and 2.9's observed output.
component bldc "BLDC and AC-servo control component";

pin in bit hall1 if personality & 0x01 "Hall sensor 1";
pin in bit hall2 if personality & 0x01 "Hall sensor 2";
pin in bit hall3 if personality & 0x01 "Hall sensor 3";
pin out bit hall_error if personality & 0x01 "Set (and kept) once the Hall code is invalid for the pattern or skips a state";
pin in bit C1 if personality & 0x10 "Fanuc Gray code input, bit 0";
pin in bit C2 if personality & 0x10 "Fanuc Gray code input, bit 1";
pin in bit C4 if personality & 0x10 "Fanuc Gray code input, bit 2";
pin in bit C8 if personality & 0x10 "Fanuc Gray code input, bit 3";
pin in float value "Drive amplitude command (its sign reverses the motor)";
pin in float lead_angle if personality & 0x06 = 90 "Lead of the drive vector over the rotor, degrees";
pin in bit rev "TRUE reverses the motor";
pin in float frequency if (personality & 0x0F) == 0 "Electrical revolutions per second without feedback";
pin in float initvalue if personality & 0x04 = 0.2 "Drive amplitude while aligning an incremental encoder";
pin in s32 rawcounts if personality & 0x06 = 0 "Encoder raw counts (encoder.N.rawcounts)";
pin io bit index_enable if personality & 0x08 "Encoder index-enable: set while waiting for the index";
pin in bit init if (personality & 0x05) == 4 "A rising edge starts the alignment";
pin out bit init_done if (personality & 0x05) == 4 = 0 "TRUE once the encoder is aligned";
pin out float A_value if (personality & 0xF00) == 0 "Phase A drive";
pin out float B_value if (personality & 0xF00) == 0 "Phase B drive";
pin out float C_value if (personality & 0xF00) == 0 "Phase C drive";
pin out bit A_on if (personality & 0xF00) == 0x100 "Phase A high (trapezoidal, 3 outputs)";
pin out bit B_on if (personality & 0xF00) == 0x100 "Phase B high (trapezoidal, 3 outputs)";
pin out bit C_on if (personality & 0xF00) == 0x100 "Phase C high (trapezoidal, 3 outputs)";
pin out float A_high if (personality & 0xF00) == 0x200 "Phase A positive drive";
pin out float B_high if (personality & 0xF00) == 0x200 "Phase B positive drive";
pin out float C_high if (personality & 0xF00) == 0x200 "Phase C positive drive";
pin out float A_low if (personality & 0xF00) == 0x200 "Phase A negative drive (magnitude)";
pin out float B_low if (personality & 0xF00) == 0x200 "Phase B negative drive (magnitude)";
pin out float C_low if (personality & 0xF00) == 0x200 "Phase C negative drive (magnitude)";
pin out bit A_high_on if (personality & 0xF00) == 0x300 "Phase A high-side switch";
pin out bit B_high_on if (personality & 0xF00) == 0x300 "Phase B high-side switch";
pin out bit C_high_on if (personality & 0xF00) == 0x300 "Phase C high-side switch";
pin out bit A_low_on if (personality & 0xF00) == 0x300 "Phase A low-side switch";
pin out bit B_low_on if (personality & 0xF00) == 0x300 "Phase B low-side switch";
pin out bit C_low_on if (personality & 0xF00) == 0x300 "Phase C low-side switch";
pin out bit hall1_out if (personality & 0x400) "Emulated Hall sensor 1";
pin out bit hall2_out if (personality & 0x400) "Emulated Hall sensor 2";
pin out bit hall3_out if (personality & 0x400) "Emulated Hall sensor 3";
pin out bit C1_out if (personality & 0x800) "Emulated Fanuc Gray code, bit 0";
pin out bit C2_out if (personality & 0x800) "Emulated Fanuc Gray code, bit 1";
pin out bit C4_out if (personality & 0x800) "Emulated Fanuc Gray code, bit 2";
pin out bit C8_out if (personality & 0x800) "Emulated Fanuc Gray code, bit 3";
pin out float phase_angle = 0 "Angle of the drive vector, electrical revolutions (0..1)";
pin out float rotor_angle = 0 "Rotor angle, electrical revolutions (0..1)";
pin out float out "Amplitude with rev applied (initvalue while aligning)";
pin out bit out_dir "TRUE when value is negative XOR rev";
pin out float out_abs "Magnitude of value";

param r s32 in_type = -1 "Input mode in use (-1 before the first period, -2 disabled)";
param r s32 out_type = -1 "Output mode in use";
param rw s32 scale if personality & 0x06 = 512 "Encoder counts per rotor revolution";
param rw s32 poles if personality & 0x06 = 4 "Number of motor poles";
param rw s32 encoder_offset if personality & 0x0A = 0 "Counts from the encoder zero (or index) to motor zero";
param r s32 offset_measured if personality & 0x04 = 0 "Encoder offset found by the alignment";
param rw float drive_offset = 0 "Angle the drive adds to its command, degrees (shown in rotor-angle while aligning)";
param rw u32 output_pattern if personality & 0x400 = 25 "Hall pattern of the emulated Hall outputs (0..47)";
param rw u32 pattern if personality & 0x01 = 25 "Hall pattern of the Hall inputs (0..47)";

variable int old_raw;
variable int have_hall;
variable int last_idx;
variable int old_init;
variable int homed;
variable int last_gray;
variable int bits[3];
variable double timer = 2.4;
variable double angle;

function _;
option count_function yes;
option extra_setup yes;
modparam dummy cfg """Tags of each instance, comma separated (up to 8 instances)""";
license "GPL";
author "Andy Pugh (LinuxCNC's bldc); this implementation written for this project";
;;
#include <rtapi_math.h>

#define BLDC_MAX 8
static char *cfg[BLDC_MAX];
RTAPI_MP_ARRAY_STRING(cfg, BLDC_MAX, "tags of each instance");

// personality bits of the tags
#define P_HALL 0x01
#define P_ABS 0x02
#define P_QUAD 0x04
#define P_INDEX 0x08
#define P_FANUC 0x10
#define P_TRAP 0x1000

#define S3_2 0.8660254037844386 /* sqrt(3) / 2 */

// Hall codes (H1 H2 H3 as bits 2, 1, 0) for the excitations B-A, C-A, C-B,
// A-B, A-C, B-C of each of the 48 patterns (man 9 bldc)
static const unsigned char bldc_pat[48][6] = {
    {0, 1, 3, 7, 6, 4}, {1, 0, 2, 6, 7, 5}, {0, 2, 3, 7, 5, 4}, {1, 3, 2, 6, 4, 5},
    {2, 3, 1, 5, 4, 6}, {3, 2, 0, 4, 5, 7}, {2, 0, 1, 5, 7, 6}, {3, 1, 0, 4, 6, 7},
    {0, 1, 5, 7, 6, 2}, {1, 0, 4, 6, 7, 3}, {0, 2, 6, 7, 5, 1}, {1, 3, 7, 6, 4, 0},
    {2, 3, 7, 5, 4, 0}, {3, 2, 6, 4, 5, 1}, {2, 0, 4, 5, 7, 3}, {3, 1, 5, 4, 6, 2},
    {0, 4, 5, 7, 3, 2}, {1, 5, 4, 6, 2, 3}, {0, 4, 6, 7, 3, 1}, {1, 5, 7, 6, 2, 0},
    {2, 6, 7, 5, 1, 0}, {3, 7, 6, 4, 0, 1}, {2, 6, 4, 5, 1, 3}, {3, 7, 5, 4, 0, 2},
    {4, 5, 7, 3, 2, 0}, {5, 4, 6, 2, 3, 1}, {4, 6, 7, 3, 1, 0}, {5, 7, 6, 2, 0, 1},
    {6, 7, 5, 1, 0, 2}, {7, 6, 4, 0, 1, 3}, {6, 4, 5, 1, 3, 2}, {7, 5, 4, 0, 2, 3},
    {4, 5, 1, 3, 2, 6}, {5, 4, 0, 2, 3, 7}, {4, 6, 2, 3, 1, 5}, {5, 7, 3, 2, 0, 4},
    {6, 7, 3, 1, 0, 4}, {7, 6, 2, 0, 1, 5}, {6, 4, 0, 1, 3, 7}, {7, 5, 1, 0, 2, 6},
    {4, 0, 1, 3, 7, 6}, {5, 1, 0, 2, 6, 7}, {4, 0, 2, 3, 7, 5}, {5, 1, 3, 2, 6, 4},
    {6, 2, 3, 1, 5, 4}, {7, 3, 2, 0, 4, 5}, {6, 2, 0, 1, 5, 7}, {7, 3, 1, 0, 4, 6},
};

// drive of phases A, B, C for each excitation (source +1, sink -1)
static const signed char bldc_exc[6][3] = {
    {-1, 1, 0}, {-1, 0, 1}, {0, -1, 1}, {1, -1, 0}, {1, 0, -1}, {0, 1, -1},
};

int get_count(void)
{
    int n = 0;
    while (n < BLDC_MAX && cfg[n] != NULL)
        n++;
    if (n == 0)
        rtapi_print_msg(RTAPI_MSG_ERR, "The bldc component needs at least one feedback type "
                                       "tag.\nValid tags are h, a, q, i, b, 6, n\n");
    return n;
}

EXTRA_SETUP() {
    int p = 0;
    for (const char *c = cfg[extra_arg]; c != NULL && *c; c++) {
        switch (*c) {
        case 'h': p |= P_HALL; break;
        case 'a': p |= P_ABS; break;
        case 'q': p |= P_QUAD; break;
        case 'i': p |= P_INDEX; break;
        case 'f': p |= P_FANUC; break;
        case 'B': p |= 0x100; break;
        case '6': p |= 0x200; break;
        case 'H': p |= 0x400; break;
        case 'F': p |= 0x800; break;
        case 'T': p |= P_TRAP; break;
        default: break; // other letters (n) select nothing
        }
    }
    personality = p;
    return 0;
}

static double bldc_wrap(double x)
{
    return x - floor(x);
}

// the trapezoid sector whose centre is nearest (the lower one on a boundary)
static int bldc_sector6(double r)
{
    if (!isfinite(r))
        return 0;
    return (int)ceil(r * 6.0 - 0.5) % 6;
}

// the Hall input code as H1 H2 H3 bits, its excitation in the pattern or -1
static int bldc_hall_index(unsigned pat, int code)
{
    if (pat > 47)
        return -1;
    for (int k = 0; k < 6; k++)
        if (bldc_pat[pat][k] == code)
            return k;
    return -1;
}

#define HAS(bit) ((personality & (bit)) != 0)

// a op b keeping a's NaN when a is one, as x86 does for 2.9's operand order
// (the compiler may swap the operands of a commutative operation)
static double bldc_nan_first(double a, double r)
{
    return isnan(a) ? a : r;
}

// Outputs from the unscaled phase terms ta, tb, tc and the amplitude m:
// three values m * t, or the six high/low halves chosen by the sign of t
static void bldc_put3(struct __comp_state *__comp_inst, double m, double ta, double tb, double tc,
                      int trap)
{
    double a, b, c;
    if (trap) { // +m, -m or 0, not m times the drive sign
        a = ta > 0 ? m : ta < 0 ? -m : 0.0;
        b = tb > 0 ? m : tb < 0 ? -m : 0.0;
        c = tc > 0 ? m : tc < 0 ? -m : 0.0;
    } else {
        a = bldc_nan_first(m, m * ta);
        b = bldc_nan_first(m, m * tb);
        c = bldc_nan_first(m, m * tc);
    }
    if ((personality & 0xF00) == 0) {
        A_value = a;
        B_value = b;
        C_value = c;
    } else if ((personality & 0xF00) == 0x200) {
        A_high = ta > 0 ? a : 0.0;
        A_low = ta < 0 ? -a : 0.0;
        B_high = tb > 0 ? b : 0.0;
        B_low = tb < 0 ? -b : 0.0;
        C_high = tc > 0 ? c : 0.0;
        C_low = tc < 0 ? -c : 0.0;
    }
}

static void bldc_sine(struct __comp_state *__comp_inst, double ph, double m)
{
    double c = cos(2 * M_PI * ph), s = sin(2 * M_PI * ph);
    bldc_put3(__comp_inst, m, c, -0.5 * c + S3_2 * s, -0.5 * c - S3_2 * s, 0);
}

static int bldc_is_trap(struct __comp_state *__comp_inst)
{
    return HAS(P_TRAP) || out_type == 0x100 || out_type == 0x300 || in_type == 1 ||
           in_type == 5 || in_type == 13;
}

// Set the angles and the outputs.  hall is the excitation from the Hall
// inputs (-1 invalid) or -2 to take it from the rotor angle.
static void bldc_drive(struct __comp_state *__comp_inst, double m, int neg, double rotor,
                       double phase, int hall)
{
    rotor_angle = rotor;
    phase_angle = phase;
    if (out_type == 0x400) {
        unsigned op = output_pattern;
        int code = 0;
        if (hall == -2)
            code = op <= 47 ? bldc_pat[op][bldc_sector6(rotor)] : 0;
        else if (hall >= 0)
            code = op <= 47 ? bldc_pat[op][hall] : 0;
        else // 2.9 outputs the lowest code the pattern does not use
            while (op <= 47 && bldc_hall_index(op, code) >= 0)
                code++;
        hall1_out = (code >> 2) & 1;
        hall2_out = (code >> 1) & 1;
        hall3_out = code & 1;
        return;
    }
    if (out_type == 0x800) {
        int k = isfinite(rotor) ? (int)ceil(rotor * 16.0) - 1 : 0;
        if (k < 0)
            k = 0;
        int g = k ^ (k >> 1);
        C1_out = g & 1;
        C2_out = (g >> 1) & 1;
        C4_out = (g >> 2) & 1;
        C8_out = (g >> 3) & 1;
        return;
    }
    if (!bldc_is_trap(__comp_inst)) {
        bldc_sine(__comp_inst, phase, m);
        return;
    }
    int e = hall == -2 ? bldc_sector6(rotor) : hall;
    static const signed char none[3] = {0, 0, 0};
    const signed char *v = none;
    if (e >= 0)
        v = bldc_exc[neg ? (e + 3) % 6 : e];
    if (out_type == 0x100) {
        if (e < 0) {
            bits[0] = bits[1] = bits[2] = 0;
        }
        for (int k = 0; k < 3; k++) {
            if (v[k] > 0)
                bits[k] = 1;
            else if (v[k] < 0)
                bits[k] = 0;
        }
        A_on = bits[0];
        B_on = bits[1];
        C_on = bits[2];
    } else if (out_type == 0x300) {
        A_high_on = v[0] > 0;
        A_low_on = v[0] < 0;
        B_high_on = v[1] > 0;
        B_low_on = v[1] < 0;
        C_high_on = v[2] > 0;
        C_low_on = v[2] < 0;
    } else {
        bldc_put3(__comp_inst, m, v[0], v[1], v[2], 1);
    }
}

// Message and input mode for the tags, as 2.9 decides them
static int bldc_in_type(int p)
{
    switch (p & 0x1F) {
    case 0: case 1: case 2: case 4: case 5: case 12: case 13: case 16: case 20: case 28:
        return p & 0x1F;
    case 3: case 11:
        rtapi_print_msg(RTAPI_MSG_ERR, "Both Hall Sensors and Absolute encoder specified on "
                                       "the same motor. Only theEncoder will be used\n");
        return 2;
    case 10:
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "Index is not needed with an Absoluteencoder and will be ignored\n");
        return 2;
    case 6: case 7: case 14: case 15:
        rtapi_print_msg(RTAPI_MSG_ERR, "Specifying the use of both absolute and incremental "
                                       "encoders on the same motor is an error. Motor "
                                       "disabled\n");
        return -2;
    case 8:
        rtapi_print_msg(RTAPI_MSG_ERR, "Driving an electronically commutatedmotor with only "
                                       "an index for feedback is notpossible. Motor Disabled\n");
        return -2;
    case 9:
        rtapi_print_msg(RTAPI_MSG_ERR, "The use of an encoder Index with Hall sensors is not "
                                       "supported. Defaulting to trapezoidal commutation\n");
        return 1;
    default:
        rtapi_print_msg(RTAPI_MSG_ERR, "Unknown input type pattern (%X) in bldc\n", p & 0x1F);
        return -2;
    }
}

// encoder counts with half of the last period's motion added (2.9's latency
// compensation), integer arithmetic
static int bldc_counts(struct __comp_state *__comp_inst)
{
    int raw = rawcounts;
    int eff = raw + (int)(((long long)raw - old_raw) / 2);
    old_raw = raw;
    return eff;
}

static double bldc_rotor_from(struct __comp_state *__comp_inst, int c)
{
    int k = (int)((int32_t)((uint32_t)c * (uint32_t)poles) / 2);
    return bldc_wrap((double)k / scale);
}

// sinusoidal (or forced trapezoidal) commutation from the encoder
static void bldc_run_encoder(struct __comp_state *__comp_inst, double o, int neg)
{
    int eff = bldc_counts(__comp_inst);
    double rotor = bldc_rotor_from(__comp_inst, eff - encoder_offset - offset_measured);
    double lead = lead_angle / 360.0;
    double phase = bldc_wrap(bldc_nan_first(
        rotor, neg && !bldc_is_trap(__comp_inst) ? rotor - lead : rotor + lead));
    bldc_drive(__comp_inst, fabs(o), neg, rotor, phase, -2);
}

// encoder counts per electrical revolution
static double bldc_cpr(struct __comp_state *__comp_inst)
{
    return scale / (poles / 2.0);
}

// magnetic alignment of an incremental encoder: ramp the current in 0.4 s,
// turn the field to -90, +90 and back to 0 electrical degrees (0.8, 0.4 and
// 0.4 s), hold 0.4 s, then take the counts as motor zero
static void bldc_align(struct __comp_state *__comp_inst, long period, double o, int neg)
{
    int edge = init && !old_init;
    old_init = init;
    if (homed) {
        if (edge) {
            homed = 0;
            init_done = 0;
            timer = 2.4;
            return;
        }
        bldc_run_encoder(__comp_inst, o, neg);
        out = o;
        return;
    }
    if (!init)
        return;
    double t = timer, iv = initvalue, m = iv, ang = 0.0;
    if (t > 2.0)
        m = iv * ((2.4 - t) / (2.4 - 2.0));
    else if (t > 1.2)
        ang = -0.25 * ((2.0 - t) / (2.0 - 1.2));
    else if (t > 0.8)
        ang = -0.25 + 0.5 * ((1.2 - t) / (1.2 - 0.8));
    else if (t > 0.4)
        ang = 0.25 - 0.25 * ((0.8 - t) / (0.8 - 0.4));
    else if (t <= 0) {
        homed = 1;
        offset_measured = rawcounts;
    }
    ang = bldc_wrap(ang);
    init_done = homed;
    phase_angle = ang;
    rotor_angle = bldc_wrap(ang - drive_offset / 360.0);
    bldc_sine(__comp_inst, ang, m);
    out = m;
    timer -= fperiod;
    old_raw = rawcounts;
}

// alignment to the encoder index: turn the field at one electrical
// revolution per second until the encoder clears index-enable
static void bldc_index(struct __comp_state *__comp_inst, long period, double o)
{
    int edge = init && !old_init;
    old_init = init;
    int raw = rawcounts;
    if (init && !index_enable) {
        init_done = 1;
        offset_measured = raw;
        in_type = 2;
        bldc_sine(__comp_inst, angle, fabs(o));
        out = o;
        old_raw = raw;
        return;
    }
    if (edge)
        index_enable = 1;
    if (init) {
        angle = bldc_wrap(angle + fperiod);
        rotor_angle = angle;
        phase_angle = angle;
        bldc_sine(__comp_inst, angle, initvalue);
        out = initvalue;
    }
    old_raw = raw;
}

// the Hall index with the error check; *prev gets the last index or -3
static int bldc_hall(struct __comp_state *__comp_inst, int *prev)
{
    int code = (hall1 << 2) | (hall2 << 1) | hall3;
    int idx = bldc_hall_index(pattern, code);
    *prev = -3;
    if (have_hall) {
        *prev = last_idx;
        if (idx < 0 || (idx != last_idx && (idx - last_idx + 6) % 6 != 1 &&
                        (idx - last_idx + 6) % 6 != 5))
            hall_error = 1;
    }
    have_hall = 1;
    last_idx = idx;
    return idx;
}

FUNCTION(_) {
    double v = value;
    double o = rev ? -v : v;
    int neg = o < 0;
    out_abs = fabs(v);
    out_dir = neg;
    if (in_type == -1) {
        in_type = bldc_in_type(personality);
        int ot = personality & 0xF00;
        out_type = (ot & 0x400) ? 0x400 : (ot & 0x800) ? 0x800 : (ot & 0x300);
        if (HAS(P_INDEX) && (in_type == 12 || in_type == 13 || in_type == 28))
            index_enable = 1;
        if (HAS(P_ABS | P_QUAD))
            old_raw = rawcounts;
        if ((personality & 0x05) == 4)
            old_init = init;
        return;
    }
    switch (in_type) {
    case -2:
        return;
    case 0: // no feedback: the field turns at frequency
        angle = bldc_wrap(angle + frequency * fperiod);
        bldc_drive(__comp_inst, fabs(o), neg, angle, angle, -2);
        break;
    case 1: { // Hall sensors, trapezoidal
        int prev, idx = bldc_hall(__comp_inst, &prev);
        double rotor = idx >= 0 ? bldc_wrap((idx + 1) / 6.0) : 0.0;
        bldc_drive(__comp_inst, fabs(o), neg, rotor, bldc_wrap(rotor + (neg ? 0.25 : -0.25)),
                   idx);
        break;
    }
    case 2: // absolute (or aligned) encoder
        if ((personality & 0x1F) == 12 && init && !old_init) {
            // index alignment again
            old_init = init;
            homed = 0;
            init_done = 0;
            in_type = 12;
            index_enable = 1;
            angle = rotor_angle;
            return;
        }
        if ((personality & 0x05) == 4)
            old_init = init;
        bldc_run_encoder(__comp_inst, o, neg);
        break;
    case 4: // incremental encoder, magnetic alignment
        bldc_align(__comp_inst, period, o, neg);
        return;
    case 12: // incremental encoder, index alignment
        bldc_index(__comp_inst, period, o);
        return;
    case 5:
    case 13: { // Hall sensors until the first Hall edge (qh) or the index (qhi)
        int prev, idx = bldc_hall(__comp_inst, &prev);
        int raw = rawcounts;
        double rotor = idx >= 0 ? bldc_wrap((idx + 1) / 6.0) : 0.0;
        double phase = bldc_wrap(rotor + (neg ? 0.25 : -0.25));
        if (in_type == 5 && prev >= 0 && idx >= 0 && idx != prev) {
            // the edge between the two states, in the middle of their angles
            double r0 = rotor_angle, r1 = (idx + 1) / 6.0;
            if (r1 - r0 > 0.5)
                r0 += 1;
            else if (r0 - r1 > 0.5)
                r1 += 1;
            double e = bldc_wrap((r0 + r1) / 2);
            offset_measured = (int)(raw - e * bldc_cpr(__comp_inst));
            bldc_drive(__comp_inst, fabs(o), neg, e, bldc_wrap(e + (neg ? -0.25 : 0.25)), idx);
            in_type = 2;
        } else {
            bldc_drive(__comp_inst, fabs(o), neg, rotor, phase, idx);
            if (in_type == 13 && !index_enable) {
                offset_measured = raw;
                in_type = 2;
            }
        }
        old_raw = raw;
        break;
    }
    case 16:
    case 20:
    case 28: { // Fanuc Gray code; until its first edge (fq) or the index (fqi)
        int g = C1 | (C2 << 1) | (C4 << 2) | (C8 << 3);
        int k = g ^ (g >> 1) ^ (g >> 2) ^ (g >> 3);
        double rotor = (k + 0.5) / 16.0;
        if (in_type == 20 && g != last_gray && last_gray != 0) {
            double e = (k == 0 || k == 15 ? 0 : k + 1) / 16.0;
            offset_measured = (int)(rawcounts - e * bldc_cpr(__comp_inst));
            in_type = 2;
            rotor = e;
        } else if (in_type == 28 && !index_enable) {
            offset_measured = rawcounts;
            in_type = 2;
        }
        last_gray = g;
        bldc_drive(__comp_inst, fabs(o), neg, rotor, bldc_wrap(rotor + (neg ? -0.25 : 0.25)), -2);
        if (HAS(P_ABS | P_QUAD))
            old_raw = rawcounts;
        break;
    }
    }
    out = o;
}
