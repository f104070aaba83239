// SPDX-License-Identifier: GPL-2.0-or-later
// carousel: drive a carousel tool changer to the requested pocket from
// position sensors (gray, binary, BCD, one sensor a pocket, index + pulse,
// pulse edges, encoder or stepgen counts), LinuxCNC 2.9's names, load
// options and behaviour (docs/carousel.md).
component carousel "Orient a toolchanger carousel using various encoding schemes";
pin in s32 pocket_number "The pocket to move to when enable goes high (beyond pockets: modulo)";
pin in bit enable "High starts the move; low stops it";
pin out bit active "The component is moving the carousel";
pin out bit ready "The carousel is at the requested pocket";
pin in bit strobe = 1 "The position feedback is valid";
pin in bit parity_ "Parity bit of the encoder";
pin in bit sense_#[32 : personality] "Position sensors (index mode: sense-0 index, sense-1 pocket pulse)";
pin in float rev_pulse "Seconds of reverse drive at the end of a move (ratchet changers)";
pin in float fwd_dc "Velocity or duty cycle forwards";
pin in float rev_dc "Velocity or duty cycle in reverse";
pin in float hold_dc "Duty cycle while in position";
pin in float align_dc "Velocity of the final alignment move";
pin in float decel_time "Seconds to wait for the carousel to stop before the alignment";
pin in s32 counts "Encoder or stepgen counts (counts mode)";
pin in s32 scale = 100 "Counts from one pocket to the next (counts mode)";
pin in s32 width = 0 "Counts either side of a pocket centre that count as the pocket (counts mode)";
pin in s32 home_offset = 0 "Counts from the index to pocket 1 (counts mode)";
pin io bit index_enable "Index-enable of the encoder (homing)";
pin in bit jog_fwd "Rising edge: one pocket forwards";
pin in bit jog_rev "Rising edge: one pocket in reverse (bidirectional only)";
pin out bit motor_fwd "Run the motor forwards";
pin out bit motor_rev "Run the motor in reverse";
pin out bit parity_error "The sensors and parity bit disagree with the parity";
pin out s32 current_position "The position the sensors report";
pin out float motor_vel "Velocity or duty cycle for the motor";
pin out bit homed = 0 "Homing is complete (index, edge and counts modes)";
pin in bit unhome = 0 "Forget the home";
param r s32 state = 0 "State of the component";
param r bit homing = 0 "Homing is in progress";
param r float timer "The internal timer";
param r s32 motor_dir "Direction of the move: 1 forwards, -1 reverse, 0 none";
param r u32 debounce "Periods the position has been stable";
variable int inst_pockets;
variable int inst_dir;
variable int inst_code;
variable int inst_parity;
variable int target;
variable int old_pulse;
variable int old_jog_fwd;
variable int old_jog_rev;
variable int old_index;
variable int base_counts;
variable int marker;
variable int jogging;
variable int old_marker;
function _;
option count_function yes;
option extra_setup yes;
modparam dummy pockets """The number of pockets of each carousel, comma separated (up to 8 carousels)""";
modparam dummy encoding """gray, binary, bcd, index, edge, counts or single (default gray), comma separated""";
modparam dummy num_sense """The number of sensor pins of each carousel (default 4)""";
modparam dummy dir """1 unidirectional, 2 bidirectional (default 2)""";
modparam dummy parity """1 odd parity, 0 even parity (default 0)""";
license "GPL";
;;
#include <rtapi_math.h>
#include <rtapi_string.h>

#define CAR_MAX 8
static int pockets[CAR_MAX] = {-1, -1, -1, -1, -1, -1, -1, -1};
RTAPI_MP_ARRAY_INT(pockets, CAR_MAX, "The number of pockets in each carousel");
static char *encoding[CAR_MAX];
RTAPI_MP_ARRAY_STRING(encoding, CAR_MAX, "Position encoding of each carousel");
static int num_sense[CAR_MAX] = {-1, -1, -1, -1, -1, -1, -1, -1};
RTAPI_MP_ARRAY_INT(num_sense, CAR_MAX, "The number of sensor pins of each carousel");
static int dir[CAR_MAX] = {-1, -1, -1, -1, -1, -1, -1, -1};
RTAPI_MP_ARRAY_INT(dir, CAR_MAX, "1 unidirectional, 2 bidirectional");
static int parity[CAR_MAX] = {-1, -1, -1, -1, -1, -1, -1, -1};
RTAPI_MP_ARRAY_INT(parity, CAR_MAX, "1 odd, 0 even parity");

/* the states (the state parameter shows them) */
enum {
    CAR_IDLE = 0,
    CAR_HOME_START = 1,
    CAR_MOVING = 2,
    CAR_REV_PULSE = 3,
    CAR_DECEL = 4,
    CAR_ALIGN_ON = 5,
    CAR_ALIGN_OFF = 6,
    CAR_ALIGN_FWD = 7,
    CAR_IN_POSITION = 9,
    CAR_HOMING = 10,
    CAR_HOMING_COUNTS = 11,
    CAR_JOG = 20,
};

int get_count(void)
{
    int n = 0;
    while (n < CAR_MAX && pockets[n] > 0)
        n++;
    return n > 0 ? n : 1;
}

/* A modparam array entry, or the one before it (or the default) when the
 * entry is missing. */
static int car_mp(const int *a, int i, int dflt)
{
    int v = dflt;
    int k;
    for (k = 0; k <= i; k++)
        if (a[k] >= 0)
            v = a[k];
    return v;
}

static int car_code(int i)
{
    const char *e = NULL;
    int k;
    for (k = 0; k <= i && k < CAR_MAX; k++)
        if (encoding[k] && encoding[k][0])
            e = encoding[k];
    if (!e)
        return 'G';
    if (strcmp(e, "binary") == 0)
        return 'B';
    if (strcmp(e, "bcd") == 0)
        return 'D';
    if (strcmp(e, "index") == 0)
        return 'I';
    if (strcmp(e, "edge") == 0)
        return 'E';
    if (strcmp(e, "counts") == 0)
        return 'C';
    if (strcmp(e, "single") == 0)
        return 'S';
    return 'G';
}

EXTRA_SETUP()
{
    inst_pockets = car_mp(pockets, extra_arg, 1);
    if (inst_pockets < 1) {
        rtapi_print_msg(RTAPI_MSG_ERR, "carousel: %s: pockets=%d: needs at least 1 pocket\n", prefix,
                        inst_pockets);
        return -EINVAL;
    }
    inst_code = car_code(extra_arg);
    inst_dir = car_mp(dir, extra_arg, 2);
    inst_parity = car_mp(parity, extra_arg, 0);
    personality = inst_code == 'I' ? 2 : car_mp(num_sense, extra_arg, 4);
    return 0;
}

/* The position the sensors give (gray, binary, bcd, single). */
static int car_decode(struct __comp_state *__comp_inst)
{
    int i, v = 0, p = 1;
    switch (inst_code) {
    case 'B':
        for (i = personality - 1; i >= 0; i--)
            v = (v << 1) | (sense(i) ? 1 : 0);
        return v;
    case 'D':
        for (i = 0; i < personality; i += 4) {
            int d = 0, k;
            for (k = 3; k >= 0; k--)
                d = (d << 1) | ((i + k < personality && sense(i + k)) ? 1 : 0);
            v += d * p;
            p *= 10;
        }
        return v;
    case 'S': /* the highest sensor that is on */
        for (i = 0; i < personality; i++)
            if (sense(i))
                v = i + 1;
        return v;
    default: /* gray */
        for (i = personality - 1; i >= 0; i--)
            v = (v << 1) | (((v & 1) ^ (sense(i) ? 1 : 0)) & 1);
        return v;
    }
}

/* The ones the parity covers: the sensor bits (none in single mode,
 * where parity-error is the parity pin against the parity). */
static int car_ones(struct __comp_state *__comp_inst)
{
    int i, n = 0;
    if (inst_code == 'S')
        return 0;
    for (i = 0; i < personality; i++)
        n += sense(i) ? 1 : 0;
    return n;
}

/* Whether pocket pulses count: index mode while moving to a pocket or
 * jogging, edge mode while a direction output is on (also while waiting
 * and aligning after a move, as LinuxCNC 2.9). */
static int car_counting(struct __comp_state *__comp_inst)
{
    if (inst_code == 'E')
        return motor_fwd || motor_rev;
    return state == CAR_MOVING || state == CAR_JOG;
}

/* Position from the sensors or the counts, each period. */
static void car_position(struct __comp_state *__comp_inst)
{
    int pulse, idx;
    switch (inst_code) {
    case 'I':
    case 'E':
        idx = sense(0) ? 1 : 0;
        pulse = personality > 1 && sense(1) ? 1 : 0;
        if (homing && idx && pulse) {
            current_position = 1;
            homed = 1;
        } else if (homed && car_counting(__comp_inst) &&
                   ((pulse && !old_pulse) || (inst_code == 'E' && !pulse && old_pulse))) {
            current_position += motor_dir;
            if (current_position > inst_pockets)
                current_position = 1;
            if (current_position < 1)
                current_position = inst_pockets;
        }
        old_pulse = pulse;
        old_index = idx;
        break;
    case 'C':
        if (homing && !index_enable && old_index) {
            base_counts = counts;
            homed = 1;
        }
        old_index = index_enable;
        if (homed && scale != 0) {
            long long sc = scale;
            long long c = (long long)counts - base_counts - home_offset;
            long long m = ((c % sc) + sc) % sc;
            long long pocket = (c - m) / sc;
            if (m <= width || m >= sc - width || width == 0) {
                if (width != 0 && m >= sc - width)
                    pocket++;
                current_position = (int)(((pocket % inst_pockets) + inst_pockets) % inst_pockets + 1);
            }
        }
        break;
    default:
        if (strobe) {
            current_position = car_decode(__comp_inst);
            parity_error =
                ((car_ones(__comp_inst) + (parity_ ? 1 : 0)) & 1) != inst_parity;
        }
        break;
    }
}

/* The position marker the alignment looks for: the pocket pulse (index
 * and edge modes) or being at the requested pocket. */
static void car_marker(struct __comp_state *__comp_inst)
{
    old_marker = marker;
    if (inst_code == 'I' || inst_code == 'E')
        marker = personality > 1 && sense(1);
    else
        marker = current_position == target;
}

static void car_stop(struct __comp_state *__comp_inst)
{
    motor_fwd = 0;
    motor_rev = 0;
    motor_vel = 0;
}

static void car_drive(struct __comp_state *__comp_inst, int d)
{
    motor_dir = d;
    motor_fwd = d > 0;
    motor_rev = d < 0;
    motor_vel = d > 0 ? fwd_dc : rev_dc;
}

/* The requested pocket: beyond pockets, modulo (pocket N is N). */
static int car_target(struct __comp_state *__comp_inst)
{
    int p = pocket_number;
    if (p > inst_pockets)
        p = (p - 1) % inst_pockets + 1;
    return p;
}

/* Direction to the target: the shorter way when bidirectional. */
static int car_direction(struct __comp_state *__comp_inst)
{
    int d = target - current_position;
    if (inst_dir != 2)
        return 1;
    if (d > inst_pockets / 2)
        d -= inst_pockets;
    if (d < -inst_pockets / 2)
        d += inst_pockets;
    return d > 0 ? 1 : -1;
}

static int car_needs_home(struct __comp_state *__comp_inst)
{
    return (inst_code == 'I' || inst_code == 'E' || inst_code == 'C') && !homed;
}

/* The move is over: a jog leaves ready as it was; without enable the
 * direction is forgotten. */
static void car_done(struct __comp_state *__comp_inst)
{
    car_stop(__comp_inst);
    motor_vel = hold_dc;
    active = 0;
    if (!jogging)
        ready = 1;
    jogging = 0;
    if (!enable)
        motor_dir = 0;
    state = enable ? CAR_IN_POSITION : CAR_IDLE;
}

/* At the pocket: the reverse pulse, the wait before the alignment, or
 * done. */
static void car_arrived(struct __comp_state *__comp_inst)
{
    if (decel_time > 0) {
        /* the direction outputs stay as they were, the velocity is 0 */
        timer = decel_time;
        motor_vel = 0;
        state = CAR_DECEL;
        return;
    }
    if (rev_pulse > 0) {
        timer = rev_pulse;
        motor_fwd = 0;
        motor_rev = 1;
        motor_vel = rev_dc;
        state = CAR_REV_PULSE;
        return;
    }
    car_done(__comp_inst);
}

FUNCTION(_)
{
    int jf = jog_fwd, jr = jog_rev;
    if (unhome)
        homed = 0;
    car_position(__comp_inst);
    car_marker(__comp_inst);
    switch (state) {
    case CAR_IDLE:
        if (enable && !jf && !jr) {
            active = 1;
            if (car_needs_home(__comp_inst)) {
                state = CAR_HOME_START;
                break;
            }
            ready = 0;
            target = car_target(__comp_inst);
            if (target == current_position) {
                motor_dir = car_direction(__comp_inst);
                car_arrived(__comp_inst);
                break;
            }
            car_drive(__comp_inst, car_direction(__comp_inst));
            state = CAR_MOVING;
            break;
        }
        if (!enable && ((jf && !old_jog_fwd) || (jr && !old_jog_rev && inst_dir == 2))) {
            /* both at once: back to where it is, in reverse */
            int up = jf && !old_jog_fwd, down = jr && !old_jog_rev;
            int d = up && !down ? 1 : -1;
            target = current_position + up - down;
            if (target > inst_pockets)
                target = 1;
            if (target < 1)
                target = inst_pockets;
            active = 1;
            jogging = 1;
            car_drive(__comp_inst, d);
            state = CAR_JOG;
        }
        break;
    case CAR_HOME_START:
        homing = 1;
        index_enable = 1;
        car_drive(__comp_inst, 1);
        state = inst_code == 'C' ? CAR_HOMING_COUNTS : CAR_HOMING;
        break;
    case CAR_HOMING:
    case CAR_HOMING_COUNTS:
        if (homed) {
            homing = 0;
            car_stop(__comp_inst);
            active = 0;
            state = CAR_IDLE;
            if (decel_time > 0)
                car_arrived(__comp_inst);
        }
        break;
    case CAR_MOVING:
        if (!enable) {
            car_stop(__comp_inst);
            active = 0;
            motor_dir = 0;
            state = CAR_IDLE;
            break;
        }
        target = car_target(__comp_inst);
        if (current_position == target)
            car_arrived(__comp_inst);
        break;
    case CAR_JOG:
        if (current_position == target)
            car_arrived(__comp_inst);
        break;
    case CAR_DECEL:
        timer -= fperiod;
        if (timer > 0)
            break;
        /* forwards: back onto the marker and off it; reverse: off it;
         * then forwards onto its edge */
        if (motor_dir > 0) {
            motor_vel = -align_dc;
            state = CAR_ALIGN_ON;
        } else {
            motor_vel = -align_dc;
            state = CAR_ALIGN_OFF;
        }
        break;
    case CAR_ALIGN_ON:
        if (marker && !old_marker)
            state = CAR_ALIGN_OFF;
        break;
    case CAR_ALIGN_OFF:
        if (!marker && old_marker) {
            motor_vel = align_dc;
            state = CAR_ALIGN_FWD;
        }
        break;
    case CAR_ALIGN_FWD:
        if (marker && !old_marker)
            car_done(__comp_inst);
        break;
    case CAR_REV_PULSE:
        timer -= fperiod;
        if (timer > 0)
            break;
        car_done(__comp_inst);
        break;
    case CAR_IN_POSITION:
        if (!enable) {
            motor_dir = 0;
            state = CAR_IDLE;
        }
        break;
    }
    old_jog_fwd = jf;
    old_jog_rev = jr;
}
