/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * scope_rt - the realtime half of halscope.
 *
 *   loadrt scope_rt [num_samples=N]
 *   addf scope.sample THREAD
 *
 * As LinuxCNC's: one component `scope_rt`, one function `scope.sample`,
 * num_samples value slots shared by the channels (default 16000).  The
 * front ends (halscope, halweb) configure it through shared memory
 * (scope_shm.h): up to 16 channels, each a pin, signal or parameter of any
 * type, sampled every mult-th call; a capture of rec_len records with
 * pretrig of them before the trigger (a level crossed rising or falling on
 * one channel), in modes normal/single/auto or roll.
 *
 * The function never waits and never takes the HAL mutex: channel values
 * are read through hal_q_ref_read() and records are published with a
 * release store of the record count, so a reader never sees half a record
 * (scope_shm.h).  The one exception is the simulated clock with a reader
 * that asked for it (reader_wait): in roll mode a full ring, and in the
 * triggered modes a finished capture, make the function wait for the
 * reader (to drain the ring, or to re-arm or stop) with rtapi_sim_yield(),
 * during which virtual time does not move, as sampler does.  A simulated
 * run then loses nothing and re-arms at a reproducible time.  The wait ends
 * when the reader's process is gone, or the threads stop.
 *
 * Floating point is used only to compare a float channel against the
 * trigger level; the function is exported without the FP flag so that it
 * can run in a base thread created with fp=0, as in LinuxCNC.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <signal.h>
#include <sys/types.h>
#include <stdint.h>
#include <string.h>

#include "hal.h"
#include "hal_query.h"
#include "rtapi.h"
#include "scope_shm.h"

static long num_samples = SCOPE_DEFAULT_SAMPLES;
RTAPI_MP_LONG(num_samples, "Number of samples in the shared memory block");

typedef struct {
    scope_ctrl_t *ctrl;
    hal_data_u *data;
    uint32_t ack;
    int state;
    int nchan;
    int mult, div;
    int mode;
    int trig_chan, edge;
    double level; /* float channels */
    int64_t ilevel; /* integer and bit channels: trigger when crossing it */
    hal_type_t trig_type;
    int reader_wait;
    uint64_t cap, rec_len, pretrig;
    uint64_t w;        /* records written since ARM */
    uint64_t slot;     /* slot index of record w */
    uint64_t trig;     /* trigger record */
    int have_prev;
    hal_data_u prev;
    hal_q_ref_t refs[SCOPE_MAX_CHAN];
} scope_rt_t;

static int comp_id;
static int ctrl_id, data_id;
static scope_rt_t *scope;

static int64_t as_int(hal_type_t t, const hal_data_u *v)
{
    switch (t) {
    case HAL_BIT: return v->b ? 1 : 0;
    case HAL_S32: return v->s;
    case HAL_U32: return v->u;
    case HAL_S64: return v->ls;
    case HAL_U64: return v->lu > (uint64_t)INT64_MAX ? INT64_MAX : (int64_t)v->lu;
    default: return 0;
    }
}

/* Did the trigger channel cross the level between prev and cur? */
static int crossed(const scope_rt_t *s, const hal_data_u *prev, const hal_data_u *cur)
{
    if (s->trig_type == HAL_FLOAT) {
        double a = prev->f, b = cur->f;
        return s->edge == SCOPE_RISING ? (a < s->level && b >= s->level)
                                       : (a > s->level && b <= s->level);
    }
    int64_t a = as_int(s->trig_type, prev), b = as_int(s->trig_type, cur);
    return s->edge == SCOPE_RISING ? (a < s->ilevel && b >= s->ilevel)
                                   : (a > s->ilevel && b <= s->ilevel);
}

/* Integer threshold equivalent to "value >= level" (rising) or
 * "value <= level" (falling) for integer values. */
static int64_t int_level(double level, int edge)
{
    if (level > 9.2e18)
        return INT64_MAX;
    if (level < -9.2e18)
        return INT64_MIN;
    int64_t f = (int64_t)level;
    if (edge == SCOPE_RISING && (double)f < level)
        f++; /* smallest integer >= level */
    if (edge == SCOPE_FALLING && (double)f > level)
        f--; /* largest integer <= level */
    return f;
}

static int check_config(const scope_cfg_t *c, uint64_t num)
{
    if (c->nchan < 1 || c->nchan > SCOPE_MAX_CHAN || c->mult < 1)
        return -EINVAL;
    uint64_t cap = num / (uint64_t)c->nchan;
    if (c->mode != SCOPE_MODE_ROLL &&
        (c->rec_len < 1 || c->rec_len > cap || c->pretrig >= c->rec_len))
        return -ERANGE;
    if (c->mode == SCOPE_MODE_ROLL && cap < 2)
        return -ERANGE;
    if (c->trig_chan < -1 || c->trig_chan >= c->nchan)
        return -EINVAL;
    if (c->trig_edge != SCOPE_RISING && c->trig_edge != SCOPE_FALLING)
        return -EINVAL;
    if (c->mode < SCOPE_MODE_NORMAL || c->mode > SCOPE_MODE_ROLL)
        return -EINVAL;
    for (int i = 0; i < c->nchan; i++) {
        int k = c->chan[i].kind;
        if (k != HAL_Q_PIN && k != HAL_Q_PARAM && k != HAL_Q_SIG)
            return -EINVAL;
    }
    return 0;
}

static void set_state(scope_rt_t *s, int state)
{
    s->state = state;
    __atomic_store_n(&s->ctrl->state, (uint32_t)state, __ATOMIC_RELEASE);
}

static void arm(scope_rt_t *s, const scope_cfg_t *cfg, long period)
{
    scope_ctrl_t *c = s->ctrl;
    int r = check_config(cfg, c->num_samples);
    if (r < 0) {
        c->error = r;
        set_state(s, SCOPE_ERROR);
        return;
    }
    s->nchan = cfg->nchan;
    memcpy(s->refs, cfg->chan, sizeof(s->refs[0]) * (size_t)s->nchan);
    s->mult = cfg->mult;
    s->div = cfg->mult - 1; /* the first call after ARM samples */
    s->mode = cfg->mode;
    s->cap = c->num_samples / (uint64_t)s->nchan;
    s->rec_len = cfg->rec_len;
    s->pretrig = cfg->pretrig;
    s->trig_chan = cfg->trig_chan;
    s->edge = cfg->trig_edge;
    s->level = cfg->trig_level;
    s->trig_type = s->trig_chan >= 0 ? s->refs[s->trig_chan].type : HAL_BIT;
    s->ilevel = int_level(cfg->trig_level, cfg->trig_edge);
    s->reader_wait = cfg->reader_wait;
    s->w = 0;
    s->slot = 0;
    s->have_prev = 0;
    c->error = 0;
    c->forced = 0;
    c->capacity = s->cap;
    c->lost = 0;
    c->rd_idx = 0;
    c->trig_idx = 0;
    c->start_idx = 0;
    c->t_first = 0;
    c->t_trig = 0;
    c->interval = (int64_t)period * s->mult;
    __atomic_store_n(&c->widx, 0, __ATOMIC_RELEASE);
    set_state(s, s->mode == SCOPE_MODE_ROLL ? SCOPE_ROLLING : SCOPE_ARMED);
}

/* A new command: copy the configuration under the seqlock; if the front
 * end is writing it right now, leave the command for the next call. */
static void command(scope_rt_t *s, uint32_t seq, long period)
{
    scope_ctrl_t *c = s->ctrl;
    uint32_t g1 = __atomic_load_n(&c->cfg_gen, __ATOMIC_ACQUIRE);
    if (g1 & 1u)
        return;
    uint32_t cmd = c->cmd;
    scope_cfg_t cfg;
    memcpy(&cfg, (const void *)&c->cfg, sizeof(cfg));
    __atomic_thread_fence(__ATOMIC_ACQUIRE);
    if (__atomic_load_n(&c->cfg_gen, __ATOMIC_RELAXED) != g1 ||
        __atomic_load_n(&c->cmd_seq, __ATOMIC_RELAXED) != seq)
        return;
    if (cmd == SCOPE_CMD_ARM)
        arm(s, &cfg, period);
    else if (cmd == SCOPE_CMD_STOP)
        set_state(s, SCOPE_IDLE);
    s->ack = seq;
    __atomic_store_n(&c->ack_seq, seq, __ATOMIC_RELEASE);
}

/* The process that asked for reader_wait still exists (checked only while
 * waiting on the simulated clock, where a system call costs no time). */
static int reader_alive(const scope_rt_t *s)
{
    pid_t pid = s->ctrl->reader_pid;
    return pid > 0 && (kill(pid, 0) == 0 || errno == EPERM);
}

/* Roll mode: is there room for record w without overwriting one the reader
 * has not consumed (one record of margin, see scope_shm.h)? */
static int roll_room(scope_rt_t *s)
{
    scope_ctrl_t *c = s->ctrl;
    uint64_t rd = __atomic_load_n(&c->rd_idx, __ATOMIC_ACQUIRE);
    if (s->w - rd < s->cap - 1)
        return 1;
    if (s->reader_wait && rtapi_is_simclock()) {
        while (!rtapi_sim_yield() && reader_alive(s)) {
            rd = __atomic_load_n(&c->rd_idx, __ATOMIC_ACQUIRE);
            if (s->w - rd < s->cap - 1)
                return 1;
        }
    }
    return 0;
}

/* A finished capture on the simulated clock: wait until the reader sends
 * its next command.  Returns the new cmd_seq, or the old one. */
static uint32_t await_command(scope_rt_t *s)
{
    scope_ctrl_t *c = s->ctrl;
    while (!rtapi_sim_yield() && reader_alive(s)) {
        uint32_t seq = __atomic_load_n(&c->cmd_seq, __ATOMIC_ACQUIRE);
        if (seq != s->ack)
            return seq;
    }
    s->reader_wait = 0; /* the reader is gone: do not wait again */
    return s->ack;
}

static void triggered_step(scope_rt_t *s, const hal_data_u *rec)
{
    scope_ctrl_t *c = s->ctrl;
    uint64_t w = s->w; /* index of the record just written */
    if (s->state == SCOPE_ARMED && w >= s->pretrig) {
        int hit;
        if (s->trig_chan < 0)
            hit = 1;
        else
            hit = s->have_prev && crossed(s, &s->prev, &rec[s->trig_chan]);
        if (!hit && s->mode == SCOPE_MODE_AUTO && w - s->pretrig + 1 >= s->rec_len) {
            hit = 1;
            c->forced = 1;
        }
        if (hit) {
            s->trig = w;
            c->trig_idx = w;
            c->start_idx = w - s->pretrig;
            c->t_trig = rtapi_get_time();
            set_state(s, SCOPE_TRIGGERED);
        }
    }
    if (s->trig_chan >= 0) {
        s->prev = rec[s->trig_chan];
        s->have_prev = 1;
    }
    if (s->state == SCOPE_TRIGGERED && w + 1 == s->trig - s->pretrig + s->rec_len) {
        c->done_calls = c->calls;
        set_state(s, SCOPE_DONE);
        __atomic_add_fetch(&c->capture_seq, 1, __ATOMIC_RELEASE);
    }
}

static void sample(void *arg, long period)
{
    scope_rt_t *s = arg;
    scope_ctrl_t *c = s->ctrl;
    c->calls++;
    uint32_t seq = __atomic_load_n(&c->cmd_seq, __ATOMIC_ACQUIRE);
    if (seq == s->ack && s->state == SCOPE_DONE && s->reader_wait && rtapi_is_simclock())
        seq = await_command(s);
    if (seq != s->ack)
        command(s, seq, period);
    if (s->state != SCOPE_ARMED && s->state != SCOPE_TRIGGERED && s->state != SCOPE_ROLLING)
        return;
    if (++s->div < s->mult)
        return;
    s->div = 0;
    if (s->state == SCOPE_ROLLING && !roll_room(s))
        c->lost++;
    hal_data_u *rec = s->data + s->slot * (uint64_t)s->nchan;
    hal_q_ref_read(s->refs, s->nchan, rec);
    if (s->w == 0)
        c->t_first = rtapi_get_time();
    if (s->state != SCOPE_ROLLING)
        triggered_step(s, rec);
    s->w++;
    if (++s->slot == s->cap)
        s->slot = 0;
    __atomic_store_n(&c->widx, s->w, __ATOMIC_RELEASE);
}

static int map_blocks(scope_rt_t *s)
{
    void *p;
    ctrl_id = rtapi_shmem_new(SCOPE_CTRL_KEY, comp_id, sizeof(scope_ctrl_t));
    if (ctrl_id < 0)
        return ctrl_id;
    data_id = rtapi_shmem_new(SCOPE_DATA_KEY, comp_id,
                              (unsigned long)num_samples * sizeof(hal_data_u));
    if (data_id < 0)
        return data_id;
    if (rtapi_shmem_getptr(ctrl_id, &p) < 0)
        return -EINVAL;
    s->ctrl = p;
    if (rtapi_shmem_getptr(data_id, &p) < 0)
        return -EINVAL;
    s->data = p;
    memset(s->ctrl, 0, sizeof(*s->ctrl));
    s->ctrl->num_samples = (uint64_t)num_samples;
    s->ctrl->version = SCOPE_VERSION;
    __atomic_store_n(&s->ctrl->magic, SCOPE_MAGIC, __ATOMIC_RELEASE);
    return 0;
}

static void unmap_blocks(scope_rt_t *s)
{
    /* a front end still attached sees the scope go away */
    if (s != NULL && s->ctrl != NULL)
        __atomic_store_n(&s->ctrl->magic, 0u, __ATOMIC_RELEASE);
    if (data_id > 0)
        rtapi_shmem_delete(data_id, comp_id);
    if (ctrl_id > 0)
        rtapi_shmem_delete(ctrl_id, comp_id);
    data_id = ctrl_id = 0;
}

int rtapi_app_main(void)
{
    if (num_samples < SCOPE_MAX_CHAN || num_samples > (1L << 27)) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "SCOPE_RT: ERROR: num_samples=%ld is out of range (%d to %ld)\n",
                        num_samples, SCOPE_MAX_CHAN, 1L << 27);
        return -EINVAL;
    }
    comp_id = hal_init("scope_rt");
    if (comp_id < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "SCOPE_RT: ERROR: hal_init() failed\n");
        return comp_id;
    }
    scope_rt_t *s = hal_malloc(sizeof(*s));
    int r = s == NULL ? -ENOMEM : 0;
    if (r < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "SCOPE_RT: ERROR: out of HAL memory\n");
        goto fail;
    }
    memset(s, 0, sizeof(*s));
    if ((r = map_blocks(s)) < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "SCOPE_RT: ERROR: cannot get shared memory for %ld samples (%d)\n",
                        num_samples, r);
        goto fail;
    }
    if ((r = hal_export_funct("scope.sample", sample, s, 0, 0, comp_id)) < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "SCOPE_RT: ERROR: sample funct export failed\n");
        goto fail;
    }
    scope = s;
    hal_ready(comp_id);
    return 0;
fail:
    unmap_blocks(s);
    hal_exit(comp_id);
    return r;
}

void rtapi_app_exit(void)
{
    unmap_blocks(scope);
    hal_exit(comp_id);
}

MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Oscilloscope for HAL: the realtime sampler of halscope");
