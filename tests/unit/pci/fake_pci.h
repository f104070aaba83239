/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * fake_pci.h - test doubles for the hm2_pci backend:
 *  - a fake sysfs tree in a temp directory (bus/pci/devices/<addr>/ with
 *    the id files, "resource", resourceN regular files of the BAR size and
 *    "enable"), which the real sysfs code reads and mmaps;
 *  - a model of a PLX 9030 / 9054 bridge with a Xilinx FPGA behind it
 *    (/PROGRAM, /INIT, DONE, the configuration byte port) written from the
 *    spec (hostmot2.md §17.1) and the Xilinx slave configuration rules, that
 *    records what the driver did and can be made to misbehave.
 */
#ifndef FAKE_PCI_H
#define FAKE_PCI_H

#include <stddef.h>
#include <stdint.h>

#include "hm2_pci_core.h"

/* ---- fake sysfs ---- */
struct fake_bar {
    size_t size; /* 0: unused BAR */
    int is_io;
    size_t file_size; /* 0: same as size */
};

/* mkdtemp'd root with bus/pci/devices; path in root (PATH_MAX). 0 or -1. */
int fake_tree_create(char *root, size_t len);
void fake_tree_remove(const char *root);
/* Add a device directory; ids written as the kernel does ("0x10b5\n").
 * enable: 0 or 1 written to "enable", -1 no enable file. */
int fake_dev_add(const char *root, const char *addr, uint16_t vendor, uint16_t device,
                 uint16_t sub_vendor, uint16_t sub_device, const struct fake_bar bars[6],
                 int enable);
/* Write / read bytes of a device file (resourceN, enable, vendor ...). */
int fake_file_write(const char *root, const char *addr, const char *file, size_t off,
                    const void *data, size_t len);
int fake_file_read(const char *root, const char *addr, const char *file, size_t off, void *data,
                   size_t len);

/* ---- PLX bridge + FPGA model ---- */
enum { MODEL_RESET = 0, MODEL_CLEARING, MODEL_CONFIG, MODEL_DONE };

struct plx_model {
    int is_9054;
    /* set by the test */
    int init_delay;       /* 9030: reads after /PROGRAM rises until /INIT rises; -1 never */
    int done_delay;       /* reads after the last byte until DONE rises */
    int ignore_program;   /* FPGA ignores /PROGRAM: keeps init/done as they are */
    int never_done;       /* all bytes taken, DONE never rises */
    int fail_data_at;     /* data_write fails (-EIO) at this byte index; -1 never */
    const uint8_t *expect; /* the bytes the FPGA must see on its port (D0 = bit 0) */
    size_t nexpect;
    /* state */
    uint32_t out;         /* output bits last written to CTRL/STAT */
    uint32_t las[4];      /* 9030 LAS0BRD..LAS3BRD */
    int init, done, phase, countdown, done_countdown;
    int reads_since_program; /* 9054: reset wait counted in status reads */
    uint8_t *got;
    size_t ngot, got_cap;
    int total_bytes;      /* every byte written to the port */
    int bad_bytes;        /* bytes sent while the FPGA was not taking them */
    int early_bytes;      /* 9054: bytes sent before 3300 reads after /PROGRAM */
    int ctrl_reads, ctrl_writes, program_pulses;
    int writes_to_ctrl_with_write_low; /* for the 9030 LED/WRITE check */
};

void plx_model_init(struct plx_model *m, int is_9054, const uint8_t *expect, size_t n);
void plx_model_free(struct plx_model *m);
extern const struct hm2_pci_plx_ops plx_model_ops;

#endif
