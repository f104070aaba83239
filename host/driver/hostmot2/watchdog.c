/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Watchdog (spec §9.2, §10.4).  Disabled (timer bit 31) until the first
 * write() or pet_watchdog(); petted by write() (LinuxCNC 2.7+) and by the
 * seed-era pet_watchdog function; a bite sets has_bit and stops all writes
 * until the user clears has_bit. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "modules.h"

#define WD_DEFAULT_TIMEOUT_NS 1000000000u /* seed value (2.9: 5 ms) */
#define WD_PET_COOKIE 0x5A000000u
#define WD_DISABLED 0x80000000u

struct wd_hal {
    hal_bit_t *has_bit;
    hal_u32_t timeout_ns;
};

struct hm2_watchdog_state {
    struct wd_hal *hal;
    uint32_t *status; /* TRAM read */
    uint32_t *pet;    /* TRAM write */
    bool enable;
    bool timer_written;
    uint32_t written_timeout_ns;
    bool bite_seen;
    uint32_t warned_timeout_ns;
    long warned_period;
};

#define REG_TIMER 0
#define REG_STATUS 1
#define REG_COOKIE 2

static int watchdog_setup(hostmot2_t *hm2)
{
    if (!hm2->watchdog.present || hm2->watchdog.used == 0)
        return 0;
    struct hm2_watchdog_state *s = calloc(1, sizeof(*s));
    if (!s) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating watchdog state");
        return -ENOMEM;
    }
    hm2->watchdog_s = s;
    s->hal = hm2_hal_zalloc(hm2, sizeof(*s->hal), "watchdog");
    if (!s->hal)
        return -ENOMEM;
    const char *pfx = hm2->llio->name;
    int id = hm2->llio->comp_id, r;
    if ((r = hal_pin_bit_newf(HAL_IO, &s->hal->has_bit, id, "%s.watchdog.has_bit", pfx)) ||
        (r = hal_param_u32_newf(HAL_RW, &s->hal->timeout_ns, id, "%s.watchdog.timeout_ns", pfx)))
        return hm2_hal_fail(hm2, r, "watchdog");
    *s->hal->has_bit = 0;
    s->hal->timeout_ns = WD_DEFAULT_TIMEOUT_NS;
    const struct hm2_md *md = &hm2->watchdog.md;
    if ((r = hm2_tram_add_read(hm2, hm2_reg_addr(md, REG_STATUS, 0), &s->status, 1)) ||
        (r = hm2_tram_add_write(hm2, hm2_reg_addr(md, REG_COOKIE, 0), &s->pet, 1)))
        return r;
    return 0;
}

static uint32_t timer_value(hostmot2_t *hm2)
{
    struct hm2_watchdog_state *s = hm2->watchdog_s;
    uint32_t clock = hm2->watchdog.md.clock_freq;
    bool clipped;
    uint32_t v = hm2_watchdog_timer_value(s->hal->timeout_ns, clock, &clipped);
    if (clipped) {
        uint32_t max = hm2_watchdog_max_timeout_ns(clock);
        hm2_msg(hm2, HM2_ERR, "requested watchdog timeout is out of range, setting it to max: %u ns",
                max);
        s->hal->timeout_ns = max;
        v = hm2_watchdog_timer_value(max, clock, &clipped);
    }
    return v;
}

static void write_timer(hostmot2_t *hm2)
{
    struct hm2_watchdog_state *s = hm2->watchdog_s;
    uint32_t v = s->enable ? timer_value(hm2) : WD_DISABLED;
    if (hm2_write_cfg(hm2, hm2_reg_addr(&hm2->watchdog.md, REG_TIMER, 0), v))
        return;
    s->timer_written = s->enable;
    s->written_timeout_ns = s->hal->timeout_ns;
}

static void watchdog_force_write(hostmot2_t *hm2)
{
    if (!hm2->watchdog_s)
        return;
    write_timer(hm2);
    hm2_watchdog_clear_bite(hm2);
}

void hm2_watchdog_clear_bite(hostmot2_t *hm2)
{
    struct hm2_watchdog_state *s = hm2->watchdog_s;
    if (!s)
        return;
    hm2_write_cfg(hm2, hm2_reg_addr(&hm2->watchdog.md, REG_STATUS, 0), 0);
    s->bite_seen = false;
}

static void watchdog_write_changed(hostmot2_t *hm2)
{
    struct hm2_watchdog_state *s = hm2->watchdog_s;
    if (!s || !s->enable)
        return;
    if (!s->timer_written || s->written_timeout_ns != s->hal->timeout_ns)
        write_timer(hm2);
}

static void watchdog_process_read(hostmot2_t *hm2, long period)
{
    (void)period;
    struct hm2_watchdog_state *s = hm2->watchdog_s;
    if (!s)
        return;
    if ((*s->status & 1u) && !s->bite_seen) {
        s->bite_seen = true;
        *s->hal->has_bit = 1;
        hm2->needs_reset = true;
        hm2_msg(hm2, HM2_ERR, "Watchdog has bit! (set the .has-bit pin to False to resume)");
    }
}

static void watchdog_prepare_write(hostmot2_t *hm2, long period)
{
    struct hm2_watchdog_state *s = hm2->watchdog_s;
    /* the load-time transfer leaves the watchdog disabled: it is enabled
     * by the first HAL write() or pet_watchdog */
    if (!s || period == HM2_LOAD_PERIOD)
        return;
    *s->pet = WD_PET_COOKIE;
    s->enable = true;
    uint32_t t = s->hal->timeout_ns;
    if (period > 0 && (double)t < 1.5 * (double)period &&
        (t != s->warned_timeout_ns || period != s->warned_period)) {
        hm2_msg(hm2, HM2_WARN,
                "Watchdog timeout (%u ns) is dangerously short compared to the write period "
                "(%ld ns)",
                t, period);
        s->warned_timeout_ns = t;
        s->warned_period = period;
    }
}

int hm2_watchdog_pet(hostmot2_t *hm2)
{
    struct hm2_watchdog_state *s = hm2->watchdog_s;
    if (!s)
        return 0;
    s->enable = true;
    watchdog_write_changed(hm2);
    return hm2_write_reg(hm2, hm2_reg_addr(&hm2->watchdog.md, REG_COOKIE, 0), WD_PET_COOKIE);
}

bool hm2_watchdog_has_bit(const hostmot2_t *hm2)
{
    return hm2->watchdog_s && *hm2->watchdog_s->hal->has_bit;
}

void hm2_watchdog_force_bite(hostmot2_t *hm2)
{
    struct hm2_watchdog_state *s = hm2->watchdog_s;
    if (!s)
        return;
    /* timer 0: the counter passes below zero on the next clock */
    hm2_write_reg(hm2, hm2_reg_addr(&hm2->watchdog.md, REG_TIMER, 0), 0);
}

static void watchdog_cleanup(hostmot2_t *hm2)
{
    free(hm2->watchdog_s);
    hm2->watchdog_s = NULL;
}

const struct hm2_module_ops hm2_watchdog_ops = {
    .name = "watchdog",
    .setup = watchdog_setup,
    .process_read = watchdog_process_read,
    .prepare_write = watchdog_prepare_write,
    .write_changed = watchdog_write_changed,
    .force_write = watchdog_force_write,
    .cleanup = watchdog_cleanup,
};
