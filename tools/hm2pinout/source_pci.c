/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2pinout's pci: source: a Mesa PCI board found through sysfs
 * ($HM2_PCI_SYSFS_ROOT or /sys) by the hm2_pci backend, read through its
 * mapped hm2 window.  The FPGA is never (re)programmed: the report is of
 * the firmware the board runs now.
 *   pci:                 the first Anything-I/O board found
 *   pci:0000:01:00.0     the board at that address ("01:00.0" = domain 0000)
 */
#define _GNU_SOURCE
#include "source_pci.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2_pci_core.h"


static void pci_log(void *ctx, int level, const char *line)
{
    (void)ctx;
    if (level == HM2_ERR || level == HM2_WARN)
        fprintf(stderr, "hm2pinout: %s\n", line);
}

static int pick(const struct pci_sysfs_dev *devs, int n, const char *addr)
{
    int seen_other = -1;
    for (int i = 0; i < n; i++) {
        if (addr[0] && !pci_sysfs_same_addr(addr, devs[i].addr))
            continue;
        if (hm2_pci_match(&devs[i]))
            return i;
        if (addr[0])
            seen_other = i;
    }
    if (seen_other >= 0)
        fprintf(stderr,
                "hm2pinout: PCI device %s (%04x:%04x, subsystem %04x:%04x) is not a Mesa "
                "Anything-I/O board\n",
                devs[seen_other].addr, devs[seen_other].vendor, devs[seen_other].device,
                devs[seen_other].subsystem_vendor, devs[seen_other].subsystem_device);
    else if (addr[0])
        fprintf(stderr, "hm2pinout: no PCI device %s\n", addr);
    else
        fprintf(stderr, "hm2pinout: no Mesa Anything-I/O PCI board among the %d devices in "
                        "%s/bus/pci/devices\n", n, hm2_pci_sysfs_root());
    return -1;
}

int hm2pinout_open_pci(const char *addr, int index, hm2_llio_t **llio, void **handle)
{
    char err[PCI_SYSFS_PATH_LEN + 64];
    struct pci_sysfs_dev *devs = NULL;
    int n, r;
    struct hm2_pci_tool_board *p = calloc(1, sizeof(*p));
    if (!p) {
        fprintf(stderr, "hm2pinout: out of memory\n");
        return -ENOMEM;
    }
    r = pci_sysfs_scan(hm2_pci_sysfs_root(), &devs, &n, NULL, err, sizeof(err));
    if (r) {
        fprintf(stderr, "hm2pinout: %s\n", err);
        goto fail;
    }
    int i = pick(devs, n, addr);
    if (i < 0) {
        r = -ENODEV;
        goto fail;
    }
    char why[PCI_SYSFS_PATH_LEN + 128];
    r = hm2_pci_tool_open(p, &devs[i], index, pci_log, NULL, why, sizeof(why));
    if (r) {
        fprintf(stderr, "hm2pinout: %s\n", why);
        goto fail;
    }
    /* report what runs now: no reset, no programming */
    p->board.llio.reset = NULL;
    p->board.llio.program_fpga = NULL;
    free(devs);
    *llio = &p->board.llio;
    *handle = p;
    return 0;
fail:
    free(devs);
    free(p);
    return r;
}

void hm2pinout_close_pci(void *handle)
{
    struct hm2_pci_tool_board *p = handle;
    if (!p)
        return;
    hm2_pci_tool_close(p);
    free(p);
}
