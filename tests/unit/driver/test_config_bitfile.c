/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Config string parsing, .BIT parsing (good and bad files), firmware
 * search and the firmware loader through a programmable fake llio.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../check.h"
#include "hm2/bitfile.h"
#include "testlib.h"

static void test_config(void)
{
    struct hm2_config c;
    char err[200];
    CHECK_EQ_INT(hm2_config_parse(NULL, &c, err, sizeof(err)), 0);
    CHECK_EQ_INT(c.num_encoders, -1);
    CHECK_EQ_INT(c.stepgen_width, -1);
    CHECK_EQ_INT(c.enable_raw, 0);
    CHECK_EQ_INT(hm2_config_parse("  firmware=hm2/5i20/SVST8_4.BIT\tnum_encoders=3 "
                                  "num_pwmgens=0x2 num_stepgens=-1 enable_raw num_leds=0 "
                                  "sserial_port_0=0x21xx stepgen_width=4 ssi_chan_0=abc",
                                  &c, err, sizeof(err)),
                 0);
    CHECK_EQ_STR(c.firmware, "hm2/5i20/SVST8_4.BIT");
    CHECK_EQ_INT(c.num_encoders, 3);
    CHECK_EQ_INT(c.num_pwmgens, 2);
    CHECK_EQ_INT(c.num_stepgens, -1);
    CHECK_EQ_INT(c.num_leds, 0);
    CHECK_EQ_INT(c.stepgen_width, 4);
    CHECK_EQ_INT(c.enable_raw, 1);
    CHECK_EQ_STR(c.sserial_modes[0], "0x21xx");
    CHECK_EQ_INT(hm2_config_parse("\"num_encoders=2 num_pwmgens=1\"", &c, err, sizeof(err)), 0);
    CHECK_EQ_INT(c.num_encoders, 2);
    CHECK_EQ_INT(c.num_pwmgens, 1);
    CHECK_EQ_INT(hm2_config_parse("\"num_encoders=2", &c, err, sizeof(err)), -EINVAL);
    static const struct {
        const char *cfg, *msg;
    } bad[] = {
        {"bogus", "invalid token in config string: \"bogus\""},
        {"num_encoders=", "invalid token in config string: \"num_encoders=\" (not a number)"},
        {"num_encoders=3x", "invalid token in config string: \"num_encoders=3x\" (not a number)"},
        {"num_encoders=-2", "invalid token in config string: \"num_encoders=-2\" (must be -1 (all) "
                            "or >= 0)"},
        {"num_stepgens=99999999999", "invalid token in config string: \"num_stepgens=99999999999\" "
                                     "(not a number)"},
        {"stepgen_width=0", "invalid token in config string: \"stepgen_width=0\" (stepgen_width "
                            "must be >= 1)"},
        {"firmware=hm2/5i20/a_very_long_firmware_name.BIT",
         "requested firmware name 'hm2/5i20/a_very_long_firmware_name.BIT' is too long (max "
         "length is 30)"},
        {"firmware=", "invalid token in config string: \"firmware=\" (empty firmware name)"},
        {"sserial_port_4=000", "invalid token in config string: \"sserial_port_4=000\" (port "
                               "must be 0..3)"},
        {"sserial_port_1=0z", "invalid token in config string: \"sserial_port_1=0z\" (channel "
                              "mode must be 0..9 or x)"},
        {"sserial_port_1=000000000", "invalid token in config string: \"sserial_port_1=000000000\" "
                                     "(1 to 8 channel modes expected)"},
        {"enable_raw=1", "invalid token in config string: \"enable_raw=1\""},
        {"ssi_chan_0", "invalid token in config string: \"ssi_chan_0\""},
    };
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        CHECK_EQ_INT(hm2_config_parse(bad[i].cfg, &c, err, sizeof(err)), -EINVAL);
        CHECK_EQ_STR(err, bad[i].msg);
    }
    /* a token longer than the token buffer */
    char big[600];
    memset(big, 'a', sizeof(big) - 1);
    big[sizeof(big) - 1] = '\0';
    CHECK_EQ_INT(hm2_config_parse(big, &c, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "token too long") != NULL);
}

/* ---- .BIT files ---- */
static size_t put_small(uint8_t *p, char tag, const char *text)
{
    size_t n = strlen(text) + 1;
    p[0] = (uint8_t)tag;
    p[1] = (uint8_t)(n >> 8);
    p[2] = (uint8_t)n;
    memcpy(p + 3, text, n);
    return 3 + n;
}

static size_t make_bit(uint8_t *buf, const char *part, const uint8_t *data, uint32_t n)
{
    static const uint8_t hdr[13] = {0, 9, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F, 0xF0, 0, 0, 1};
    size_t pos = 0;
    memcpy(buf, hdr, 13);
    pos = 13;
    pos += put_small(buf + pos, 'a', "SVST8_4.ncd;UserID=0xFFFFFFFF");
    if (part)
        pos += put_small(buf + pos, 'b', part);
    pos += put_small(buf + pos, 'c', "2009/03/22");
    pos += put_small(buf + pos, 'd', "12:34:56");
    buf[pos++] = 'e';
    buf[pos++] = (uint8_t)(n >> 24);
    buf[pos++] = (uint8_t)(n >> 16);
    buf[pos++] = (uint8_t)(n >> 8);
    buf[pos++] = (uint8_t)n;
    memcpy(buf + pos, data, n);
    return pos + n;
}

static void expect_bad(const uint8_t *buf, size_t len, const char *msg)
{
    struct hm2_bitfile bf;
    char err[100];
    CHECK_EQ_INT(hm2_bitfile_parse(buf, len, &bf, err, sizeof(err)), -EINVAL);
    CHECK_EQ_STR(err, msg);
}

static void test_bitfile(void)
{
    uint8_t data[300], buf[1024];
    for (int i = 0; i < 300; i++)
        data[i] = (uint8_t)(i * 7);
    size_t len = make_bit(buf, "2s200pq208", data, 300);
    struct hm2_bitfile bf;
    char err[100];
    CHECK_EQ_INT(hm2_bitfile_parse(buf, len, &bf, err, sizeof(err)), 0);
    CHECK_EQ_STR(bf.design, "SVST8_4.ncd;UserID=0xFFFFFFFF");
    CHECK_EQ_STR(bf.part, "2s200pq208");
    CHECK_EQ_STR(bf.date, "2009/03/22");
    CHECK_EQ_STR(bf.time, "12:34:56");
    CHECK_EQ_INT(bf.size, 300);
    CHECK(memcmp(bf.data, data, 300) == 0);
    /* bad files */
    expect_bad(buf, 10, "bitfile is too short");
    uint8_t b2[1024];
    memcpy(b2, buf, len);
    b2[3] = 0;
    expect_bad(b2, len, "bitfile has invalid header");
    expect_bad(buf, len - 1, "bitfile chunk extends past end of firmware");
    for (size_t cut = 14; cut < len; cut += 13) {
        struct hm2_bitfile x;
        CHECK(hm2_bitfile_parse(buf, cut, &x, err, sizeof(err)) == -EINVAL);
    }
    memcpy(b2, buf, len);
    b2[13 + 3 + 29] = 'X'; /* design name loses its NUL */
    expect_bad(b2, len, "bitfile small chunk is not NULL terminated");
    memcpy(b2, buf, len);
    b2[13] = 'z';
    expect_bad(b2, len, "bitfile has unknown chunk 'z'");
    memcpy(b2, buf, len);
    b2[13] = 0x01;
    expect_bad(b2, len, "bitfile has unknown chunk '\\x01'");
    len = make_bit(buf, NULL, data, 10);
    expect_bad(buf, len, "bitfile lacks Part Name (chunk 'b')!");
    len = make_bit(buf, "x", data, 10);
    expect_bad(buf, len - 15, "bitfile lacks FPGA Config (part 'e')!");
    /* bit reversal */
    CHECK_EQ_INT(hm2_bitfile_reverse(0xAA), 0x55);
    CHECK_EQ_INT(hm2_bitfile_reverse(0x01), 0x80);
    CHECK_EQ_INT(hm2_bitfile_reverse(0x12), 0x48);
    for (int v = 0; v < 256; v++) {
        int r = 0;
        for (int b = 0; b < 8; b++)
            r |= ((v >> b) & 1) << (7 - b);
        CHECK_EQ_INT(hm2_bitfile_reverse((uint8_t)v), r);
    }
}

/* ---- firmware loading through a programmable fake llio ---- */
static struct hm2_image_llio im;
static struct tlog lg;
static int resets, programs, fail_reset, fail_program;
static uint32_t programmed_size;
static uint8_t programmed_first;

static int fake_reset(hm2_llio_t *l)
{
    (void)l;
    resets++;
    return fail_reset ? -EIO : 0;
}

static int fake_program(hm2_llio_t *l, const struct hm2_bitfile *bf)
{
    (void)l;
    programs++;
    programmed_size = bf->size;
    programmed_first = bf->data[0];
    return fail_program ? -EIO : 0;
}

static char dir[64];

static void write_file(const char *rel, const uint8_t *buf, size_t len)
{
    char path[256], sub[256];
    snprintf(sub, sizeof(sub), "%s/hm2", dir);
    mkdir(sub, 0755);
    snprintf(sub, sizeof(sub), "%s/hm2/5i20", dir);
    mkdir(sub, 0755);
    snprintf(path, sizeof(path), "%s/%s", dir, rel);
    FILE *f = fopen(path, "wb");
    fwrite(buf, 1, len, f);
    fclose(f);
}

static int load(const char *config)
{
    tlog_clear(&lg);
    resets = programs = 0;
    t_setup_5i20(&im);
    im.llio.reset = fake_reset;
    im.llio.program_fpga = fake_program;
    struct hm2_options opt = {{0, 0, 0, 0}, dir};
    int err;
    hostmot2_t *hm2 = hm2_probe(&im.llio, config, &opt, tlog_sink, &lg, &err);
    hm2_free(hm2);
    return err;
}

static void test_firmware_loader(void)
{
    snprintf(dir, sizeof(dir), "/tmp/hm2fw.XXXXXX");
    CHECK(mkdtemp(dir) != NULL);
    uint8_t data[64], buf[512];
    memset(data, 0x5A, sizeof(data));
    data[0] = 0xAA;
    size_t len = make_bit(buf, "2s200pq208", data, sizeof(data));
    write_file("hm2/5i20/GOOD.BIT", buf, len);
    write_file("hm2/5i20/TRUNC.BIT", buf, len - 20);
    size_t l2 = make_bit(buf, "3s400tq144", data, sizeof(data));
    write_file("hm2/5i20/7I43.BIT", buf, l2);

    CHECK_EQ_INT(load("firmware=hm2/5i20/GOOD.BIT"), 0);
    CHECK_EQ_INT(resets, 1);
    CHECK_EQ_INT(programs, 1);
    CHECK_EQ_INT(programmed_size, 64);
    CHECK_EQ_INT(programmed_first, 0xAA); /* unmodified: the backend reverses */
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: firmware hm2/5i20/GOOD.BIT:", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0:     SVST8_4.ncd;UserID=0xFFFFFFFF 2009/03/22 12:34:56",
                    0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0:     Part Name: 2s200pq208", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0:     FPGA Config: 64 bytes", 0) >= 0);

    CHECK_EQ_INT(load("firmware=hm2/5i20/NONE.BIT"), -ENOENT);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: firmware hm2/5i20/NONE.BIT not found", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: install the package containing the firmware.", 0) >= 0);
    CHECK_EQ_INT(programs, 0);

    CHECK(load("firmware=hm2/5i20/TRUNC.BIT") < 0);
    CHECK(tlog_find(&lg, "hm2: bitfile chunk extends past end of firmware", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: firmware hm2/5i20/TRUNC.BIT fails verification, "
                         "aborting hm2_register",
                    0) >= 0);
    CHECK_EQ_INT(resets, 0); /* board stays as it was */

    CHECK(load("firmware=hm2/5i20/7I43.BIT") < 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: board has FPGA '2s200pq208', but the firmware in "
                         "hm2/5i20/7I43.BIT is for FPGA '3s400tq144'",
                    0) >= 0);
    CHECK_EQ_INT(resets, 0);

    CHECK(load("firmware=../etc/passwd") < 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: firmware ../etc/passwd not found", 0) >= 0);

    fail_reset = 1;
    CHECK(load("firmware=hm2/5i20/GOOD.BIT") < 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: failed to reset fpga, aborting hm2_register", 0) >= 0);
    CHECK_EQ_INT(programs, 0);
    fail_reset = 0;
    fail_program = 1;
    CHECK(load("firmware=hm2/5i20/GOOD.BIT") < 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: failed to program fpga, aborting hm2_register", 0) >= 0);
    fail_program = 0;

    CHECK_EQ_INT(load(NULL), 0);
    CHECK(tlog_find(&lg, "hm2: no firmware specified in config modparam!  the board had better "
                         "have firmware configured already, or this won't work",
                    0) >= 0);
    CHECK_EQ_INT(programs, 0);

    /* search path: first hit wins, empty entries skipped */
    char path[512], out[512];
    snprintf(path, sizeof(path), "/nonexistent::%s:/tmp", dir);
    CHECK_EQ_INT(hm2_firmware_find(path, "hm2/5i20/GOOD.BIT", out, sizeof(out)), 0);
    char want[300];
    snprintf(want, sizeof(want), "%s/hm2/5i20/GOOD.BIT", dir);
    CHECK_EQ_STR(out, want);
    CHECK_EQ_INT(hm2_firmware_find(path, "/etc/passwd", out, sizeof(out)), -EINVAL);
    CHECK_EQ_INT(hm2_firmware_find(path, "hm2/../hm2/5i20/GOOD.BIT", out, sizeof(out)), -EINVAL);
    CHECK_EQ_INT(hm2_firmware_find(path, "hm2/5i20", out, sizeof(out)), -ENOENT); /* a dir */
    setenv("HM2_FIRMWARE_PATH", "/a:/b", 1);
    CHECK_EQ_STR(hm2_firmware_default_path(path, sizeof(path)), "/a:/b");
    unsetenv("HM2_FIRMWARE_PATH");
    setenv("HM_BUILD", "/x/build", 1);
    CHECK_EQ_STR(hm2_firmware_default_path(path, sizeof(path)),
                 "/x/build/lib/firmware:" HM_OWN_FIRMWARE ":/lib/firmware");
    /* without any environment: the build's own lib/firmware, then the system's */
    unsetenv("HM_BUILD");
    CHECK_EQ_STR(hm2_firmware_default_path(path, sizeof(path)), HM_OWN_FIRMWARE ":/lib/firmware");
    char tiny[8];
    CHECK(strlen(hm2_firmware_default_path(tiny, sizeof(tiny))) < sizeof(tiny));

    /* image llio file loading */
    char err[200];
    snprintf(path, sizeof(path), "%s/hm2/5i20/GOOD.BIT", dir);
    CHECK_EQ_INT(hm2_image_llio_load(&im, path, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "expected 65536 (register space), 1024 (IDROM) or an IDROM hex file") != NULL);
    CHECK(hm2_image_llio_load(&im, "/nonexistent/x", err, sizeof(err)) < 0);

    char cmd[300];
    snprintf(cmd, sizeof(cmd), "rm -rf %s", dir);
    CHECK_EQ_INT(system(cmd), 0);
}

int main(void)
{
    RUN(test_config);
    RUN(test_bitfile);
    RUN(test_firmware_loader);
    tlog_clear(&lg);
    return check_summary();
}
