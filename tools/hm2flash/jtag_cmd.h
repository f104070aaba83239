/* SPDX-License-Identifier: GPL-2.0-or-later */
/* jtag_cmd.h - hm2flash --jtag CABLE --scan | --program FILE (jtag_cmd.c). */
#ifndef HM2FLASH_JTAG_CMD_H
#define HM2FLASH_JTAG_CMD_H

/* 0, or 1 after printing why. */
int hm2flash_jtag_scan(const char *cable);
int hm2flash_jtag_program(const char *cable, const char *file);

#endif /* HM2FLASH_JTAG_CMD_H */
