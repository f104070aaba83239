/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_pci backend without hardware: sysfs enumeration and BAR access on a
 * fake sysfs tree (regular files mmap'ed / pread like the real resourceN
 * files), board identification against the spec's id table, the hm2 window
 * under the real hostmot2 probe, and the PLX 9030/9054 FPGA programming
 * sequences against a bridge + FPGA model, including the failure modes.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "../check.h"
#include "fake_pci.h"
#include "hm2/bitfile.h"
#include "hm2/hm2.h"
#include "hm2_pci_core.h"
#include "testlib.h"

static char root[4096];
static struct tlog lg;

static const struct fake_bar BARS_NATIVE[6] = {{0x10000, 0, 0}};
static const struct fake_bar BARS_9030[6] = {
    {0x80, 0, 0}, {0x80, 1, 0}, {0x10, 1, 0}, {0, 0, 0}, {0, 0, 0}, {0x10000, 0, 0}};
static const struct fake_bar BARS_9054[6] = {
    {0x200, 0, 0}, {0x100, 1, 0}, {0x10, 1, 0}, {0x10000, 0, 0}, {0, 0, 0}, {0, 0, 0}};

static void fresh_tree(void)
{
    if (root[0])
        fake_tree_remove(root);
    if (fake_tree_create(root, sizeof(root))) {
        perror("fake_tree_create");
        exit(2);
    }
    tlog_clear(&lg);
}

static struct pci_sysfs_dev dev_of(const char *addr)
{
    struct pci_sysfs_dev *d;
    struct pci_sysfs_dev out;
    int n;
    char err[256];
    memset(&out, 0, sizeof(out));
    if (pci_sysfs_scan(root, &d, &n, NULL, err, sizeof(err)) == 0) {
        for (int i = 0; i < n; i++)
            if (strcmp(d[i].addr, addr) == 0)
                out = d[i];
        free(d);
    }
    return out;
}

/* ---- enumeration and identification ---- */

static void test_scan_and_match(void)
{
    fresh_tree();
    CHECK_EQ_INT(fake_dev_add(root, "0000:03:00.0", 0x2718, 0x5125, 0x2718, 0x5125, BARS_NATIVE, 0), 0);
    CHECK_EQ_INT(fake_dev_add(root, "0000:01:00.0", 0x10b5, 0x9030, 0x10b5, 0x3131, BARS_9030, 1), 0);
    /* somebody else's card on the same PLX bridge */
    CHECK_EQ_INT(fake_dev_add(root, "0000:02:00.0", 0x10b5, 0x9030, 0x10b5, 0x9050, BARS_9030, 1), 0);
    CHECK_EQ_INT(fake_dev_add(root, "0000:00:00.0", 0x8086, 0x1237, 0x8086, 0x0000, BARS_NATIVE, 1), 0);
    CHECK_EQ_INT(fake_dev_add(root, "0000:04:00.0", 0x2718, 0x6125, 0x2718, 0x6125, BARS_NATIVE, 1), 0);
    const char bad[] = "zz\n";
    CHECK_EQ_INT(fake_file_write(root, "0000:04:00.0", "vendor", 0, bad, 3), 0);

    struct pci_sysfs_dev *d;
    int n, skipped;
    char err[256];
    CHECK_EQ_INT(pci_sysfs_scan(root, &d, &n, &skipped, err, sizeof(err)), 0);
    CHECK_EQ_INT(n, 4);
    CHECK_EQ_INT(skipped, 1);
    if (n == 4) {
        CHECK_EQ_STR(d[0].addr, "0000:00:00.0");
        CHECK_EQ_STR(d[1].addr, "0000:01:00.0");
        CHECK_EQ_STR(d[3].addr, "0000:03:00.0");
        CHECK_EQ_INT(d[1].vendor, 0x10b5);
        CHECK_EQ_INT(d[1].device, 0x9030);
        CHECK_EQ_INT(d[1].subsystem_vendor, 0x10b5);
        CHECK_EQ_INT(d[1].subsystem_device, 0x3131);
        CHECK(hm2_pci_match(&d[0]) == NULL);
        CHECK(hm2_pci_match(&d[2]) == NULL);
        const struct hm2_pci_id *a = hm2_pci_match(&d[1]), *b = hm2_pci_match(&d[3]);
        CHECK(a && strcmp(a->board, "5i20") == 0 && a->bridge == HM2_PCI_PLX9030);
        CHECK(b && strcmp(b->board, "5i25") == 0 && b->bridge == HM2_PCI_NATIVE);
    }
    free(d);

    /* no sysfs at all */
    char missing[4200];
    snprintf(missing, sizeof(missing), "%s/nothing", root);
    CHECK_EQ_INT(pci_sysfs_scan(missing, &d, &n, &skipped, err, sizeof(err)), -ENOENT);
    CHECK(strstr(err, "cannot list PCI devices in") && strstr(err, "/nothing/bus/pci/devices"));
    CHECK(d == NULL && n == 0);
}

/* The "resource" table and the id files, bad and odd input. */
static void test_sysfs_parsing(void)
{
    fresh_tree();
    CHECK_EQ_INT(fake_dev_add(root, "0000:01:00.0", 0x10b5, 0x9030, 0x10b5, 0x3131, BARS_9030, 1), 0);
    struct pci_sysfs_dev d = dev_of("0000:01:00.0");
    size_t size = 0;
    int io = -1;
    char err[600];
    CHECK_EQ_INT(pci_sysfs_bar_info(&d, 1, &size, &io, err, sizeof(err)), 0);
    CHECK(size == 0x80 && io == 1);
    CHECK_EQ_INT(pci_sysfs_bar_info(&d, 5, &size, &io, err, sizeof(err)), 0);
    CHECK(size == 0x10000 && io == 0);
    CHECK_EQ_INT(pci_sysfs_bar_info(&d, 3, &size, &io, err, sizeof(err)), -ENOENT);
    CHECK(strstr(err, "0000:01:00.0: BAR 3 is not assigned") != NULL);
    CHECK_EQ_INT(pci_sysfs_bar_info(&d, 6, &size, &io, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "BAR 6 does not exist") != NULL);
    struct pci_bar bar;
    CHECK_EQ_INT(pci_bar_open(&d, 3, 4, &bar, err, sizeof(err)), -ENOENT);
    CHECK(bar.fd < 0);
    /* a truncated table */
    const char two[] = "0x0 0xff 0x200\n0xe000 0xe07f 0x101\n";
    char p[4400];
    snprintf(p, sizeof(p), "%s/bus/pci/devices/0000:01:00.0/resource", root);
    FILE *f = fopen(p, "w");
    fputs(two, f);
    fclose(f);
    CHECK_EQ_INT(pci_sysfs_bar_info(&d, 1, &size, &io, err, sizeof(err)), 0);
    CHECK_EQ_INT(pci_sysfs_bar_info(&d, 5, &size, &io, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "/resource: no line for BAR 5") != NULL);
    /* id files: no newline is fine, > 16 bits and junk are not */
    uint16_t v = 0;
    snprintf(p, sizeof(p), "%s/bus/pci/devices/0000:01:00.0/vendor", root);
    f = fopen(p, "w");
    fputs("0x2718", f);
    fclose(f);
    CHECK_EQ_INT(pci_sysfs_read_id(d.path, "vendor", &v, err, sizeof(err)), 0);
    CHECK_EQ_INT(v, 0x2718);
    snprintf(p, sizeof(p), "%s/bus/pci/devices/0000:01:00.0/device", root);
    f = fopen(p, "w");
    fputs("0x12345\n", f);
    fclose(f);
    CHECK_EQ_INT(pci_sysfs_read_id(d.path, "device", &v, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "is not a 16-bit hex id") != NULL);
    CHECK_EQ_INT(pci_sysfs_read_id(d.path, "class", &v, err, sizeof(err)), -ENOENT);
    CHECK(strstr(err, "cannot read") && strstr(err, "/class: No such file or directory"));
}

/* Every id of spec §16 and the "other ids" paragraph. */
static void test_id_table(void)
{
    static const struct {
        uint16_t dev, ssdev;
        const char *board;
        int bridge;
        int conns, width;
        const char *part;
        int leds;
    } want[] = {
        {0x9030, 0x3131, "5i20", HM2_PCI_PLX9030, 3, 24, "2s200pq208", 8},
        {0x9030, 0x3132, "4i65", HM2_PCI_PLX9030, 3, 24, "2s200pq208", 8},
        {0x9054, 0x3314, "5i22-1.0M", HM2_PCI_PLX9054, 4, 24, "3s1000fg320", 8},
        {0x9054, 0x3313, "5i22-1.5M", HM2_PCI_PLX9054, 4, 24, "3s1500fg320", 8},
        {0x9054, 0x3315, "5i23", HM2_PCI_PLX9054, 3, 24, "3s400pq208", 2},
        {0x9054, 0x3311, "4i68", HM2_PCI_PLX9054, 3, 24, "3s400pq208", 4},
        {0x9054, 0x3133, "4i68", HM2_PCI_PLX9054, 3, 24, "3s400pq208", 4},
        {0x9054, 0x3312, "5i21", HM2_PCI_PLX9054, 2, 32, "3s400pq208", 8},
        {0x9054, 0x3472, "4I69-16", HM2_PCI_PLX9054, 3, 24, "6slx16ftg256", 0},
        {0x9054, 0x3473, "4I69-25", HM2_PCI_PLX9054, 3, 24, "6slx25ftg256", 0},
        {0x9056, 0x3427, "3x20-1.0M", HM2_PCI_PLX9054, 6, 24, "3s1000fg456", 0},
        {0x9056, 0x3428, "3x20-1.5M", HM2_PCI_PLX9054, 6, 24, "3s1500fg456", 0},
        {0x9056, 0x3429, "3x20-2.0M", HM2_PCI_PLX9054, 6, 24, "3s2000fg456", 0},
        {0x5124, 0x5124, "5i24", HM2_PCI_NATIVE, 3, 24, "6slx16ftg256", 2},
        {0x5125, 0x5125, "5i25", HM2_PCI_NATIVE, 2, 17, "6slx9tqg144", 2},
        {0x6125, 0x6125, "6i25", HM2_PCI_NATIVE, 2, 17, "6slx9tqg144", 2},
    };
    for (size_t i = 0; i < sizeof(want) / sizeof(want[0]); i++) {
        int mesa = want[i].bridge == HM2_PCI_NATIVE;
        struct pci_sysfs_dev d = {.vendor = mesa ? 0x2718 : 0x10b5, .device = want[i].dev,
                                  .subsystem_vendor = mesa ? 0x2718 : 0x10b5,
                                  .subsystem_device = want[i].ssdev};
        const struct hm2_pci_id *id = hm2_pci_match(&d);
        CHECK(id != NULL);
        if (!id)
            continue;
        CHECK_EQ_STR(id->board, want[i].board);
        CHECK_EQ_INT(id->bridge, want[i].bridge);
        const struct hm2_board_info *b = hm2_pci_board_info(id);
        CHECK(b != NULL);
        if (!b)
            continue;
        CHECK_EQ_INT(b->num_connectors, want[i].conns);
        CHECK_EQ_INT(b->pins_per_connector, want[i].width);
        CHECK_EQ_STR(b->fpga_part, want[i].part);
        CHECK_EQ_INT(b->num_leds, want[i].leds);
        /* a subsystem vendor that is not PLX/Mesa is another product */
        d.subsystem_vendor = 0x1234;
        CHECK(hm2_pci_match(&d) == NULL);
    }
    /* names count per model: two 5i22 variants and both 4i68 ids share */
    struct pci_sysfs_dev a = {.vendor = 0x10b5, .device = 0x9054, .subsystem_vendor = 0x10b5,
                              .subsystem_device = 0x3314};
    struct pci_sysfs_dev b = a, c = a;
    b.subsystem_device = 0x3313;
    c.subsystem_device = 0x3133;
    const struct hm2_pci_id *list[3] = {hm2_pci_match(&a), hm2_pci_match(&c), hm2_pci_match(&b)};
    CHECK_EQ_INT(hm2_pci_type_index(list, 0, list[0]), 0);
    CHECK_EQ_INT(hm2_pci_type_index(list, 1, list[1]), 0);
    CHECK_EQ_INT(hm2_pci_type_index(list, 2, list[2]), 1);
    CHECK_EQ_INT(hm2_pci_type_index(list, 3, list[0]), 2);
}

/* ---- the hm2 window ---- */

static void put_image(const char *addr, const char *res, const struct hm2_image_llio *im)
{
    CHECK_EQ_INT(fake_file_write(root, addr, res, 0, im->mem, HM2_IMAGE_SIZE), 0);
}

static struct hm2_image_llio *new_5i20_image(void)
{
    struct hm2_image_llio *im = calloc(1, sizeof(*im));
    t_setup_5i20(im); /* SVST8_4 from the stock pin-map CSVs */
    return im;
}

/* The pin report the core prints over an llio, as lines. */
static int report(hm2_llio_t *llio, const char *config, const struct hm2_options *opts,
                  struct tlog *out)
{
    int err;
    tlog_clear(out);
    hostmot2_t *hm2 = hm2_probe(llio, config, opts, tlog_sink, out, &err);
    if (!hm2)
        return err;
    hm2_print_pin_usage(hm2);
    hm2_free(hm2);
    return 0;
}

static int same_report_lines(const struct tlog *a, const struct tlog *b)
{
    int ia = tlog_find(a, "hm2/hm2_5i20.0: 72 I/O Pins used:", 0);
    int ib = tlog_find(b, "hm2/hm2_5i20.0: 72 I/O Pins used:", 0);
    if (ia < 0 || ib < 0 || a->n - ia != b->n - ib)
        return 0;
    for (int k = 0; ia + k < a->n; k++)
        if (strcmp(a->line[ia + k], b->line[ib + k]) != 0)
            return 0;
    return 1;
}

static void test_window_5i20(void)
{
    fresh_tree();
    CHECK_EQ_INT(fake_dev_add(root, "0000:02:02.0", 0x10b5, 0x9030, 0x10b5, 0x3131, BARS_9030, 1), 0);
    struct hm2_image_llio *im = new_5i20_image();
    put_image("0000:02:02.0", "resource5", im);
    struct pci_sysfs_dev d = dev_of("0000:02:02.0");
    struct hm2_pci_board *b = calloc(1, sizeof(*b));
    struct plx_model m;
    plx_model_init(&m, 0, NULL, 0);
    m.las[1] = PLX9030_LASBRD_READY;
    CHECK_EQ_INT(hm2_pci_setup(b, &d, hm2_pci_match(&d), 0, &plx_model_ops, &m, tlog_sink, &lg), 0);
    CHECK_EQ_INT(tlog_find(&lg, "hm2_pci: discovered 5i20 at 0000:02:02.0", 0), 0);
    CHECK_EQ_STR(b->llio.name, "hm2_5i20.0");
    CHECK_EQ_INT(b->llio.threadsafe, 1);
    CHECK(b->llio.reset && b->llio.program_fpga);

    /* cookie and config name at the spec's addresses, through the mmap */
    uint32_t w[3] = {0};
    CHECK_EQ_INT(b->llio.read(&b->llio, 0x100, w, 12), 0);
    CHECK_EQ_INT(w[0], 0x55AACAFEu);
    CHECK(memcmp(&w[1], "HOSTMOT2", 8) == 0);
    /* a write lands little-endian in the BAR file at the same offset */
    uint32_t v = 0x12345678u;
    CHECK_EQ_INT(b->llio.write(&b->llio, 0x1000, &v, 4), 0);
    uint8_t raw[4];
    CHECK_EQ_INT(fake_file_read(root, "0000:02:02.0", "resource5", 0x1000, raw, 4), 0);
    CHECK(raw[0] == 0x78 && raw[1] == 0x56 && raw[2] == 0x34 && raw[3] == 0x12);
    /* only aligned words inside the 64 KiB window */
    CHECK_EQ_INT(b->llio.read(&b->llio, 0x102, w, 4), -EINVAL);
    CHECK_EQ_INT(b->llio.read(&b->llio, 0x100, w, 6), -EINVAL);
    CHECK_EQ_INT(b->llio.read(&b->llio, 0xFFFC, w, 8), -EINVAL);
    CHECK_EQ_INT(b->llio.write(&b->llio, 0x10000, &v, 4), -EINVAL);
    CHECK_EQ_INT(b->llio.read(&b->llio, 0xFFFC, w, 4), 0);

    /* the hostmot2 probe reads the IDROM through the window: the same
     * pin report as over the image itself, incl. the spec's example line */
    struct tlog *via_pci = calloc(1, sizeof(*via_pci)), *via_image = calloc(1, sizeof(*via_image));
    const char *cfg = "num_encoders=1 num_pwmgens=1 num_stepgens=3";
    CHECK_EQ_INT(report(&b->llio, cfg, NULL, via_pci), 0);
    CHECK_EQ_INT(report(&im->llio, cfg, NULL, via_image), 0);
    CHECK(same_report_lines(via_pci, via_image));
    CHECK(tlog_find(via_pci, "hm2/hm2_5i20.0:     IO Pin 002 (P2-05): Encoder #0, pin B (Input)",
                    0) >= 0);
    CHECK(tlog_find(via_pci, "hm2/hm2_5i20.0:     IO Pin 011 (P2-23): PWMGen #0, pin Not-Enable "
                             "(Output)", 0) >= 0);
    /* no firmware= on a programmable board: the core warns, nothing is
     * programmed (the model saw no /PROGRAM pulse) */
    CHECK(tlog_contains(via_pci, "no firmware specified in config modparam!"));
    CHECK_EQ_INT(m.program_pulses, 0);

    hm2_pci_teardown(b);
    hm2_pci_teardown(b);
    plx_model_free(&m);
    tlog_clear(via_pci);
    tlog_clear(via_image);
    free(via_pci);
    free(via_image);
    free(b);
    free(im);
}

static void test_window_errors(void)
{
    fresh_tree();
    /* BAR0 only 4 KiB: cannot be the hm2 window */
    struct fake_bar small[6] = {{0x1000, 0, 0}};
    CHECK_EQ_INT(fake_dev_add(root, "0000:05:00.0", 0x2718, 0x5125, 0x2718, 0x5125, small, 1), 0);
    /* resource file claims 64 KiB but the resource0 file is short */
    struct fake_bar shortf[6] = {{0x10000, 0, 0x1000}};
    CHECK_EQ_INT(fake_dev_add(root, "0000:06:00.0", 0x2718, 0x5125, 0x2718, 0x5125, shortf, 1), 0);
    /* BAR0 is an I/O BAR */
    struct fake_bar io[6] = {{0x10000, 1, 0}};
    CHECK_EQ_INT(fake_dev_add(root, "0000:07:00.0", 0x2718, 0x6125, 0x2718, 0x6125, io, 1), 0);
    struct hm2_pci_board b;
    struct pci_sysfs_dev d = dev_of("0000:05:00.0");
    CHECK_EQ_INT(hm2_pci_setup(&b, &d, hm2_pci_match(&d), 0, NULL, NULL, tlog_sink, &lg), -ENXIO);
    CHECK(tlog_find(&lg, "hm2_5i25.0: could not map in FPGA address space", 0) >= 0);
    CHECK(tlog_contains(&lg, "0000:05:00.0: BAR 0 is 4096 bytes, need 65536"));
    CHECK(b.window.fd < 0 && b.window.mem == NULL);

    tlog_clear(&lg);
    d = dev_of("0000:06:00.0");
    CHECK_EQ_INT(hm2_pci_setup(&b, &d, hm2_pci_match(&d), 1, NULL, NULL, tlog_sink, &lg), -ENXIO);
    CHECK(tlog_find(&lg, "hm2_5i25.1: could not map in FPGA address space", 0) >= 0);
    CHECK(tlog_contains(&lg, "resource0 is 4096 bytes, but BAR 0 is 65536"));

    /* an I/O BAR as window: opened but not mapped; every access refused */
    tlog_clear(&lg);
    d = dev_of("0000:07:00.0");
    CHECK_EQ_INT(hm2_pci_setup(&b, &d, hm2_pci_match(&d), 0, NULL, NULL, tlog_sink, &lg), 0);
    uint32_t w;
    CHECK_EQ_INT(b.llio.read(&b.llio, 0x100, &w, 4), -EINVAL);
    hm2_pci_teardown(&b);

    /* a vanished resource file */
    char p[4300];
    snprintf(p, sizeof(p), "%s/bus/pci/devices/0000:05:00.0/resource", root);
    remove(p);
    tlog_clear(&lg);
    d = dev_of("0000:05:00.0");
    CHECK_EQ_INT(hm2_pci_setup(&b, &d, hm2_pci_match(&d), 0, NULL, NULL, tlog_sink, &lg), -ENOENT);
    CHECK(tlog_contains(&lg, "cannot read") && tlog_contains(&lg, "No such file"));
}

/* 9030 setup through the real sysfs path: BAR1 is an I/O BAR (pread /
 * pwrite of resource1), the LASxBRD READY fix-up lands in it. */
static void test_9030_lasbrd_sysfs(void)
{
    fresh_tree();
    CHECK_EQ_INT(fake_dev_add(root, "0000:01:00.0", 0x10b5, 0x9030, 0x10b5, 0x3132, BARS_9030, 1), 0);
    const uint32_t las[4] = {0x00000000u, 0xABCD0002u, 0x11110000u, 0x00400001u};
    CHECK_EQ_INT(fake_file_write(root, "0000:01:00.0", "resource1", 0x28, las, 16), 0);
    struct pci_sysfs_dev d = dev_of("0000:01:00.0");
    struct hm2_pci_board b;
    CHECK_EQ_INT(hm2_pci_setup(&b, &d, hm2_pci_match(&d), 2, NULL, NULL, tlog_sink, &lg), 0);
    CHECK_EQ_STR(b.llio.name, "hm2_4i65.2");
    CHECK(b.ctrl.is_io && b.data.is_io && b.ctrl.mem == NULL);
    uint32_t got[4];
    CHECK_EQ_INT(fake_file_read(root, "0000:01:00.0", "resource1", 0x28, got, 16), 0);
    CHECK_EQ_INT(got[0], 0x00000002u);
    CHECK_EQ_INT(got[1], 0xABCD0002u);
    CHECK_EQ_INT(got[2], 0x11110002u);
    CHECK_EQ_INT(got[3], 0x00400003u);
    CHECK(tlog_find(&lg, "hm2_4i65.2: LAS0BRD #READY is off, enabling now", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2_4i65.2: LAS1BRD #READY is off, enabling now", 0) < 0);
    CHECK(tlog_find(&lg, "hm2_4i65.2: LAS2BRD #READY is off, enabling now", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2_4i65.2: LAS3BRD #READY is off, enabling now", 0) >= 0);
    CHECK_EQ_INT(lg.level[tlog_find(&lg, "hm2_4i65.2: LAS0BRD #READY is off, enabling now", 0)],
                 HM2_INFO);
    /* the configuration byte port: one byte written at offset 0 of BAR2 */
    struct hm2_bitfile bf = {.part = "2s200pq208", .data = (const uint8_t *)"\x01\xAA\x0F",
                             .size = 3};
    /* no FPGA behind the files: /INIT never comes back after reset */
    CHECK_EQ_INT(b.llio.reset(&b.llio), -EIO);
    CHECK(tlog_contains(&lg, "hm2_4i65.2: FPGA did not"));
    CHECK_EQ_INT(b.llio.program_fpga(&b.llio, &bf), -EIO);
    uint8_t last;
    CHECK_EQ_INT(fake_file_read(root, "0000:01:00.0", "resource2", 0, &last, 1), 0);
    CHECK_EQ_INT(last, 0xF0); /* the last byte 0x0F, bit-reversed */
    hm2_pci_teardown(&b);
}

/* 9054 through the real sysfs path: CTRL/STAT at BAR1 + 0x6C is an I/O
 * register; with nothing behind the file DONE reads 0, so the reset
 * passes and programming ends in the DONE timeout. */
static void test_9054_sysfs(void)
{
    fresh_tree();
    CHECK_EQ_INT(fake_dev_add(root, "0000:04:00.0", 0x10b5, 0x9056, 0x10b5, 0x3428, BARS_9054, 1), 0);
    struct pci_sysfs_dev d = dev_of("0000:04:00.0");
    struct hm2_pci_board b;
    CHECK_EQ_INT(hm2_pci_setup(&b, &d, hm2_pci_match(&d), 0, NULL, NULL, tlog_sink, &lg), 0);
    CHECK_EQ_STR(b.llio.name, "hm2_3x20.0");
    CHECK_EQ_STR(b.llio.fpga_part_number, "3s1500fg456");
    CHECK_EQ_INT(b.llio.reset(&b.llio), 0);
    uint32_t ctl = 0;
    CHECK_EQ_INT(fake_file_read(root, "0000:04:00.0", "resource1", PLX9054_CTRL_STAT, &ctl, 4), 0);
    CHECK_EQ_INT(ctl, PLX9054_PROGRAM_N | PLX9054_DONE_ENABLE | PLX9054_PROGRAM_ENABLE);
    struct hm2_bitfile bf = {.part = "3s1500fg456", .data = (const uint8_t *)"\x80", .size = 1};
    CHECK_EQ_INT(b.llio.program_fpga(&b.llio, &bf), -EIO);
    CHECK(tlog_find(&lg, "hm2_3x20.0: Error: Not /DONE; programming not completed.", 0) >= 0);
    uint8_t last = 0;
    CHECK_EQ_INT(fake_file_read(root, "0000:04:00.0", "resource2", 0, &last, 1), 0);
    CHECK_EQ_INT(last, 0x01);
    hm2_pci_teardown(&b);
}

/* ---- enable file ---- */
static void test_enable(void)
{
    fresh_tree();
    CHECK_EQ_INT(fake_dev_add(root, "0000:01:00.0", 0x2718, 0x5125, 0x2718, 0x5125, BARS_NATIVE, 0), 0);
    CHECK_EQ_INT(fake_dev_add(root, "0000:02:00.0", 0x2718, 0x5125, 0x2718, 0x5125, BARS_NATIVE, -1), 0);
    struct pci_sysfs_dev d = dev_of("0000:01:00.0");
    int was = -1;
    char err[256], buf[2] = {0};
    CHECK_EQ_INT(pci_sysfs_enable(&d, &was, err, sizeof(err)), 0);
    CHECK_EQ_INT(was, 0);
    CHECK_EQ_INT(fake_file_read(root, "0000:01:00.0", "enable", 0, buf, 1), 0);
    CHECK_EQ_INT(buf[0], '1');
    CHECK_EQ_INT(pci_sysfs_enable(&d, &was, err, sizeof(err)), 0);
    CHECK_EQ_INT(was, 1);
    CHECK_EQ_INT(pci_sysfs_disable(&d), 0);
    CHECK_EQ_INT(fake_file_read(root, "0000:01:00.0", "enable", 0, buf, 1), 0);
    CHECK_EQ_INT(buf[0], '0');
    d = dev_of("0000:02:00.0");
    CHECK_EQ_INT(pci_sysfs_enable(&d, &was, err, sizeof(err)), 0);
    CHECK_EQ_INT(was, 1);
}

/* ---- PLX programming against the bridge + FPGA model ---- */

/* Independent reference for the port order: D0 gets the byte's MSB. */
static uint8_t ref_reverse(uint8_t x)
{
    uint8_t r = 0;
    for (int i = 0; i < 8; i++)
        if (x & (1u << i))
            r |= (uint8_t)(0x80u >> i);
    return r;
}

#define NBYTES 4096
static uint8_t stream[NBYTES], port_order[NBYTES];

static void make_stream(void)
{
    uint32_t x = 0x12345678u;
    for (int i = 0; i < NBYTES; i++) {
        x = x * 1103515245u + 12345u;
        stream[i] = (uint8_t)(x >> 16);
        port_order[i] = ref_reverse(stream[i]);
    }
}

struct rig {
    struct hm2_pci_board b;
    struct plx_model m;
    struct hm2_bitfile bf;
};

static void rig_up(struct rig *r, int is_9054)
{
    fresh_tree();
    const char *addr = "0000:01:00.0";
    if (is_9054)
        CHECK_EQ_INT(fake_dev_add(root, addr, 0x10b5, 0x9054, 0x10b5, 0x3315, BARS_9054, 1), 0);
    else
        CHECK_EQ_INT(fake_dev_add(root, addr, 0x10b5, 0x9030, 0x10b5, 0x3131, BARS_9030, 1), 0);
    struct pci_sysfs_dev d = dev_of(addr);
    plx_model_init(&r->m, is_9054, port_order, NBYTES);
    CHECK_EQ_INT(hm2_pci_setup(&r->b, &d, hm2_pci_match(&d), 0, &plx_model_ops, &r->m, tlog_sink,
                               &lg), 0);
    r->bf = (struct hm2_bitfile){.part = is_9054 ? "3s400pq208" : "2s200pq208",
                                 .data = stream, .size = NBYTES};
}

static void rig_down(struct rig *r)
{
    hm2_pci_teardown(&r->b);
    plx_model_free(&r->m);
}

static void test_9030_program_ok(void)
{
    struct rig r;
    rig_up(&r, 0);
    CHECK_EQ_INT(r.m.las[0] & PLX9030_LASBRD_READY, PLX9030_LASBRD_READY);
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), 0);
    CHECK_EQ_INT(r.m.program_pulses, 1);
    CHECK_EQ_INT(r.m.init, 1);
    CHECK_EQ_INT(r.b.llio.program_fpga(&r.b.llio, &r.bf), 0);
    CHECK_EQ_INT(r.m.ngot, NBYTES);
    CHECK(memcmp(r.m.got, port_order, NBYTES) == 0);
    CHECK_EQ_INT(r.m.bad_bytes, 0);
    CHECK_EQ_INT(r.m.done, 1);
    /* after programming: /WRITE and /LED high (idle), /PROGRAM high */
    CHECK_EQ_INT(r.m.out & (PLX9030_WRITE_N | PLX9030_LED_N | PLX9030_PROGRAM_N),
                 PLX9030_WRITE_N | PLX9030_LED_N | PLX9030_PROGRAM_N);
    /* slow memory clear, still inside the 3300-read budget */
    r.m.init_delay = 3000;
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), 0);
    CHECK_EQ_INT(r.m.init, 1);
    rig_down(&r);
}

static void test_9030_program_faults(void)
{
    struct rig r;
    /* /INIT stuck low after /PROGRAM */
    rig_up(&r, 0);
    r.m.init_delay = -1;
    int reads0 = r.m.ctrl_reads;
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), -EIO);
    CHECK(tlog_find(&lg, "hm2_5i20.0: FPGA did not come out of /INIT", 0) >= 0);
    /* 1 status read before /PROGRAM, 1 check, then the 3300 polls */
    CHECK_EQ_INT(r.m.ctrl_reads - reads0, 2 + PLX9030_INIT_POLLS);
    rig_down(&r);

    /* FPGA does not react to /PROGRAM (DONE and /INIT stay high) */
    rig_up(&r, 0);
    r.m.ignore_program = 1;
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), -EIO);
    CHECK(tlog_find(&lg, "hm2_5i20.0: FPGA did not reset: /INIT = 1, DONE = 1", 0) >= 0);
    rig_down(&r);

    /* CRC error: the FPGA wanted other bytes -> /INIT low */
    rig_up(&r, 0);
    static uint8_t other[NBYTES];
    memcpy(other, port_order, NBYTES);
    other[100] ^= 0x10;
    r.m.expect = other;
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), 0);
    CHECK_EQ_INT(r.b.llio.program_fpga(&r.b.llio, &r.bf), -EIO);
    CHECK(tlog_find(&lg, "hm2_5i20.0: FPGA asserted /INIT: CRC error", 0) >= 0);
    CHECK_EQ_INT(r.m.out & PLX9030_PROGRAM_N, 0); /* held in reset */
    CHECK_EQ_INT(r.m.out & (PLX9030_WRITE_N | PLX9030_LED_N), PLX9030_WRITE_N | PLX9030_LED_N);
    rig_down(&r);

    /* all bytes in, DONE never rises */
    rig_up(&r, 0);
    r.m.never_done = 1;
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), 0);
    CHECK_EQ_INT(r.b.llio.program_fpga(&r.b.llio, &r.bf), -EIO);
    CHECK(tlog_find(&lg, "hm2_5i20.0: FPGA did not assert DONE", 0) >= 0);
    CHECK_EQ_INT(r.m.out & PLX9030_PROGRAM_N, 0);
    rig_down(&r);

    /* the byte port fails half way */
    rig_up(&r, 0);
    r.m.fail_data_at = 10;
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), 0);
    CHECK_EQ_INT(r.b.llio.program_fpga(&r.b.llio, &r.bf), -EIO);
    CHECK(tlog_contains(&lg, "hm2_5i20.0: writing configuration byte 10 of 4096 failed"));
    CHECK_EQ_INT(r.m.total_bytes, 10);
    rig_down(&r);
}

static void test_9054_program(void)
{
    struct rig r;
    rig_up(&r, 1);
    CHECK_EQ_STR(r.b.llio.name, "hm2_5i23.0");
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), 0);
    CHECK_EQ_INT(r.m.out & (PLX9054_DONE_ENABLE | PLX9054_PROGRAM_ENABLE),
                 PLX9054_DONE_ENABLE | PLX9054_PROGRAM_ENABLE);
    CHECK_EQ_INT(r.m.program_pulses, 1);
    CHECK(r.m.reads_since_program >= PLX9054_RESET_READS);
    r.m.done_delay = 1000;
    CHECK_EQ_INT(r.b.llio.program_fpga(&r.b.llio, &r.bf), 0);
    CHECK_EQ_INT(r.m.ngot, NBYTES);
    CHECK(memcmp(r.m.got, port_order, NBYTES) == 0);
    CHECK_EQ_INT(r.m.early_bytes + r.m.bad_bytes, 0);
    CHECK_EQ_INT(r.m.done, 1);
    rig_down(&r);

    /* DONE never rises: exactly 20000 polls, then the 2.9 message */
    rig_up(&r, 1);
    r.m.never_done = 1;
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), 0);
    int reads0 = r.m.ctrl_reads;
    CHECK_EQ_INT(r.b.llio.program_fpga(&r.b.llio, &r.bf), -EIO);
    CHECK_EQ_INT(r.m.ctrl_reads - reads0, PLX9054_DONE_POLLS);
    CHECK(tlog_find(&lg, "hm2_5i23.0: Error: Not /DONE; programming not completed.", 0) >= 0);
    rig_down(&r);

    /* DONE stuck high: the reset refuses */
    rig_up(&r, 1);
    r.m.ignore_program = 1;
    CHECK_EQ_INT(r.b.llio.reset(&r.b.llio), -EIO);
    CHECK(tlog_find(&lg, "hm2_5i23.0: /DONE status bit indicates busy at start of programming",
                    0) >= 0);
    rig_down(&r);
}

/* ---- the whole load sequence: firmware file -> reset -> program ->
 * IDROM through the window (hm2_probe, as hm2_register runs it) ---- */

static size_t put_small(uint8_t *p, char tag, const char *text)
{
    size_t n = strlen(text) + 1;
    p[0] = (uint8_t)tag;
    p[1] = (uint8_t)(n >> 8);
    p[2] = (uint8_t)n;
    memcpy(p + 3, text, n);
    return 3 + n;
}

/* A .BIT container (spec §18) around data. */
static int write_bit(const char *path, const char *part, const uint8_t *data, uint32_t n)
{
    static const uint8_t hdr[13] = {0, 9, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F, 0xF0, 0, 0, 1};
    uint8_t *buf = malloc(n + 256);
    size_t pos = 13;
    memcpy(buf, hdr, 13);
    pos += put_small(buf + pos, 'a', "PCITEST.ncd;UserID=0xFFFFFFFF");
    pos += put_small(buf + pos, 'b', part);
    pos += put_small(buf + pos, 'c', "2026/11/24");
    pos += put_small(buf + pos, 'd', "01:02:03");
    buf[pos++] = 'e';
    for (int s = 24; s >= 0; s -= 8)
        buf[pos++] = (uint8_t)(n >> s);
    memcpy(buf + pos, data, n);
    pos += n;
    FILE *f = fopen(path, "wb");
    int r = (f && fwrite(buf, 1, pos, f) == pos) ? 0 : -1;
    if (f)
        fclose(f);
    free(buf);
    return r;
}

static void test_probe_with_firmware(void)
{
    struct rig r;
    rig_up(&r, 0);
    struct hm2_image_llio *im = new_5i20_image();
    put_image("0000:01:00.0", "resource5", im);
    char fwdir[4200], p[4300];
    snprintf(fwdir, sizeof(fwdir), "%s/fw", root);
    mkdir(fwdir, 0755);
    snprintf(p, sizeof(p), "%s/hm2", fwdir);
    mkdir(p, 0755);
    snprintf(p, sizeof(p), "%s/hm2/good.bit", fwdir);
    CHECK_EQ_INT(write_bit(p, "2s200pq208", stream, NBYTES), 0);
    snprintf(p, sizeof(p), "%s/hm2/other.bit", fwdir);
    CHECK_EQ_INT(write_bit(p, "3s400pq208", stream, NBYTES), 0);
    struct hm2_options opts = {{0, 0, 0, 0}, fwdir};
    struct tlog *out = calloc(1, sizeof(*out));

    CHECK_EQ_INT(report(&r.b.llio, "firmware=hm2/good.bit num_encoders=1 num_pwmgens=1 "
                        "num_stepgens=3", &opts, out), 0);
    CHECK_EQ_INT(r.m.program_pulses, 1);
    CHECK(memcmp(r.m.got, port_order, NBYTES) == 0);
    CHECK(tlog_find(out, "hm2/hm2_5i20.0:     Part Name: 2s200pq208", 0) >= 0);
    CHECK(tlog_find(out, "hm2/hm2_5i20.0: 72 I/O Pins used:", 0) >= 0);

    /* firmware for another FPGA: refused before the board is touched */
    r.m.program_pulses = 0;
    CHECK_EQ_INT(report(&r.b.llio, "firmware=hm2/other.bit", &opts, out), -EINVAL);
    CHECK(tlog_find(out, "hm2/hm2_5i20.0: board has FPGA '2s200pq208', but the firmware in "
                         "hm2/other.bit is for FPGA '3s400pq208'", 0) >= 0);
    CHECK_EQ_INT(r.m.program_pulses, 0);

    /* programming fails: the load stops with the core's message */
    r.m.never_done = 1;
    CHECK(report(&r.b.llio, "firmware=hm2/good.bit", &opts, out) < 0);
    CHECK(tlog_find(out, "hm2_5i20.0: FPGA did not assert DONE", 0) >= 0 ||
          tlog_contains(&lg, "hm2_5i20.0: FPGA did not assert DONE"));
    CHECK(tlog_find(out, "hm2/hm2_5i20.0: failed to program fpga, aborting hm2_register", 0) >= 0);

    /* reset fails */
    r.m.never_done = 0;
    r.m.init_delay = -1;
    CHECK(report(&r.b.llio, "firmware=hm2/good.bit", &opts, out) < 0);
    CHECK(tlog_find(out, "hm2/hm2_5i20.0: failed to reset fpga, aborting hm2_register", 0) >= 0);
    tlog_clear(out);
    free(out);
    free(im);
    rig_down(&r);
}

int main(void)
{
    make_stream();
    RUN(test_scan_and_match);
    RUN(test_sysfs_parsing);
    RUN(test_id_table);
    RUN(test_window_5i20);
    RUN(test_window_errors);
    RUN(test_9030_lasbrd_sysfs);
    RUN(test_9054_sysfs);
    RUN(test_enable);
    RUN(test_9030_program_ok);
    RUN(test_9030_program_faults);
    RUN(test_9054_program);
    RUN(test_probe_with_firmware);
    if (check_failures_)
        tlog_dump(&lg);
    tlog_clear(&lg);
    fake_tree_remove(root);
    return check_summary();
}
