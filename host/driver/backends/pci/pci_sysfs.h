/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pci_sysfs.h - PCI devices through Linux sysfs, the interface a user-space
 * driver has: /sys/bus/pci/devices/<addr>/{vendor,device,subsystem_vendor,
 * subsystem_device,resource,resourceN,enable}.
 *
 * Memory BARs are mmap'ed from resourceN (MAP_SHARED) and accessed with
 * aligned 32-bit volatile loads/stores.  I/O-port BARs cannot be mmap'ed on
 * x86; the kernel lets resourceN be pread/pwrite'n instead, where a 1-, 2-
 * or 4-byte access at offset X becomes one inb/inw/inl or outb/outw/outl at
 * BAR start + X.  Both are what the hardware needs; a regular file in a
 * fake tree behaves the same way, which is how the tests run without a card.
 *
 * The sysfs root ("/sys") is a parameter so tests can point it at a
 * directory they built; hm2_pci_sysfs_root() gives $HM2_PCI_SYSFS_ROOT or
 * "/sys".
 */
#ifndef HM2_PCI_SYSFS_H
#define HM2_PCI_SYSFS_H

#include <limits.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PCI_SYSFS_ADDR_LEN 32
#define PCI_SYSFS_PATH_LEN 512
#define PCI_SYSFS_NUM_BARS 6

struct pci_sysfs_dev {
    char addr[PCI_SYSFS_ADDR_LEN]; /* "0000:01:00.0", as the kernel names it */
    char path[PCI_SYSFS_PATH_LEN]; /* <root>/bus/pci/devices/<addr> */
    uint16_t vendor, device, subsystem_vendor, subsystem_device;
};

/* $HM2_PCI_SYSFS_ROOT when set and not empty, else "/sys". */
const char *hm2_pci_sysfs_root(void);

/* List <root>/bus/pci/devices in address order.  *devs is malloc'd (free()
 * it), *n its length.  A device whose id files cannot be read or parsed is
 * left out and, when skipped is not NULL, counted there.  0, or -errno with
 * what failed in err when the directory itself cannot be listed. */
int pci_sysfs_scan(const char *root, struct pci_sysfs_dev **devs, int *n, int *skipped,
                   char *err, size_t errlen);

/* Read one "0x%x" id file of a device directory (vendor, device, ...). */
int pci_sysfs_read_id(const char *dir, const char *file, uint16_t *val, char *err, size_t errlen);

/* One BAR, opened through resourceN. */
struct pci_bar {
    int fd;              /* -1 when closed */
    int index;
    int is_io;           /* I/O-port BAR (pread/pwrite) */
    size_t size;         /* bytes (BAR length) */
    volatile uint32_t *mem; /* memory BAR mapping, NULL for I/O */
    char path[PCI_SYSFS_PATH_LEN + 16];
};

/* BAR flags from the "resource" file: 0 ok; -ENOENT BAR unused (size 0). */
int pci_sysfs_bar_info(const struct pci_sysfs_dev *dev, int bar, size_t *size, int *is_io,
                       char *err, size_t errlen);
/* Open BAR `bar`; at least min_size bytes must be there.  Memory BARs are
 * mapped (min_size bytes or the whole BAR if smaller is enough).  0 or
 * -errno with the reason in err. */
int pci_bar_open(const struct pci_sysfs_dev *dev, int bar, size_t min_size, struct pci_bar *b,
                 char *err, size_t errlen);
void pci_bar_close(struct pci_bar *b);
/* 32-bit and 8-bit register access at byte offset off (32-bit: aligned).
 * Work on both kinds of BAR.  0, -EINVAL (out of range/unaligned) or -EIO. */
int pci_bar_read32(struct pci_bar *b, uint32_t off, uint32_t *val);
int pci_bar_write32(struct pci_bar *b, uint32_t off, uint32_t val);
int pci_bar_write8(struct pci_bar *b, uint32_t off, uint8_t val);

/* The device's "enable" file: *was gets the previous state; the device is
 * enabled (writes "1") when it was not.  A tree without the file counts as
 * enabled.  0 or -errno with the reason in err. */
int pci_sysfs_enable(const struct pci_sysfs_dev *dev, int *was, char *err, size_t errlen);
int pci_sysfs_disable(const struct pci_sysfs_dev *dev);

/* Whether a user's address names device address have: equal, or want
 * without the "0000:" domain ("01:00.0" is "0000:01:00.0"). */
int pci_sysfs_same_addr(const char *want, const char *have);

#ifdef __cplusplus
}
#endif

#endif /* HM2_PCI_SYSFS_H */
