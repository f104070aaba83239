/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * source_pci.c - hm2flash's pci: source: a Mesa PCI board found through
 * sysfs ($HM2_PCI_SYSFS_ROOT or /sys) by the hm2_pci backend; the flash
 * registers are reached through its mapped hm2 window.
 *   pci:                 the first Anything-I/O board of the wanted type
 *   pci:0000:01:00.0     the board at that address ("01:00.0" = domain 0000)
 */
#define _GNU_SOURCE
#include "source_pci.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "hm2_pci_core.h"

struct flash_pci {
    struct hm2_pci_board board;
    int was_enabled;
};

static void pci_log(void *ctx, int level, const char *line)
{
    (void)ctx;
    if (level == HM2_ERR || level == HM2_WARN)
        fprintf(stderr, "hm2flash: %s\n", line);
}

static int addr_matches(const char *want, const char *have)
{
    return !want[0] || strcmp(want, have) == 0 ||
           (strncmp(have, "0000:", 5) == 0 && strcmp(want, have + 5) == 0);
}

int hm2flash_open_pci(const char *addr, const char *board, hm2_llio_t **llio, void **handle,
                      char *why, size_t whylen)
{
    char err[PCI_SYSFS_PATH_LEN + 64];
    struct pci_sysfs_dev *devs = NULL;
    int n = 0, pick = -1, r;
    struct flash_pci *p = calloc(1, sizeof(*p));
    if (!p) {
        snprintf(why, whylen, "out of memory");
        return -ENOMEM;
    }
    r = pci_sysfs_scan(hm2_pci_sysfs_root(), &devs, &n, NULL, err, sizeof(err));
    if (r) {
        snprintf(why, whylen, "%s", err);
        goto fail;
    }
    for (int i = 0; i < n && pick < 0; i++) {
        const struct hm2_pci_id *id = hm2_pci_match(&devs[i]);
        if (id && addr_matches(addr, devs[i].addr) && strcasecmp(id->model, board) == 0)
            pick = i;
    }
    if (pick < 0) {
        snprintf(why, whylen, "No %s board found%s%s (among the %d PCI devices in "
                              "%s/bus/pci/devices)", board, addr[0] ? " at " : "", addr, n,
                 hm2_pci_sysfs_root());
        r = -ENODEV;
        goto fail;
    }
    r = pci_sysfs_enable(&devs[pick], &p->was_enabled, err, sizeof(err));
    if (r) {
        snprintf(why, whylen, "cannot enable PCI device %s: %s", devs[pick].addr, err);
        goto fail;
    }
    r = hm2_pci_setup(&p->board, &devs[pick], hm2_pci_match(&devs[pick]), 0, NULL, NULL,
                      pci_log, NULL);
    if (r) {
        if (!p->was_enabled)
            pci_sysfs_disable(&devs[pick]);
        snprintf(why, whylen, "cannot map the hm2 window of %s", devs[pick].addr);
        goto fail;
    }
    free(devs);
    *llio = &p->board.llio;
    *handle = p;
    return 0;
fail:
    free(devs);
    free(p);
    return r;
}

void hm2flash_close_pci(void *handle)
{
    struct flash_pci *p = handle;
    if (!p)
        return;
    hm2_pci_teardown(&p->board);
    if (!p->was_enabled)
        pci_sysfs_disable(&p->board.dev);
    free(p);
}
