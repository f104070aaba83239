/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_board_module.h - the realtime-module skeleton the HostMot2 board
 * drivers share (hm2_7i43, hm2_sim): hal_init, a slot per board given by
 * the module parameters, set up in order, all undone when one fails,
 * hal_ready; and on unload every slot released, hal_exit.  The driver
 * describes what differs; this file knows nothing of ports or sockets.
 */
#ifndef HM2_BOARD_MODULE_H
#define HM2_BOARD_MODULE_H

#include <stddef.h>

struct hm2_board_module_desc {
    const char *name; /* "hm2_sim": HAL component, message prefix */
    int max_boards;   /* slots */
    size_t slot_size; /* the driver's per-board struct */
    /* board i is given by the module parameters (the first one that is
     * not ends the list) */
    int (*wanted)(int i);
    /* set up board i in slot i of `slots` (the array, so a driver can look
     * at the boards before it).  0, or -errno after printing why. */
    int (*setup)(void *slots, int i, int comp_id);
    /* undo what setup did to slot i, also a half-done or untouched (zeroed)
     * one */
    void (*release)(void *slots, int i);
    const char *none_given; /* the error when no board is given */
};

/* The module's state between load and unload; {NULL, -1} before. */
struct hm2_board_module {
    void *slots;
    int comp_id;
};

/* rtapi_app_main after the driver's own banner and checks.  0, or -errno
 * with everything undone (m back to {NULL, -1}). */
int hm2_board_module_load(struct hm2_board_module *m, const struct hm2_board_module_desc *d);
/* rtapi_app_exit: release every slot, hal_exit, "NAME: driver unloaded". */
void hm2_board_module_unload(struct hm2_board_module *m, const struct hm2_board_module_desc *d);

/* A line of the hm2 core's log (HM2_PRINT, HM2_ERR, ...) to rtapi. */
void hm2_board_rtapi_log(void *ctx, int level, const char *line);

#endif /* HM2_BOARD_MODULE_H */
