/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hostmot2.h - what the hostmot2 realtime module offers board drivers
 * (hm2_pci, hm2_7i43, hm2_sim, hm2_test): register a board given its llio
 * and config string, and unregister it.  See docs/hostmot2.md, docs/llio.md.
 */
#ifndef HM2_HOSTMOT2_H
#define HM2_HOSTMOT2_H

#include "hm2/llio.h"
#include "rtapi.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Probe the board, export its HAL objects under llio->comp_id and its
 * functions.  0 on success; -errno after printing why.  On failure no HAL
 * object of the board is left that the caller's hal_exit(comp_id) would
 * not remove, and nothing was exported when the IDROM or config is bad. */
RTAPI_EXPORT int hm2_register(hm2_llio_t *llio, const char *config);
/* Stop the board (its watchdog is made to bite so outputs go safe) and
 * free it.  Call before hal_exit() of the backend's component. */
RTAPI_EXPORT void hm2_unregister(hm2_llio_t *llio);

#ifdef __cplusplus
}
#endif

#endif /* HM2_HOSTMOT2_H */
