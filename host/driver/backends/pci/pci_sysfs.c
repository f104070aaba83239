/* SPDX-License-Identifier: GPL-2.0-or-later */
/* PCI devices through sysfs (see pci_sysfs.h for the kernel interfaces). */
#define _GNU_SOURCE
#include "pci_sysfs.h"

#include <dirent.h>
#include <endian.h>
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

/* include/linux/ioport.h */
#define IORESOURCE_IO 0x00000100ull
#define IORESOURCE_MEM 0x00000200ull

const char *hm2_pci_sysfs_root(void)
{
    const char *r = getenv("HM2_PCI_SYSFS_ROOT");
    return (r && r[0]) ? r : "/sys";
}

/* Read a small text file into buf (NUL-terminated).  0 or -errno. */
static int read_small(const char *path, char *buf, size_t len)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return -errno;
    ssize_t n = read(fd, buf, len - 1);
    int e = errno;
    close(fd);
    if (n < 0)
        return -e;
    buf[n] = '\0';
    return 0;
}

int pci_sysfs_read_id(const char *dir, const char *file, uint16_t *val, char *err, size_t errlen)
{
    char path[PCI_SYSFS_PATH_LEN + 32], buf[32];
    snprintf(path, sizeof(path), "%s/%s", dir, file);
    int r = read_small(path, buf, sizeof(buf));
    if (r) {
        snprintf(err, errlen, "cannot read %s: %s", path, strerror(-r));
        return r;
    }
    char *end;
    errno = 0;
    unsigned long v = strtoul(buf, &end, 16);
    while (*end == '\n' || *end == ' ')
        end++;
    if (errno || end == buf || *end != '\0' || v > 0xFFFF) {
        snprintf(err, errlen, "%s: '%.16s' is not a 16-bit hex id", path, buf);
        return -EINVAL;
    }
    *val = (uint16_t)v;
    return 0;
}

static int not_dot(const struct dirent *d)
{
    return d->d_name[0] != '.';
}

static int fill_dev(const char *devdir, const char *name, struct pci_sysfs_dev *d, char *err,
                    size_t errlen)
{
    memset(d, 0, sizeof(*d));
    if (strlen(name) >= sizeof(d->addr)) {
        snprintf(err, errlen, "device name '%s' too long", name);
        return -ENAMETOOLONG;
    }
    snprintf(d->addr, sizeof(d->addr), "%s", name);
    int n = snprintf(d->path, sizeof(d->path), "%s/%s", devdir, name);
    if (n < 0 || (size_t)n >= sizeof(d->path)) {
        snprintf(err, errlen, "path of device %s too long", name);
        return -ENAMETOOLONG;
    }
    int r;
    if ((r = pci_sysfs_read_id(d->path, "vendor", &d->vendor, err, errlen)) ||
        (r = pci_sysfs_read_id(d->path, "device", &d->device, err, errlen)) ||
        (r = pci_sysfs_read_id(d->path, "subsystem_vendor", &d->subsystem_vendor, err, errlen)) ||
        (r = pci_sysfs_read_id(d->path, "subsystem_device", &d->subsystem_device, err, errlen)))
        return r;
    return 0;
}

int pci_sysfs_scan(const char *root, struct pci_sysfs_dev **devs, int *n, int *skipped,
                   char *err, size_t errlen)
{
    char devdir[PCI_SYSFS_PATH_LEN - 64];
    struct dirent **names = NULL;
    *devs = NULL;
    *n = 0;
    if (skipped)
        *skipped = 0;
    int len = snprintf(devdir, sizeof(devdir), "%s/bus/pci/devices", root);
    if (len < 0 || (size_t)len >= sizeof(devdir)) {
        snprintf(err, errlen, "sysfs root '%s' is too long", root);
        return -ENAMETOOLONG;
    }
    int count = scandir(devdir, &names, not_dot, alphasort);
    if (count < 0) {
        int e = errno;
        snprintf(err, errlen, "cannot list PCI devices in %s: %s", devdir, strerror(e));
        return -e;
    }
    struct pci_sysfs_dev *list = calloc(count > 0 ? (size_t)count : 1, sizeof(*list));
    if (!list) {
        snprintf(err, errlen, "out of memory listing %d PCI devices", count);
        for (int i = 0; i < count; i++)
            free(names[i]);
        free(names);
        return -ENOMEM;
    }
    int k = 0;
    for (int i = 0; i < count; i++) {
        char why[PCI_SYSFS_PATH_LEN + 64];
        if (fill_dev(devdir, names[i]->d_name, &list[k], why, sizeof(why)) == 0)
            k++;
        else if (skipped)
            (*skipped)++;
        free(names[i]);
    }
    free(names);
    *devs = list;
    *n = k;
    return 0;
}

int pci_sysfs_bar_info(const struct pci_sysfs_dev *dev, int bar, size_t *size, int *is_io,
                       char *err, size_t errlen)
{
    char path[PCI_SYSFS_PATH_LEN + 16], buf[1024];
    if (bar < 0 || bar >= PCI_SYSFS_NUM_BARS) {
        snprintf(err, errlen, "%s: BAR %d does not exist", dev->addr, bar);
        return -EINVAL;
    }
    snprintf(path, sizeof(path), "%s/resource", dev->path);
    int r = read_small(path, buf, sizeof(buf));
    if (r) {
        snprintf(err, errlen, "cannot read %s: %s", path, strerror(-r));
        return r;
    }
    /* one "start end flags" line per resource, BARs 0..5 first */
    char *line = buf;
    for (int i = 0; i < bar && line; i++) {
        line = strchr(line, '\n');
        if (line)
            line++;
    }
    unsigned long long start, end, flags;
    if (!line || sscanf(line, "%llx %llx %llx", &start, &end, &flags) != 3) {
        snprintf(err, errlen, "%s: no line for BAR %d", path, bar);
        return -EINVAL;
    }
    if ((start == 0 && end == 0) || end < start || !(flags & (IORESOURCE_IO | IORESOURCE_MEM))) {
        snprintf(err, errlen, "%s: BAR %d is not assigned", dev->addr, bar);
        return -ENOENT;
    }
    *size = (size_t)(end - start + 1);
    *is_io = (flags & IORESOURCE_IO) ? 1 : 0;
    return 0;
}

int pci_bar_open(const struct pci_sysfs_dev *dev, int bar, size_t min_size, struct pci_bar *b,
                 char *err, size_t errlen)
{
    memset(b, 0, sizeof(*b));
    b->fd = -1;
    b->index = bar;
    int r = pci_sysfs_bar_info(dev, bar, &b->size, &b->is_io, err, errlen);
    if (r)
        return r;
    if (b->size < min_size) {
        snprintf(err, errlen, "%s: BAR %d is %zu bytes, need %zu", dev->addr, bar, b->size,
                 min_size);
        return -ENXIO;
    }
    snprintf(b->path, sizeof(b->path), "%s/resource%d", dev->path, bar);
    b->fd = open(b->path, O_RDWR | O_SYNC | O_CLOEXEC);
    if (b->fd < 0) {
        r = -errno;
        snprintf(err, errlen, "cannot open %s: %s", b->path, strerror(-r));
        return r;
    }
    /* sysfs gives resourceN the BAR's length as file size; a shorter file
     * (a fake tree) would SIGBUS on mmap access past its end. */
    struct stat st;
    if (fstat(b->fd, &st) == 0 && S_ISREG(st.st_mode) && (size_t)st.st_size < b->size) {
        snprintf(err, errlen, "%s is %lld bytes, but BAR %d is %zu", b->path,
                 (long long)st.st_size, bar, b->size);
        r = -ENXIO;
        goto fail;
    }
    if (!b->is_io) {
        void *m = mmap(NULL, b->size, PROT_READ | PROT_WRITE, MAP_SHARED, b->fd, 0);
        if (m == MAP_FAILED) {
            r = -errno;
            snprintf(err, errlen, "cannot mmap %s (%zu bytes): %s", b->path, b->size,
                     strerror(-r));
            goto fail;
        }
        b->mem = m;
    }
    return 0;
fail:
    close(b->fd);
    b->fd = -1;
    return r;
}

void pci_bar_close(struct pci_bar *b)
{
    if (b->mem)
        munmap((void *)b->mem, b->size);
    b->mem = NULL;
    if (b->fd >= 0)
        close(b->fd);
    b->fd = -1;
}

static int bar_check(const struct pci_bar *b, uint32_t off, size_t len)
{
    if (b->fd < 0 || (size_t)off + len > b->size || off % len != 0)
        return -EINVAL;
    return 0;
}

int pci_bar_read32(struct pci_bar *b, uint32_t off, uint32_t *val)
{
    int r = bar_check(b, off, 4);
    if (r)
        return r;
    if (b->mem) {
        *val = le32toh(b->mem[off / 4]);
        return 0;
    }
    uint32_t le;
    if (pread(b->fd, &le, 4, off) != 4)
        return -EIO;
    *val = le32toh(le);
    return 0;
}

int pci_bar_write32(struct pci_bar *b, uint32_t off, uint32_t val)
{
    int r = bar_check(b, off, 4);
    if (r)
        return r;
    uint32_t le = htole32(val);
    if (b->mem) {
        b->mem[off / 4] = le;
        return 0;
    }
    return pwrite(b->fd, &le, 4, off) == 4 ? 0 : -EIO;
}

int pci_bar_write8(struct pci_bar *b, uint32_t off, uint8_t val)
{
    int r = bar_check(b, off, 1);
    if (r)
        return r;
    if (b->mem) {
        ((volatile uint8_t *)b->mem)[off] = val;
        return 0;
    }
    return pwrite(b->fd, &val, 1, off) == 1 ? 0 : -EIO;
}

int pci_sysfs_enable(const struct pci_sysfs_dev *dev, int *was, char *err, size_t errlen)
{
    char path[PCI_SYSFS_PATH_LEN + 16], buf[16];
    snprintf(path, sizeof(path), "%s/enable", dev->path);
    *was = 1;
    int r = read_small(path, buf, sizeof(buf));
    if (r == -ENOENT)
        return 0;
    if (r) {
        snprintf(err, errlen, "cannot read %s: %s", path, strerror(-r));
        return r;
    }
    if (buf[0] != '0') /* the kernel counts enables: any non-zero is on */
        return 0;
    *was = 0;
    int fd = open(path, O_WRONLY | O_CLOEXEC);
    if (fd < 0 || write(fd, "1", 1) != 1) {
        r = -errno;
        snprintf(err, errlen, "cannot write 1 to %s: %s", path, strerror(-r));
        if (fd >= 0)
            close(fd);
        return r;
    }
    close(fd);
    return 0;
}

int pci_sysfs_disable(const struct pci_sysfs_dev *dev)
{
    char path[PCI_SYSFS_PATH_LEN + 16];
    snprintf(path, sizeof(path), "%s/enable", dev->path);
    int fd = open(path, O_WRONLY | O_CLOEXEC);
    if (fd < 0)
        return -errno;
    int r = write(fd, "0", 1) == 1 ? 0 : -errno;
    close(fd);
    return r;
}

int pci_sysfs_same_addr(const char *want, const char *have)
{
    if (strcmp(want, have) == 0)
        return 1;
    return strncmp(have, "0000:", 5) == 0 && strcmp(want, have + 5) == 0;
}
