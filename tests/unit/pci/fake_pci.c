/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Test doubles for hm2_pci (see fake_pci.h). */
#define _GNU_SOURCE
#include "fake_pci.h"

#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int fake_tree_create(char *root, size_t len)
{
    snprintf(root, len, "/tmp/hm2pci-XXXXXX");
    if (!mkdtemp(root))
        return -1;
    char p[4096];
    snprintf(p, sizeof(p), "%s/bus", root);
    if (mkdir(p, 0755))
        return -1;
    snprintf(p, sizeof(p), "%s/bus/pci", root);
    if (mkdir(p, 0755))
        return -1;
    snprintf(p, sizeof(p), "%s/bus/pci/devices", root);
    return mkdir(p, 0755) ? -1 : 0;
}

static int rm_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    return remove(path);
}

void fake_tree_remove(const char *root)
{
    if (root && strncmp(root, "/tmp/hm2pci-", 12) == 0)
        nftw(root, rm_one, 16, FTW_DEPTH | FTW_PHYS);
}

static int put_text(const char *dir, const char *file, const char *text)
{
    char p[1100];
    snprintf(p, sizeof(p), "%s/%s", dir, file);
    FILE *f = fopen(p, "w");
    if (!f)
        return -1;
    fputs(text, f);
    return fclose(f);
}

int fake_dev_add(const char *root, const char *addr, uint16_t vendor, uint16_t device,
                 uint16_t sub_vendor, uint16_t sub_device, const struct fake_bar bars[6],
                 int enable)
{
    char dir[1024], t[64];
    snprintf(dir, sizeof(dir), "%s/bus/pci/devices/%s", root, addr);
    if (mkdir(dir, 0755))
        return -1;
    const uint16_t v[4] = {vendor, device, sub_vendor, sub_device};
    const char *names[4] = {"vendor", "device", "subsystem_vendor", "subsystem_device"};
    for (int i = 0; i < 4; i++) {
        snprintf(t, sizeof(t), "0x%04x\n", v[i]);
        if (put_text(dir, names[i], t))
            return -1;
    }
    /* "resource": BARs 0-5 then the ROM and bridge windows, as the kernel
     * writes them; addresses are made up, only lengths and flags matter */
    char res[2048] = "";
    unsigned long long start = 0xf0000000ull;
    for (int i = 0; i < 6; i++) {
        char line[96];
        if (bars[i].size) {
            unsigned long long s = bars[i].is_io ? 0xe000ull + 0x100ull * i : start;
            start += 0x100000ull;
            snprintf(line, sizeof(line), "0x%016llx 0x%016llx 0x%016llx\n", s,
                     s + bars[i].size - 1, bars[i].is_io ? 0x40101ull : 0x40200ull);
            char rp[1100];
            snprintf(rp, sizeof(rp), "%s/resource%d", dir, i);
            int fd = open(rp, O_RDWR | O_CREAT | O_TRUNC, 0644);
            size_t fs = bars[i].file_size ? bars[i].file_size : bars[i].size;
            if (fd < 0 || ftruncate(fd, (off_t)fs) != 0)
                return -1;
            close(fd);
        } else {
            snprintf(line, sizeof(line), "0x%016llx 0x%016llx 0x%016llx\n", 0ull, 0ull, 0ull);
        }
        strcat(res, line);
    }
    for (int i = 0; i < 7; i++)
        strcat(res, "0x0000000000000000 0x0000000000000000 0x0000000000000000\n");
    if (put_text(dir, "resource", res))
        return -1;
    if (enable >= 0 && put_text(dir, "enable", enable ? "1\n" : "0\n"))
        return -1;
    return 0;
}

static int file_io(const char *root, const char *addr, const char *file, size_t off, void *data,
                   size_t len, int wr)
{
    char p[4096];
    snprintf(p, sizeof(p), "%s/bus/pci/devices/%s/%s", root, addr, file);
    int fd = open(p, wr ? O_WRONLY : O_RDONLY);
    if (fd < 0)
        return -1;
    ssize_t n = wr ? pwrite(fd, data, len, (off_t)off) : pread(fd, data, len, (off_t)off);
    close(fd);
    return n == (ssize_t)len ? 0 : -1;
}

int fake_file_write(const char *root, const char *addr, const char *file, size_t off,
                    const void *data, size_t len)
{
    return file_io(root, addr, file, off, (void *)data, len, 1);
}

int fake_file_read(const char *root, const char *addr, const char *file, size_t off, void *data,
                   size_t len)
{
    return file_io(root, addr, file, off, data, len, 0);
}

/* ---- bridge + FPGA model ----
 * Xilinx slave configuration: /PROGRAM low clears the device (/INIT and
 * DONE low); after /PROGRAM goes high the FPGA clears its memory and then
 * releases /INIT; only then it takes configuration bytes; when all bytes
 * have arrived and the CRC is good DONE rises (after some clocks), a bad
 * CRC pulls /INIT low.  9030: CTRL/STAT 0x54, /WRITE must be low for the
 * byte port to strobe.  9054: CTRL/STAT 0x6C, USER pins only act as GPIO
 * when their direction enables are set; no /INIT, so the driver waits a
 * fixed number of reads. */

#define B9030_OUT (PLX9030_LED_N | PLX9030_WRITE_N | PLX9030_PROGRAM_N)

void plx_model_init(struct plx_model *m, int is_9054, const uint8_t *expect, size_t n)
{
    memset(m, 0, sizeof(*m));
    m->is_9054 = is_9054;
    m->expect = expect;
    m->nexpect = n;
    m->fail_data_at = -1;
    m->init_delay = 50;
    /* 9030: DONE is checked right after the last byte (the byte strobes
     * clock the FPGA's start-up); the 9054 driver polls for it */
    m->done_delay = is_9054 ? 5 : 0;
    /* power-up: configured from a previous run */
    m->init = 1;
    m->done = 1;
    m->phase = MODEL_DONE;
    m->out = is_9054 ? PLX9054_PROGRAM_N : B9030_OUT;
    m->got_cap = n + 16;
    m->got = calloc(m->got_cap, 1);
}

void plx_model_free(struct plx_model *m)
{
    free(m->got);
    m->got = NULL;
}

static void fpga_program_pin(struct plx_model *m, int level, int was)
{
    if (m->ignore_program)
        return;
    if (!level) {
        m->init = m->done = 0;
        m->phase = MODEL_RESET;
        m->ngot = 0;
    } else if (!was) {
        m->program_pulses++;
        m->phase = MODEL_CLEARING;
        m->countdown = m->init_delay;
        m->reads_since_program = 0;
    }
}

static void on_read_tick(struct plx_model *m)
{
    m->reads_since_program++;
    if (m->phase == MODEL_CLEARING) {
        if (m->countdown == 0) {
            m->init = 1;
            m->phase = MODEL_CONFIG;
        } else if (m->countdown > 0) {
            m->countdown--;
        }
    }
    if (m->done_countdown > 0 && --m->done_countdown == 0)
        m->done = 1;
}

static int model_ctrl_read(void *ctx, uint32_t off, uint32_t *val)
{
    struct plx_model *m = ctx;
    if (!m->is_9054 && off >= PLX9030_LASBRD(0) && off <= PLX9030_LASBRD(3)) {
        *val = m->las[(off - PLX9030_LASBRD(0)) / 4];
        return 0;
    }
    uint32_t reg = m->is_9054 ? PLX9054_CTRL_STAT : PLX9030_CTRL_STAT;
    if (off != reg)
        return -EINVAL;
    m->ctrl_reads++;
    on_read_tick(m);
    if (m->is_9054)
        *val = (m->out & ~PLX9054_DONE) | (m->done ? PLX9054_DONE : 0);
    else
        *val = (m->out & B9030_OUT) | (m->init ? PLX9030_INIT_N : 0) |
               (m->done ? PLX9030_DONE : 0);
    return 0;
}

static int model_ctrl_write(void *ctx, uint32_t off, uint32_t val)
{
    struct plx_model *m = ctx;
    if (!m->is_9054 && off >= PLX9030_LASBRD(0) && off <= PLX9030_LASBRD(3)) {
        m->las[(off - PLX9030_LASBRD(0)) / 4] = val;
        return 0;
    }
    uint32_t reg = m->is_9054 ? PLX9054_CTRL_STAT : PLX9030_CTRL_STAT;
    if (off != reg)
        return -EINVAL;
    m->ctrl_writes++;
    uint32_t was = m->out;
    m->out = val;
    if (m->is_9054) {
        if (val & PLX9054_PROGRAM_ENABLE)
            /* an undriven /PROGRAM is pulled high */
            fpga_program_pin(m, (val & PLX9054_PROGRAM_N) != 0,
                             !(was & PLX9054_PROGRAM_ENABLE) || (was & PLX9054_PROGRAM_N));
    } else {
        fpga_program_pin(m, (val & PLX9030_PROGRAM_N) != 0, (was & PLX9030_PROGRAM_N) != 0);
    }
    return 0;
}

static int model_data_write(void *ctx, uint8_t v)
{
    struct plx_model *m = ctx;
    if (m->fail_data_at >= 0 && m->ngot + (size_t)m->bad_bytes == (size_t)m->fail_data_at)
        return -EIO;
    m->total_bytes++;
    if (m->is_9054) {
        /* the 9054 has no /INIT pin: the FPGA is ready after its clear time */
        if (m->phase == MODEL_CLEARING && m->reads_since_program >= PLX9054_RESET_READS)
            m->phase = MODEL_CONFIG;
        if (m->phase == MODEL_CLEARING)
            m->early_bytes++;
    }
    int taking = m->phase == MODEL_CONFIG && (m->is_9054 || !(m->out & PLX9030_WRITE_N));
    if (!taking || m->ngot >= m->got_cap) {
        m->bad_bytes++;
        return 0;
    }
    m->got[m->ngot++] = v;
    if (m->ngot == m->nexpect) {
        if (memcmp(m->got, m->expect, m->nexpect) != 0) {
            m->init = 0; /* CRC error */
            m->phase = MODEL_RESET;
        } else if (!m->never_done) {
            m->phase = MODEL_DONE;
            m->done_countdown = m->done_delay;
            if (m->done_delay == 0)
                m->done = 1;
        }
    }
    return 0;
}

const struct hm2_pci_plx_ops plx_model_ops = {model_ctrl_read, model_ctrl_write,
                                              model_data_write};
