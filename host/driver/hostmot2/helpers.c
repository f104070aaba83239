/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Helpers the module drivers share (module_api.h): HAL memory, export
 * failures, immediate configuration writes. */
#include <string.h>

#include "module_api.h"

void *hm2_hal_zalloc(hostmot2_t *hm2, size_t size, const char *what)
{
    void *p = hal_malloc((long)size);
    if (!p) {
        hm2_msg(hm2, HM2_ERR, "out of HAL memory allocating %s (%zu bytes)", what, size);
        return NULL;
    }
    memset(p, 0, size);
    return p;
}

int hm2_write_cfg(hostmot2_t *hm2, uint32_t addr, uint32_t val)
{
    int r = hm2_write_reg(hm2, addr, val);
    if (r) {
        hm2_msg(hm2, HM2_ERR, "error writing 0x%08X to register 0x%04X: %s", val, addr,
                strerror(-r));
        hm2->needs_reset = true;
    }
    return r;
}

int hm2_hal_fail(hostmot2_t *hm2, int r, const char *what)
{
    hm2_msg(hm2, HM2_ERR, "error %d (%s) exporting %s.%s to HAL", r, strerror(-r),
            hm2->llio->name, what);
    return r;
}
