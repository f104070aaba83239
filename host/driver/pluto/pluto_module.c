/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Load-time steps of the Pluto-P modules (see pluto_module.h). */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pluto_module.h"
#include "hal.h"
#include "rtapi.h"

void pluto_rtapi_log(void *ctx, int level, const char *fmt, ...)
{
    (void)ctx;
    va_list ap;
    va_start(ap, fmt);
    rtapi_vprint_msg(level == PLUTO_INFO ? RTAPI_MSG_INFO : RTAPI_MSG_ERR, fmt, ap);
    va_end(ap);
}

int pluto_module_setup(epp_port_t *port, const char *modname, const char *board,
                       const char *portspec, long ioaddr, long ioaddr_hi, int epp_wide,
                       const char *firmware)
{
    char err[640], path[1024];
    uint8_t *image = NULL;
    size_t len = 0;
    struct pluto_log log = {pluto_rtapi_log, NULL};
    int r;

    /* Read the file first: a missing firmware never touches the port. */
    r = pluto_read_firmware(firmware, &image, &len, path, sizeof(path), err, sizeof(err));
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: %s\n", modname, err);
        return r;
    }
    r = epp_port_open(port, portspec, ioaddr, ioaddr_hi, epp_wide, err, sizeof(err));
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: cannot open the parallel port: %s\n", modname, err);
        free(image);
        return r;
    }
    rtapi_print_msg(RTAPI_MSG_INFO, "%s: firmware %s (%zu bytes) on port %s\n", modname, path,
                    len, port->name);
    if (len < PLUTO_UPLOAD_BYTES)
        rtapi_print_msg(RTAPI_MSG_INFO,
                        "%s: firmware %s is shorter than a Pluto-P image (%zu < %u bytes)\n",
                        modname, path, len, PLUTO_UPLOAD_BYTES);
    r = pluto_upload(port, image, len, &log);
    free(image);
    if (!r)
        r = pluto_probe(port, board, &log);
    if (r) {
        if (r != -EIO)
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: firmware upload on %s failed: %s\n", modname,
                            port->name, strerror(-r));
        else
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "%s: the board on %s did not answer after the upload of %s "
                            "(wrong or damaged firmware file, or no board)\n",
                            modname, port->name, path);
        epp_port_close(port);
        return r;
    }
    return 0;
}

int pluto_module_load(const struct pluto_module_desc *d, const struct pluto_module_args *a,
                      void **block, int *comp_id)
{
    int r;
    *block = NULL;
    *comp_id = hal_init(d->modname);
    if (*comp_id < 0)
        return *comp_id;
    void *b = hal_malloc((long)d->block_size);
    if (!b) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: out of HAL memory (%zu bytes)\n", d->modname,
                        d->block_size);
        r = -ENOMEM;
        goto fail;
    }
    memset(b, 0, d->block_size);
    epp_port_t *port = (epp_port_t *)((char *)b + d->port_offset);
    r = pluto_module_setup(port, d->modname, d->board, a->port, a->ioaddr, a->ioaddr_hi,
                           a->epp_wide,
                           a->firmware && *a->firmware ? a->firmware : d->default_firmware);
    if (r)
        goto fail;
    r = d->init(b, *comp_id);
    if (!r)
        r = hal_export_functf(d->read, b, 1, 0, *comp_id, "%s.read", d->board);
    if (!r)
        r = hal_export_functf(d->write, b, 1, 0, *comp_id, "%s.write", d->board);
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: exporting the HAL objects failed: %d\n", d->modname,
                        r);
        epp_port_close(port);
        goto fail;
    }
    *block = b;
    hal_ready(*comp_id);
    return 0;
fail:
    hal_exit(*comp_id);
    *comp_id = -1;
    return r;
}

void pluto_module_unload(const struct pluto_module_desc *d, void **block, int *comp_id)
{
    if (*block)
        epp_port_close((epp_port_t *)((char *)*block + d->port_offset));
    *block = NULL;
    if (*comp_id >= 0)
        hal_exit(*comp_id);
    *comp_id = -1;
}

int pluto_export_dio(int comp_id, const char *pfx, hal_bit_t **dout, hal_bit_t *dout_invert,
                     int ndout, hal_bit_t **din, hal_bit_t **din_not, int ndin)
{
    int r = 0, i;
    for (i = 0; i < ndout && !r; i++) {
        r = hal_pin_bit_newf(HAL_IN, &dout[i], comp_id, "%s.dout.%02d", pfx, i);
        if (!r)
            r = hal_param_bit_newf(HAL_RW, &dout_invert[i], comp_id, "%s.dout.%02d-invert", pfx,
                                   i);
    }
    for (i = 0; i < ndin && !r; i++) {
        r = hal_pin_bit_newf(HAL_OUT, &din[i], comp_id, "%s.din.%02d", pfx, i);
        if (!r)
            r = hal_pin_bit_newf(HAL_OUT, &din_not[i], comp_id, "%s.din.%02d-not", pfx, i);
    }
    return r;
}

int pluto_export_diag(int comp_id, const char *pfx, hal_u32_t *communication_error,
                      hal_s32_t *debug_0, hal_s32_t *debug_1)
{
    int r = hal_param_u32_newf(HAL_RW, communication_error, comp_id, "%s.communication-error",
                               pfx);
    if (!r)
        r = hal_param_s32_newf(HAL_RW, debug_0, comp_id, "%s.debug-0", pfx);
    if (!r)
        r = hal_param_s32_newf(HAL_RW, debug_1, comp_id, "%s.debug-1", pfx);
    return r;
}
