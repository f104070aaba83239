/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_slab.h - memory allocation outside HAL shared memory with the
 * LinuxCNC names (setup code only; realtime functions must not allocate).
 */
#ifndef HM_RTAPI_SLAB_H
#define HM_RTAPI_SLAB_H

#include <stdlib.h>

#define RTAPI_GFP_KERNEL 0
#define rtapi_kmalloc(size, flags) ((void)(flags), malloc(size))
#define rtapi_kzalloc(size, flags) ((void)(flags), calloc(1, (size)))
#define rtapi_krealloc(p, size, flags) ((void)(flags), realloc((p), (size)))
#define rtapi_kfree(p) free(p)

#endif /* HM_RTAPI_SLAB_H */
