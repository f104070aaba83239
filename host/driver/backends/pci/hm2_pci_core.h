/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_pci_core.h - Mesa Anything-I/O PCI boards as hm2 llios (spec
 * hostmot2.md §16, §17.1; docs/hm2_pci.md): identify a sysfs PCI device,
 * map its 64 KiB hm2 window, and for the PLX 9030/9054/9056 bridged boards
 * reset and program the FPGA through the bridge's GPIO bits.  No HAL calls:
 * the RT module (hm2_pci.c), hm2pinout and the unit tests share it.
 */
#ifndef HM2_PCI_CORE_H
#define HM2_PCI_CORE_H

#include <stdint.h>

#include "hm2/boards.h"
#include "hm2/hm2.h"
#include "hm2/llio.h"
#include "pci_sysfs.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HM2_PCI_VERSION "0.7"
#define HM2_PCI_MAX_BOARDS 8 /* LinuxCNC 2.9: config[8], "can only handle 8" */
#define HM2_PCI_WINDOW_SIZE 0x10000u

#define HM2_PCI_VENDOR_PLX 0x10B5u
#define HM2_PCI_VENDOR_MESA 0x2718u

enum hm2_pci_bridge { HM2_PCI_PLX9030, HM2_PCI_PLX9054, HM2_PCI_NATIVE };

/* PLX 9030 (5i20, 4i65): control/status register at BAR1 + 0x54. */
#define PLX9030_CTRL_STAT 0x54u
#define PLX9030_DONE (1u << 11)    /* in */
#define PLX9030_INIT_N (1u << 14)  /* in, /INIT */
#define PLX9030_LED_N (1u << 17)   /* out, /LED */
#define PLX9030_WRITE_N (1u << 23) /* out, /WRITE */
#define PLX9030_PROGRAM_N (1u << 26) /* out, /PROGRAM */
#define PLX9030_LASBRD(n) (0x28u + 4u * (unsigned)(n))
#define PLX9030_LASBRD_READY (1u << 1)
#define PLX9030_INIT_POLLS 3300 /* >= 100 us of PCI reads: /INIT clears */

/* PLX 9054/9056 (5i22, 5i23, 4i68, 4i69, 5i21, 3x20): BAR1 + 0x6C. */
#define PLX9054_CTRL_STAT 0x6Cu
#define PLX9054_PROGRAM_N (1u << 16)
#define PLX9054_DONE (1u << 17)
#define PLX9054_DONE_ENABLE (1u << 18)
#define PLX9054_PROGRAM_ENABLE (1u << 19)
#define PLX9054_RESET_READS 3300
#define PLX9054_DONE_POLLS 20000

/* One entry of the PCI id table. */
struct hm2_pci_id {
    uint16_t vendor, device, subsystem_vendor, subsystem_device;
    const char *board;     /* board table entry ("5i22-1.0M"); also the "discovered" text */
    const char *model;     /* llio name stem: hm2_<model>.<n> ("5i22") */
    enum hm2_pci_bridge bridge;
    int old_eeprom;        /* 4i68 with the old subsystem id */
};

/* The id-table entry matching all four ids of a device, or NULL (other
 * cards use the same PLX bridges: the subsystem ids decide). */
const struct hm2_pci_id *hm2_pci_match(const struct pci_sysfs_dev *dev);
/* Board facts (connectors, FPGA part, LEDs) for an id entry. */
const struct hm2_board_info *hm2_pci_board_info(const struct hm2_pci_id *id);

/* Access to the PLX control registers (BAR1) and the FPGA configuration
 * byte port (BAR2).  The default goes through the sysfs BARs; tests put a
 * model of the bridge + FPGA here. */
struct hm2_pci_plx_ops {
    int (*ctrl_read)(void *ctx, uint32_t off, uint32_t *val);
    int (*ctrl_write)(void *ctx, uint32_t off, uint32_t val);
    int (*data_write)(void *ctx, uint8_t val);
};

struct hm2_pci_board {
    hm2_llio_t llio; /* first: llio->priv points back here anyway */
    struct pci_sysfs_dev dev;
    const struct hm2_pci_id *id;
    struct pci_bar window, ctrl, data;
    const struct hm2_pci_plx_ops *plx;
    void *plx_ctx;
    hm2_log_fn log;
    void *log_ctx;
};

/* Fill b for device dev (already matched to id and enabled): print
 * "hm2_pci: discovered <board> at <addr>", name the llio
 * hm2_<model>.<type_index>, map the hm2 window, and for PLX boards open the
 * control/data BARs (or use plx/plx_ctx when plx is not NULL), force the
 * 9030 LASxBRD READY bits, install reset/program_fpga.  0 or -errno after
 * logging why; b holds nothing open on failure. */
int hm2_pci_setup(struct hm2_pci_board *b, const struct pci_sysfs_dev *dev,
                  const struct hm2_pci_id *id, int type_index, const struct hm2_pci_plx_ops *plx,
                  void *plx_ctx, hm2_log_fn log, void *log_ctx);
/* Unmap and close what hm2_pci_setup opened (safe to call twice). */
void hm2_pci_teardown(struct hm2_pci_board *b);

/* One board opened by a command-line tool (hm2pinout, hm2flash): the
 * device enabled when it was not (remembered, so closing restores it),
 * then hm2_pci_setup with the default bridge access.  0 or -errno with the
 * reason in why; nothing is left enabled or mapped on failure. */
struct hm2_pci_tool_board {
    struct hm2_pci_board board;
    int was_enabled;
};
int hm2_pci_tool_open(struct hm2_pci_tool_board *t, const struct pci_sysfs_dev *dev,
                      int type_index, hm2_log_fn log, void *log_ctx, char *why, size_t whylen);
void hm2_pci_tool_close(struct hm2_pci_tool_board *t);

/* Per-type board counts for llio names: index of the next board of id's
 * model given the ids already set up (ids[0..n-1]). */
int hm2_pci_type_index(const struct hm2_pci_id *const *ids, int n, const struct hm2_pci_id *id);

#ifdef __cplusplus
}
#endif

#endif /* HM2_PCI_CORE_H */
