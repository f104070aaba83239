/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_pci - HAL board driver for Mesa's PCI / PC-104+ / PCIe Anything-I/O
 * boards with HostMot2 firmware (docs/hm2_pci.md).  Finds the boards in
 * sysfs ($HM2_PCI_SYSFS_ROOT or /sys), maps their hm2 window and registers
 * each with the hostmot2 core, config[i] for the i-th board found, as
 * LinuxCNC 2.9's hm2_pci does.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "hal.h"
#include "hm2/hostmot2.h"
#include "hm2_board_module.h"
#include "hm2_pci_core.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("Driver for HostMot2 on the 5i2[012345], 6i25, 4i6[589], and 3x20 Anything I/O "
                   "boards from Mesa Electronics");

#define NB HM2_PCI_MAX_BOARDS

static char *config[NB];
RTAPI_MP_ARRAY_STRING(config, NB, "config string for the AnyIO boards (see hostmot2(9) manpage)");

struct hp_slot {
    struct hm2_pci_board board;
    int was_enabled;
    int registered;
};

/* The module's boards (rtapi_app_exit finds them again here). */
static struct hp_slot *slots;
static int num_boards;
static int comp_id = -1;

static void release(struct hp_slot *s)
{
    if (s->registered)
        hm2_unregister(&s->board.llio);
    s->registered = 0;
    hm2_pci_teardown(&s->board);
    if (!s->was_enabled)
        pci_sysfs_disable(&s->board.dev);
}

static void cleanup(void)
{
    if (!slots)
        return;
    for (int i = 0; i < num_boards; i++) {
        rtapi_print("%s: dropping AnyIO board at %s\n", slots[i].board.llio.name,
                    slots[i].board.dev.addr);
        release(&slots[i]);
    }
    free(slots);
    slots = NULL;
    num_boards = 0;
}

/* One matched device: enable, map, register.  1 skipped (no free slot),
 * 0 registered, -errno when the board failed. */
static int probe_one(const struct pci_sysfs_dev *dev, const struct hm2_pci_id *id)
{
    char err[PCI_SYSFS_PATH_LEN + 64];
    if (num_boards >= NB) {
        rtapi_print("hm2_pci: skipping AnyIO board at %s, this driver can only handle %d\n",
                    dev->addr, NB);
        return 1;
    }
    struct hp_slot *s = &slots[num_boards];
    memset(s, 0, sizeof(*s));
    if (pci_sysfs_enable(dev, &s->was_enabled, err, sizeof(err))) {
        rtapi_print("hm2_pci: skipping AnyIO board at %s, failed to enable PCI device\n",
                    dev->addr);
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_pci:     %s\n", err);
        return -ENODEV;
    }
    const struct hm2_pci_id *done[NB];
    for (int i = 0; i < num_boards; i++)
        done[i] = slots[i].board.id;
    int index = hm2_pci_type_index(done, num_boards, id);
    int r = hm2_pci_setup(&s->board, dev, id, index, NULL, NULL, hm2_board_rtapi_log, NULL);
    if (r)
        goto fail;
    s->board.llio.comp_id = comp_id;
    r = hm2_register(&s->board.llio, config[num_boards]);
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: board fails HM2 registration\n", s->board.llio.name);
        hm2_pci_teardown(&s->board);
        goto fail;
    }
    s->registered = 1;
    rtapi_print("%s: initialized AnyIO board at %s\n", s->board.llio.name, dev->addr);
    num_boards++;
    return 0;
fail:
    if (!s->was_enabled)
        pci_sysfs_disable(dev);
    return r;
}

static int probe_all(void)
{
    char err[PCI_SYSFS_PATH_LEN + 64];
    struct pci_sysfs_dev *devs;
    int n, skipped;
    const char *root = hm2_pci_sysfs_root();
    int r = pci_sysfs_scan(root, &devs, &n, &skipped, err, sizeof(err));
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_pci: error registering PCI driver\n");
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_pci:     %s\n", err);
        return r;
    }
    if (skipped)
        rtapi_print_msg(RTAPI_MSG_DBG, "hm2_pci: %d device(s) in %s/bus/pci/devices without "
                                       "readable ids, ignored\n", skipped, root);
    /* as the kernel's PCI core, every board is probed even after one
     * failed; the load then fails with the last error (2.9's failed_errno) */
    int failed = 0;
    for (int i = 0; i < n; i++) {
        const struct hm2_pci_id *id = hm2_pci_match(&devs[i]);
        if (id && (r = probe_one(&devs[i], id)) < 0)
            failed = r;
    }
    free(devs);
    if (failed)
        return failed;
    if (num_boards == 0) {
        /* 2.9 fails with -ENODEV here without a message of its own */
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_pci: no Mesa AnyIO board found in %s/bus/pci/devices\n",
                        root);
        return -ENODEV;
    }
    return 0;
}

int rtapi_app_main(void)
{
    rtapi_print("hm2_pci: loading Mesa AnyIO HostMot2 driver version " HM2_PCI_VERSION "\n");
    comp_id = hal_init("hm2_pci");
    if (comp_id < 0)
        return comp_id;
    slots = calloc(NB, sizeof(*slots));
    if (!slots) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_pci: out of memory for %d board slots\n", NB);
        hal_exit(comp_id);
        comp_id = -1;
        return -ENOMEM;
    }
    int r = probe_all();
    if (r) {
        cleanup();
        hal_exit(comp_id);
        comp_id = -1;
        return r;
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    cleanup();
    if (comp_id >= 0)
        hal_exit(comp_id);
    comp_id = -1;
    rtapi_print("hm2_pci: driver unloaded\n");
}
