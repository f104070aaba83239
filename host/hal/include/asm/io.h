/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * asm/io.h - for components written for LinuxCNC's kernel-module days
 * (the seed's out8 example includes <asm/io.h> for inb/outb): the
 * userspace port I/O of rtapi_io.h.  Only on the component include path.
 */
#ifndef HM_ASM_IO_H
#define HM_ASM_IO_H

#include "rtapi_io.h"

#endif /* HM_ASM_IO_H */
