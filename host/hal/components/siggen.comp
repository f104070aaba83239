// SPDX-License-Identifier: GPL-2.0-or-later
//
// siggen: signal generator (sine, cosine, sawtooth, triangle, square, clock)
// from one phase accumulator, for testing; LinuxCNC 2.9's names, its num_chan=
// load option and its output conventions (docs/siggen.md).
//
// Each period the phase (0 <= phase < 1, in cycles) advances by
// frequency * period and wraps at 1; a frequency above the Nyquist limit
// (0.5 cycles per period) is lowered to it and written back to the pin;
// reset holds the phase at 1/2.  With a = amplitude and o = offset:
//   sawtooth = (2 phase - 1) a + o
//   triangle = (1 - 4 phase) a + o for phase <= 1/2, (4 phase - 3) a + o after
//   square   = -a + o, clock FALSE for phase <= 1/2, +a + o, clock TRUE after
//   sine     = sin(w phase) a + o,   cosine = cos(w phase) a + o
// where w = 6.2831854, the 8-digit 2 pi that 2.9 uses (a sine of -4.6e-8 at
// phase 1/2 instead of +1.2e-16).
component siggen "Signal generator: sine, cosine, sawtooth, triangle, square, clock";
pin out float square;
pin out float sawtooth;
pin out float triangle;
pin out float sine;
pin out float cosine;
pin out bit clock;
pin in float frequency = 1.0 "Hz; lowered to the Nyquist limit when above it";
pin in float amplitude = 1.0;
pin in float offset = 0.0;
pin in bit reset "Holds the phase at 1/2 while TRUE";
variable double phase;
function update;
option rtapi_app no;
license "GPL";
;;
#include <rtapi_math.h>

#define SIGGEN_MAX_CHAN 16
#define SIGGEN_TWO_PI 6.2831854 /* sic, see above */

/* LinuxCNC's siggen counts its channels with num_chan=, not count= */
static int num_chan;
RTAPI_MP_INT(num_chan, "number of channels (default 1, at most 16)");
static char *names[SIGGEN_MAX_CHAN];
RTAPI_MP_ARRAY_STRING(names, SIGGEN_MAX_CHAN, "names of the channels");

/* 2.9 writes the lowered frequency back to this IN pin; the accessor of an
 * in pin is read-only, so make this one writable. */
#undef frequency
#define frequency (*__comp_inst->frequency)

FUNCTION(update) {
    if (reset) {
        phase = 0.5;
    } else {
        double step = frequency * fperiod;
        if (step > 0.5) {
            frequency = 0.5 / fperiod;
            step = 0.5;
        }
        phase += step;
        if (phase >= 1.0)
            phase -= 1.0;
    }
    double a = amplitude;
    double o = offset;
    double ph = phase;
    sawtooth = (ph * 2.0 - 1.0) * a + o;
    triangle = ((ph <= 0.5) ? 1.0 - ph * 4.0 : ph * 4.0 - 3.0) * a + o;
    if (ph > 0.5) {
        square = a + o;
        clock = 1;
    } else {
        square = -a + o;
        clock = 0;
    }
    sine = sin(ph * SIGGEN_TWO_PI) * a + o;
    cosine = cos(ph * SIGGEN_TWO_PI) * a + o;
}

int rtapi_app_main(void) {
    if (num_chan < 0 || num_chan > SIGGEN_MAX_CHAN) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "SIGGEN: ERROR: invalid number of channels: %d (1 to %d)\n", num_chan,
                        SIGGEN_MAX_CHAN);
        return -EINVAL;
    }
    halcomp_args_t args = {
        .count = num_chan,
        .names = names,
        .count_name = "num_chan",
        .max_count = SIGGEN_MAX_CHAN,
        .max_names = SIGGEN_MAX_CHAN,
    };
    return HALCOMP_LOAD(&args);
}

void rtapi_app_exit(void) {
    hal_exit(comp_id);
}
