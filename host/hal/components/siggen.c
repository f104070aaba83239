/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * siggen - signal generator: sine, cosine, sawtooth, triangle, square and
 * clock outputs from one phase accumulator, for testing.
 *
 *   loadrt siggen [num_chan=N | names=a,b,...]     (N <= 16, default 1)
 *
 * Per channel (prefix siggen.N or the given name), as LinuxCNC 2.9:
 *   float OUT sine, cosine, sawtooth, triangle, square; bit OUT clock;
 *   float IN  frequency (Hz, default 1), amplitude (default 1), offset (0);
 *   bit   IN  reset (holds the phase at 0 while TRUE);
 *   function siggen.N.update (floating point).
 * The seeds describe amplitude/frequency/offset as parameters (2.3 era);
 * 2.9 made them pins, which is what a HAL file written today expects.
 *
 * Each period the phase (0 <= phase < 1, in cycles) advances by
 * frequency * period and wraps at 1; a frequency above the Nyquist limit
 * (0.5 cycles per period) is lowered to it, writing the limited value back
 * to the frequency pin; reset holds the phase at 1/2.  Outputs, with
 * a = amplitude and o = offset (the conventions 2.9 produces, checked
 * sample by sample against it):
 *   sawtooth = (2 phase - 1) a + o
 *   triangle = (1 - 4 phase) a + o      for phase <= 1/2
 *              (4 phase - 3) a + o      otherwise
 *   square   = -a + o, clock FALSE      for phase <= 1/2
 *              +a + o, clock TRUE       otherwise
 *   sine     = sin(w phase) a + o,   cosine = cos(w phase) a + o
 * where w = 6.2831854, the 8-digit value of 2 pi that 2.9 uses (visible as
 * sine = -4.6e-8 at phase 1/2 instead of +1.2e-16).
 * See docs/siggen.md.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>

#include "hm_comp.h"
#include "hm_simple.h"

#define SIGGEN_MAX_CHAN 16
#define SIGGEN_TWO_PI 6.2831854 /* sic, see above */

typedef struct {
    hal_float_t *square;
    hal_float_t *sawtooth;
    hal_float_t *triangle;
    hal_float_t *sine;
    hal_float_t *cosine;
    hal_bit_t *clock;
    hal_float_t *frequency;
    hal_float_t *amplitude;
    hal_float_t *offset;
    hal_bit_t *reset;
    double phase; /* in cycles, 0 <= phase < 1 */
} siggen_t;

static int num_chan;
RTAPI_MP_INT(num_chan, "number of channels (default 1, at most 16)");
static char *names[SIGGEN_MAX_CHAN];
RTAPI_MP_ARRAY_STRING(names, SIGGEN_MAX_CHAN, "names of the channels");
static int comp_id;

static void siggen_update(void *arg, long period)
{
    siggen_t *g = arg;
    if (*g->reset) {
        g->phase = 0.5;
    } else {
        double seconds = period * 1e-9;
        double step = *g->frequency * seconds;
        if (step > 0.5) {
            *g->frequency = 0.5 / seconds;
            step = 0.5;
        }
        g->phase += step;
        if (g->phase >= 1.0)
            g->phase -= 1.0;
    }

    double a = *g->amplitude;
    double o = *g->offset;
    double ph = g->phase;
    *g->sawtooth = (ph * 2.0 - 1.0) * a + o;
    double tri = (ph <= 0.5) ? 1.0 - ph * 4.0 : ph * 4.0 - 3.0;
    *g->triangle = tri * a + o;
    if (ph > 0.5) {
        *g->square = a + o;
        *g->clock = 1;
    } else {
        *g->square = -a + o;
        *g->clock = 0;
    }
    double angle = ph * SIGGEN_TWO_PI;
    *g->sine = sin(angle) * a + o;
    *g->cosine = cos(angle) * a + o;
}

static const hm_item_t siggen_pins[] = {
    HM_PIN(siggen_t, square, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(siggen_t, sawtooth, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(siggen_t, triangle, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(siggen_t, sine, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(siggen_t, cosine, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(siggen_t, clock, HAL_BIT, HAL_OUT, 0),
    HM_PIN(siggen_t, frequency, HAL_FLOAT, HAL_IN, 1.0),
    HM_PIN(siggen_t, amplitude, HAL_FLOAT, HAL_IN, 1.0),
    HM_PIN(siggen_t, offset, HAL_FLOAT, HAL_IN, 0.0),
    HM_PIN(siggen_t, reset, HAL_BIT, HAL_IN, 0),
};

static const hm_comp_desc_t siggen_desc = {
    .modname = "siggen",
    .prefix = "siggen",
    .inst_size = sizeof(siggen_t),
    .pins = siggen_pins,
    .npins = HM_COUNT(siggen_pins),
    .funct = siggen_update,
    .uses_fp = 1,
    .funct_suffix = "update",
};

int rtapi_app_main(void)
{
    /* LinuxCNC's siggen counts channels with num_chan= (not count=); reuse
     * the common loader with that parameter's limits. */
    if (num_chan < 0 || num_chan > SIGGEN_MAX_CHAN) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "SIGGEN: ERROR: invalid number of channels: %d (1 to %d)\n", num_chan,
                        SIGGEN_MAX_CHAN);
        return -EINVAL;
    }
    return hm_comp_load_ex(&siggen_desc, "num_chan", num_chan, SIGGEN_MAX_CHAN, names,
                           SIGGEN_MAX_CHAN, &comp_id);
}

void rtapi_app_exit(void)
{
    hal_exit(comp_id);
}

MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Signal generator: sine, cosine, sawtooth, triangle, square, clock");
