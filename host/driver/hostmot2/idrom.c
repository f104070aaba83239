/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Reading and validating the ID block, IDROM header, pin descriptors and
 * module descriptors (spec §2-§5, §11 steps 4-5, §15).  Every read is
 * bounds-checked against the 64 KiB register space before it reaches the
 * llio, so a corrupt offset can never index out of range. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/hm2.h"

static int bus_read(hostmot2_t *hm2, uint32_t addr, void *buf, size_t size)
{
    if (addr >= HM2_ADDR_SPACE || size > HM2_ADDR_SPACE - addr || (addr & 3) || (size & 3))
        return -EINVAL;
    return hm2->llio->read(hm2->llio, addr, buf, size);
}

int hm2_read_reg(hostmot2_t *hm2, uint32_t addr, uint32_t *val)
{
    return bus_read(hm2, addr, val, 4);
}

int hm2_write_reg(hostmot2_t *hm2, uint32_t addr, uint32_t val)
{
    if (addr >= HM2_ADDR_SPACE || (addr & 3))
        return -EINVAL;
    return hm2->llio->write(hm2->llio, addr, &val, 4);
}

static void word_bytes(uint32_t w, char *out)
{
    for (int i = 0; i < 4; i++)
        out[i] = (char)((w >> (8 * i)) & 0xFF);
}

static void printable(char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (s[i] < 0x20 || s[i] > 0x7E)
            s[i] = '?';
}

static void read_fail_reason(hostmot2_t *hm2, uint32_t addr, size_t size, int r)
{
    if (addr >= HM2_ADDR_SPACE || size > HM2_ADDR_SPACE - addr)
        hm2_msg(hm2, HM2_ERR, "    (address 0x%X + %zu bytes is outside the 64 KiB register space)",
                addr, size);
    else
        hm2_msg(hm2, HM2_ERR, "    (llio read of %zu bytes at 0x%04X failed: %s)", size, addr,
                strerror(-r));
}

void hm2_print_idrom(const hostmot2_t *hm2)
{
    const struct hm2_idrom *id = &hm2->idrom;
    char name[9];
    memcpy(name, id->board_name, 9);
    printable(name, 8);
    hm2_msg(hm2, HM2_PRINT, "IDRom:");
    hm2_msg(hm2, HM2_PRINT, "    IDRom Type: 0x%08X", id->idrom_type);
    hm2_msg(hm2, HM2_PRINT, "    Offset to Modules: 0x%08X", id->offset_to_modules);
    hm2_msg(hm2, HM2_PRINT, "    Offset to Pin Description: 0x%08X", id->offset_to_pin_desc);
    hm2_msg(hm2, HM2_PRINT, "    Board Name: %s", name);
    hm2_msg(hm2, HM2_PRINT, "    FPGA Size: %u", id->fpga_size);
    hm2_msg(hm2, HM2_PRINT, "    FPGA Pins: %u", id->fpga_pins);
    hm2_msg(hm2, HM2_PRINT, "    Port Width: %u", id->port_width);
    hm2_msg(hm2, HM2_PRINT, "    IO Ports: %u", id->io_ports);
    hm2_msg(hm2, HM2_PRINT, "    IO Width: %u", id->io_width);
    hm2_msg(hm2, HM2_PRINT, "    Clock Low: %d Hz (%d KHz, %d MHz)", (int)id->clock_low,
            (int)(id->clock_low / 1000), (int)(id->clock_low / 1000000));
    hm2_msg(hm2, HM2_PRINT, "    Clock High: %d Hz (%d KHz, %d MHz)", (int)id->clock_high,
            (int)(id->clock_high / 1000), (int)(id->clock_high / 1000000));
    hm2_msg(hm2, HM2_PRINT, "    Instance Stride 0: 0x%08X", id->instance_stride_0);
    hm2_msg(hm2, HM2_PRINT, "    Instance Stride 1: 0x%08X", id->instance_stride_1);
    hm2_msg(hm2, HM2_PRINT, "    Register Stride 0: 0x%08X", id->register_stride_0);
    hm2_msg(hm2, HM2_PRINT, "    Register Stride 1: 0x%08X", id->register_stride_1);
}

static int check_idrom_header(hostmot2_t *hm2)
{
    const struct hm2_idrom *id = &hm2->idrom;
    const hm2_llio_t *llio = hm2->llio;

    if (id->port_width != (uint32_t)llio->pins_per_connector) {
        hm2_msg(hm2, HM2_ERR,
                "invalid IDROM PortWidth %d, this board has %d pins per connector, aborting load",
                (int)id->port_width, llio->pins_per_connector);
        hm2_print_idrom(hm2);
        return -EINVAL;
    }
    if ((uint64_t)id->io_width != (uint64_t)id->io_ports * id->port_width) {
        hm2_msg(hm2, HM2_ERR,
                "IDROM IOWidth is %d, but IDROM IOPorts is %d and IDROM PortWidth is %d "
                "(inconsistent firmware), aborting driver load",
                (int)id->io_width, (int)id->io_ports, (int)id->port_width);
        return -EINVAL;
    }
    if (id->io_ports != (uint32_t)llio->num_ioport_connectors) {
        hm2_msg(hm2, HM2_ERR,
                "IDROM IOPorts is %d but llio num_ioport_connectors is %d, driver and firmware "
                "are inconsistent, aborting driver load",
                (int)id->io_ports, llio->num_ioport_connectors);
        return -EINVAL;
    }
    if (id->io_width > HM2_MAX_IO_WIDTH) {
        hm2_msg(hm2, HM2_ERR, "IDROM IOWidth is %d but max is %d, aborting driver load",
                (int)id->io_width, HM2_MAX_IO_WIDTH);
        return -EINVAL;
    }
    if (id->clock_low < HM2_MIN_CLOCK) {
        hm2_msg(hm2, HM2_ERR, "IDROM ClockLow is %d, that's too low, aborting driver load",
                (int)id->clock_low);
        return -EINVAL;
    }
    if (id->clock_high < HM2_MIN_CLOCK) {
        hm2_msg(hm2, HM2_ERR, "IDROM ClockHigh is %d, that's too low, aborting driver load",
                (int)id->clock_high);
        return -EINVAL;
    }
    return 0;
}

int hm2_read_idrom(hostmot2_t *hm2)
{
    uint32_t w, hdr[HM2_IDROM_HEADER_SIZE / 4], name[2];
    int r;

    if ((r = bus_read(hm2, HM2_ADDR_IOCOOKIE, &w, 4))) {
        hm2_msg(hm2, HM2_ERR, "error reading hm2 cookie");
        return r;
    }
    if (w != HM2_IOCOOKIE) {
        hm2_msg(hm2, HM2_ERR, "invalid cookie, got 0x%08X, expected 0x%08X", w, HM2_IOCOOKIE);
        hm2_msg(hm2, HM2_ERR, "FPGA failed to initialize, or unexpected firmware?");
        return -EINVAL;
    }
    if ((r = bus_read(hm2, HM2_ADDR_CONFIGNAME, name, sizeof(name)))) {
        hm2_msg(hm2, HM2_ERR, "error reading HM2 Config Name");
        return r;
    }
    char cname[HM2_CONFIGNAME_LEN + 1];
    word_bytes(name[0], cname);
    word_bytes(name[1], cname + 4);
    cname[HM2_CONFIGNAME_LEN] = '\0';
    if (memcmp(cname, HM2_CONFIGNAME, HM2_CONFIGNAME_LEN) != 0) {
        printable(cname, HM2_CONFIGNAME_LEN);
        hm2_msg(hm2, HM2_ERR, "invalid config name, got '%s', expected '%s'", cname,
                HM2_CONFIGNAME);
        return -EINVAL;
    }
    if ((r = bus_read(hm2, HM2_ADDR_IDROM_OFFSET, &w, 4))) {
        hm2_msg(hm2, HM2_ERR, "error reading IDROM Offset");
        return r;
    }
    hm2->idrom_offset = w & 0xFFFF;
    if ((r = bus_read(hm2, hm2->idrom_offset, &w, 4))) {
        hm2_msg(hm2, HM2_ERR, "error reading IDROM type");
        read_fail_reason(hm2, hm2->idrom_offset, 4, r);
        return r;
    }
    if (w != 2 && w != 3) {
        hm2_msg(hm2, HM2_ERR, "invalid IDROM type %d, expected 2 or 3, aborting load", (int)w);
        return -EINVAL;
    }
    if ((r = bus_read(hm2, hm2->idrom_offset, hdr, sizeof(hdr)))) {
        hm2_msg(hm2, HM2_ERR, "error reading IDROM");
        read_fail_reason(hm2, hm2->idrom_offset, sizeof(hdr), r);
        return r;
    }
    struct hm2_idrom *id = &hm2->idrom;
    id->idrom_type = hdr[0];
    id->offset_to_modules = hdr[1];
    id->offset_to_pin_desc = hdr[2];
    word_bytes(hdr[3], id->board_name);
    word_bytes(hdr[4], id->board_name + 4);
    id->board_name[8] = '\0';
    id->fpga_size = hdr[5];
    id->fpga_pins = hdr[6];
    id->io_ports = hdr[7];
    id->io_width = hdr[8];
    id->port_width = hdr[9];
    id->clock_low = hdr[10];
    id->clock_high = hdr[11];
    id->instance_stride_0 = hdr[12];
    id->instance_stride_1 = hdr[13];
    id->register_stride_0 = hdr[14];
    id->register_stride_1 = hdr[15];

    if ((r = check_idrom_header(hm2)))
        return r;
    if (hm2->debug.idrom)
        hm2_print_idrom(hm2);
    return 0;
}

static void print_pin_descriptor(const hostmot2_t *hm2, int i)
{
    const struct hm2_pin *p = &hm2->pin[i];
    const char *pn = hm2_get_general_function_name(p->primary_tag);
    hm2_msg(hm2, HM2_PRINT, "    pin %d:", i);
    hm2_msg(hm2, HM2_PRINT, "        Primary Tag: 0x%02X (%s)", p->primary_tag,
            pn ? pn : "unknown");
    if (p->sec_tag == 0)
        return;
    const char *sn = hm2_get_general_function_name(p->sec_tag);
    char buf[32];
    hm2_msg(hm2, HM2_PRINT, "        Secondary Tag: 0x%02X (%s)", p->sec_tag, sn ? sn : "unknown");
    hm2_msg(hm2, HM2_PRINT, "        Secondary Unit: 0x%02X", p->sec_unit);
    hm2_msg(hm2, HM2_PRINT, "        Secondary Pin: 0x%02X (%s, %s)", p->sec_pin,
            hm2_get_pin_secondary_name(p, buf, sizeof(buf)),
            (p->sec_pin & 0x80) ? "Output" : "Input");
}

int hm2_read_pin_descriptors(hostmot2_t *hm2)
{
    const struct hm2_idrom *id = &hm2->idrom;
    int n = (int)id->io_width;
    uint64_t base = (uint64_t)hm2->idrom_offset + id->offset_to_pin_desc;

    if (n == 0)
        return 0;
    hm2->pin = calloc((size_t)n, sizeof(*hm2->pin));
    if (!hm2->pin) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating %d pin descriptors", n);
        return -ENOMEM;
    }
    hm2->num_pins = n;
    if (hm2->debug.pin_descriptors)
        hm2_msg(hm2, HM2_PRINT, "%d HM2 Pin Descriptors:", n);
    for (int i = 0; i < n; i++) {
        uint64_t addr = base + 4u * (uint64_t)i;
        uint32_t w;
        int r = addr >= HM2_ADDR_SPACE ? -EINVAL : bus_read(hm2, (uint32_t)addr, &w, 4);
        if (r) {
            hm2_msg(hm2, HM2_ERR, "error reading Pin Descriptor %d (at 0x%04llx)", i,
                    (unsigned long long)addr);
            read_fail_reason(hm2, addr > UINT32_MAX ? UINT32_MAX : (uint32_t)addr, 4, r);
            return r ? r : -EINVAL;
        }
        struct hm2_pin *p = &hm2->pin[i];
        p->sec_pin = w & 0xFF;
        p->sec_tag = (w >> 8) & 0xFF;
        p->sec_unit = (w >> 16) & 0xFF;
        p->primary_tag = (w >> 24) & 0xFF;
        if (p->primary_tag == 0) {
            hm2_msg(hm2, HM2_ERR, "pin %d primary tag is 0 (end-of-list sentinel), expected %d pins!",
                    i, n);
            return -EINVAL;
        }
        if (p->primary_tag != HM2_GTAG_IOPORT) {
            const char *pn = hm2_get_general_function_name(p->primary_tag);
            hm2_msg(hm2, HM2_ERR, "pin %d primary tag is %d (%s), not IOPort!", i, p->primary_tag,
                    pn ? pn : "unknown");
            return -EINVAL;
        }
        /* port_width != 0 is guaranteed by the header checks (it equals the
         * llio's pins_per_connector, which hm2_llio_validate requires > 0). */
        p->port_num = i / (int)id->port_width;
        p->port_pin = i % (int)id->port_width;
        if (p->port_num >= (int)id->io_ports) {
            hm2_msg(hm2, HM2_ERR, "hm2_read_pin_descriptors: Calculated port number (%d) is invalid",
                    p->port_num);
            return -EINVAL;
        }
        p->gtag = HM2_GTAG_IOPORT;
        p->direction = HM2_PIN_DIR_INPUT;
        if (hm2->debug.pin_descriptors)
            print_pin_descriptor(hm2, i);
    }
    return 0;
}

static void print_md(const hostmot2_t *hm2, int i)
{
    const struct hm2_md *md = &hm2->md[i];
    char unk[32];
    const char *name = hm2_gtag_name(md->gtag, unk, sizeof(unk));
    hm2_msg(hm2, HM2_PRINT, "Module Descriptor %d at 0x%04X:", i, md->addr);
    hm2_msg(hm2, HM2_PRINT, "    General Function Tag: %d (%s)", md->gtag, name);
    hm2_msg(hm2, HM2_PRINT, "    Version: %d", md->version);
    hm2_msg(hm2, HM2_PRINT, "    Clock Tag: %d (%d.%03d MHz)", md->clock_tag,
            (int)(md->clock_freq / 1000000), (int)((md->clock_freq / 1000) % 1000));
    hm2_msg(hm2, HM2_PRINT, "    Instances: %d", md->instances);
    hm2_msg(hm2, HM2_PRINT, "    Base Address: 0x%04X", md->base_address);
    hm2_msg(hm2, HM2_PRINT, "    -- Num Registers: %d", md->num_registers);
    hm2_msg(hm2, HM2_PRINT, "    Register Stride: 0x%08X", md->register_stride);
    hm2_msg(hm2, HM2_PRINT, "    -- Instance Stride: 0x%08X", md->instance_stride);
    hm2_msg(hm2, HM2_PRINT, "    -- Multiple Registers: 0x%08X", md->multiple_registers);
}

int hm2_read_module_descriptors(hostmot2_t *hm2)
{
    const struct hm2_idrom *id = &hm2->idrom;
    uint64_t base = (uint64_t)hm2->idrom_offset + id->offset_to_modules;

    hm2->num_mds = 0;
    for (int i = 0; i < HM2_MAX_MODULE_DESCRIPTORS; i++) {
        uint64_t addr = base + (uint64_t)i * HM2_MD_SIZE;
        uint32_t w[3];
        int r = addr >= HM2_ADDR_SPACE ? -EINVAL
                                       : bus_read(hm2, (uint32_t)addr, w, sizeof(w));
        if (r) {
            hm2_msg(hm2, HM2_ERR, "error reading Module Descriptor %d (at 0x%04llx)", i,
                    (unsigned long long)addr);
            read_fail_reason(hm2, addr > UINT32_MAX ? UINT32_MAX : (uint32_t)addr, sizeof(w), r);
            return r;
        }
        struct hm2_md *md = &hm2->md[i];
        memset(md, 0, sizeof(*md));
        md->gtag = w[0] & 0xFF;
        if (md->gtag == 0)
            return 0; /* end of table */
        md->version = (w[0] >> 8) & 0xFF;
        md->clock_tag = (w[0] >> 16) & 0xFF;
        md->instances = (w[0] >> 24) & 0xFF;
        md->base_address = w[1] & 0xFFFF;
        md->num_registers = (w[1] >> 16) & 0xFF;
        md->strides = (w[1] >> 24) & 0xFF;
        md->multiple_registers = w[2];
        md->addr = (uint16_t)addr;

        if (md->clock_tag == 1) {
            md->clock_freq = id->clock_low;
        } else if (md->clock_tag == 2) {
            md->clock_freq = id->clock_high;
        } else {
            hm2_msg(hm2, HM2_ERR, "Module Descriptor %d (at 0x%04x) has invalid ClockTag %d", i,
                    md->addr, md->clock_tag);
            return -EINVAL;
        }
        int rs = md->strides & 0x0F, is = md->strides >> 4;
        if (rs == 0) {
            md->register_stride = id->register_stride_0;
        } else if (rs == 1) {
            md->register_stride = id->register_stride_1;
        } else {
            hm2_msg(hm2, HM2_ERR, "Module Descriptor %d (at 0x%04x) has invalid RegisterStride %d",
                    i, md->addr, rs);
            return -EINVAL;
        }
        if (is == 0) {
            md->instance_stride = id->instance_stride_0;
        } else if (is == 1) {
            md->instance_stride = id->instance_stride_1;
        } else {
            hm2_msg(hm2, HM2_ERR, "Module Descriptor %d (at 0x%04x) has invalid InstanceStride %d",
                    i, md->addr, is);
            return -EINVAL;
        }
        hm2->num_mds = i + 1;
        if (hm2->debug.module_descriptors)
            print_md(hm2, i);
    }
    hm2_msg(hm2, HM2_ERR,
            "Module Descriptor table at 0x%04x has no terminator (GTag 0) within %d entries, "
            "inconsistent firmware, aborting driver load",
            (unsigned)base, HM2_MAX_MODULE_DESCRIPTORS);
    return -EINVAL;
}
