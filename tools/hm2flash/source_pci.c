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


static void pci_log(void *ctx, int level, const char *line)
{
    (void)ctx;
    if (level == HM2_ERR || level == HM2_WARN)
        fprintf(stderr, "hm2flash: %s\n", line);
}

int hm2flash_open_pci(const char *addr, const char *board, hm2_llio_t **llio, void **handle,
                      char *why, size_t whylen)
{
    char err[PCI_SYSFS_PATH_LEN + 64];
    struct pci_sysfs_dev *devs = NULL;
    int n = 0, pick = -1, r;
    struct hm2_pci_tool_board *p = calloc(1, sizeof(*p));
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
        int here = !addr[0] || pci_sysfs_same_addr(addr, devs[i].addr);
        if (id && here && strcasecmp(id->model, board) == 0)
            pick = i;
    }
    if (pick < 0) {
        snprintf(why, whylen, "No %s board found%s%s (among the %d PCI devices in "
                              "%s/bus/pci/devices)", board, addr[0] ? " at " : "", addr, n,
                 hm2_pci_sysfs_root());
        r = -ENODEV;
        goto fail;
    }
    r = hm2_pci_tool_open(p, &devs[pick], 0, pci_log, NULL, why, whylen);
    if (r)
        goto fail;
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
    struct hm2_pci_tool_board *p = handle;
    if (!p)
        return;
    hm2_pci_tool_close(p);
    free(p);
}
