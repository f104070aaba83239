/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * board.c - hm2flash's board sources and progress display (hm2flash.h).
 *
 *   sim:SOCKET   a virtual board (bin/vboard): the hm2_sim backend's llio.
 *                The board runs in lockstep with a clock of this tool's own:
 *                every register access takes 1 us of board time and a wait
 *                for the flash advances the clock instead of sleeping, so
 *                the board's flash timing is met without real waiting and
 *                the times printed are board times.
 *   pci:[ADDR]   a Mesa PCI board (5i25, 6i25) through sysfs (source_pci.c):
 *                real time, waits sleep.
 *   IP           an Ethernet board (7i92, 7i96S) at that IPv4 address (also
 *                eth:IP; default 192.168.1.121): hm2 and the flash over
 *                LBP16 (source_eth.c), real time.
 */
#define _GNU_SOURCE
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

#include "hm2_sim_llio.h"
#include "hm2flash.h"
#include "source_eth.h"
#include "source_pci.h"

#define SIM_ACCESS_NS 1000u

/* The simulated clock of a sim: board (hm2_sim_now_fn has no context; one
 * tool run drives one board). */
static int64_t sim_clock_ns = 1;

static int64_t sim_now(void)
{
    sim_clock_ns += SIM_ACCESS_NS;
    return sim_clock_ns;
}

static void sim_delay(void *ctx, uint64_t ns)
{
    (void)ctx;
    sim_clock_ns += (int64_t)ns;
}

static uint64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

static void real_delay(void *ctx, uint64_t ns)
{
    (void)ctx;
    struct timespec ts = {(time_t)(ns / 1000000000ull), (long)(ns % 1000000000ull)};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR)
        ;
}

uint64_t hm2flash_now_ns(struct hm2flash_board *bd)
{
    return bd->is_pci || bd->is_eth ? mono_ns() : (uint64_t)sim_clock_ns;
}

static void sim_log(void *ctx, int level, const char *line)
{
    struct hm2flash_board *bd = ctx;
    if (level == HM2_ERR && !bd->why[0])
        snprintf(bd->why, sizeof(bd->why), "%s", line);
}

static void progress_cb(void *ctx, const char *phase, uint32_t done, uint32_t total);

static int open_sim(struct hm2flash_board *bd, const char *path)
{
    struct hm2_sim_board *sb = calloc(1, sizeof(*sb));
    if (!sb) {
        snprintf(bd->why, sizeof(bd->why), "out of memory");
        return -ENOMEM;
    }
    int r = hm2_sim_setup(sb, path, bd->board->name, 0, sim_now, sim_log, bd);
    if (r) {
        free(sb);
        return r;
    }
    if (sb->hello.state != VB_STATE_CONFIGURED) {
        snprintf(bd->why, sizeof(bd->why),
                 "the %s at %s is not configured (blank FPGA: no firmware came up from its "
                 "flash), so its flash cannot be reached through the hm2 firmware",
                 bd->display_name, path);
        hm2_sim_teardown(sb);
        free(sb);
        return -ENODEV;
    }
    snprintf(bd->firmware, sizeof(bd->firmware), "%s", sb->hello.firmware);
    snprintf(bd->description, sizeof(bd->description), "%s (virtual board at %s)",
             bd->display_name, path);
    bd->handle = sb;
    bd->io.llio = &sb->llio;
    return 0;
}

static int open_eth(struct hm2flash_board *bd, const char *addr)
{
    const char *ip = !addr ? "192.168.1.121" : strncmp(addr, "eth:", 4) == 0 ? addr + 4 : addr;
    if (strncmp(ip, "sim:", 4) == 0 || strncmp(ip, "pci:", 4) == 0) {
        snprintf(bd->why, sizeof(bd->why),
                 "--addr %s: the %s is an Ethernet board: give its IP address (e.g. --addr "
                 "192.168.1.121; a virtual one: vboard --udp IP)", addr, bd->display_name);
        return -ENODEV;
    }
    bd->is_eth = 1;
    bd->io.delay_ns = real_delay;
    snprintf(bd->source, sizeof(bd->source), "%s", ip);
    int r = hm2flash_open_eth(ip, &bd->io, &bd->handle, bd->why, sizeof(bd->why));
    if (r)
        return r;
    const char *got = hm2flash_eth_board(bd->handle);
    if (strcasecmp(got, bd->board->name) != 0) {
        snprintf(bd->why, sizeof(bd->why), "No %s board found (the board at %s is a %s)",
                 bd->display_name, ip, got);
        hm2flash_close_eth(bd->handle);
        bd->handle = NULL;
        return -ENODEV;
    }
    snprintf(bd->description, sizeof(bd->description), "ETH device %s at ip=%s",
             bd->display_name, ip);
    snprintf(bd->firmware, sizeof(bd->firmware), "(see --readhmid)");
    return 0;
}

int hm2flash_open(struct hm2flash_board *bd, const char *device, const char *addr)
{
    memset(bd, 0, sizeof(*bd));
    bd->tty = isatty(STDOUT_FILENO);
    bd->board = hm2_board_lookup(device);
    if (!bd->board) {
        snprintf(bd->why, sizeof(bd->why), "No %s board found (unknown board name)", device);
        return -ENODEV;
    }
    if (bd->board->programmable) {
        snprintf(bd->why, sizeof(bd->why),
                 "the %s has no configuration flash: its FPGA is loaded over the bus at "
                 "every start (use firmware= of its driver)", bd->board->name);
        return -ENOTSUP;
    }
    size_t i = 0;
    for (; bd->board->name[i] && i + 1 < sizeof(bd->display_name); i++)
        bd->display_name[i] = (char)toupper((unsigned char)bd->board->name[i]);
    bd->display_name[i] = 0;
    bd->io.delay_ns = sim_delay;
    bd->io.delay_ctx = bd;
    bd->io.progress = progress_cb;
    bd->io.progress_ctx = bd;
    /* Mesa's layouts: Spartan-6 boot block + fallback + user image; the
     * Efinix T20 (7i96S): fallback at 0, user image at 2 MiB */
    int efinix = strcmp(bd->board->fpga_part, "T20F256") == 0;
    bd->user_addr = efinix ? 0x200000u : HM2_FLASH_USER_ADDR;
    bd->fallback_addr = efinix ? 0u : HM2_FLASH_FALLBACK_ADDR;
    bd->boot_block = !efinix;
    if (bd->board->ethernet)
        return open_eth(bd, addr);
    if (!addr || strncmp(addr, "pci:", 4) == 0) {
        bd->is_pci = 1;
        bd->io.delay_ns = real_delay;
        const char *a = addr ? addr + 4 : "";
        int r = hm2flash_open_pci(a, bd->board->name, &bd->io.llio, &bd->handle, bd->why,
                                  sizeof(bd->why));
        if (r)
            return r;
        snprintf(bd->description, sizeof(bd->description), "%s (PCI %s)", bd->display_name,
                 a[0] ? a : "first found");
        snprintf(bd->firmware, sizeof(bd->firmware), "(see hm2pinout pci:%s)", a);
        return 0;
    }
    if (strncmp(addr, "sim:", 4) != 0) {
        snprintf(bd->why, sizeof(bd->why),
                 "--addr %s: want sim:SOCKET (a virtual board) or pci:[ADDR]; no %s board found",
                 addr, bd->display_name);
        return -ENODEV;
    }
    snprintf(bd->source, sizeof(bd->source), "%s", addr);
    return open_sim(bd, addr + 4);
}

void hm2flash_close(struct hm2flash_board *bd)
{
    if (bd->is_eth) {
        hm2flash_close_eth(bd->handle);
        bd->handle = NULL;
        return;
    }
    if (bd->is_pci) {
        hm2flash_close_pci(bd->handle);
        bd->handle = NULL;
        return;
    }
    struct hm2_sim_board *sb = bd->handle;
    if (sb) {
        hm2_sim_teardown(sb);
        free(sb);
    }
    bd->handle = NULL;
}

/* After a reload the Ethernet board answers again once its FPGA is up:
 * connect again (up to 5 s) and read the hm2 cookie. */
static int reopen_eth(struct hm2flash_board *bd)
{
    struct hm2_flash_io keep = bd->io;
    hm2flash_close(bd);
    int r = -ETIMEDOUT;
    for (int i = 0; i < 50 && r; i++) {
        real_delay(bd, 100000000ull);
        bd->why[0] = 0;
        r = hm2flash_open_eth(bd->source, &bd->io, &bd->handle, bd->why, sizeof(bd->why));
    }
    if (r)
        return r;
    uint32_t cookie = 0;
    r = bd->io.llio->read(bd->io.llio, 0x100, &cookie, sizeof(cookie));
    if (!r && cookie != 0x55AACAFEu)
        r = -ENODEV;
    if (r) {
        snprintf(bd->why, sizeof(bd->why), "no hm2 firmware answers at %s (cookie 0x%08X)",
                 bd->source, cookie);
        return r;
    }
    snprintf(bd->firmware, sizeof(bd->firmware), "HostMot2 (cookie 0x%08X)", cookie);
    keep.llio = bd->io.llio;
    keep.ops_ctx = bd->io.ops_ctx;
    bd->io = keep;
    return 0;
}

int hm2flash_reopen(struct hm2flash_board *bd)
{
    if (bd->is_eth)
        return reopen_eth(bd);
    if (bd->is_pci) {
        /* the window stays mapped; the FPGA takes a moment to reconfigure
         * (mesaflash waits 2 s) */
        bd->io.delay_ns(bd, 2000000000ull);
        return 0;
    }
    struct hm2_flash_io keep = bd->io;
    hm2flash_close(bd);
    bd->why[0] = 0;
    int r = open_sim(bd, bd->source + 4);
    uint8_t sig = keep.signature;
    uint32_t size = keep.size;
    keep.llio = bd->io.llio;
    bd->io = keep;
    bd->io.signature = sig;
    bd->io.size = size;
    return r;
}

/* ---- progress ---- */

static void print_line(struct hm2flash_board *bd, int final)
{
    uint32_t done = bd->last_done, total = bd->last_total ? bd->last_total : 1;
    int pct = (int)((uint64_t)done * 100 / total);
    double secs = (double)(hm2flash_now_ns(bd) - bd->phase_start_ns) / 1e9;
    char bar[41];
    int fill = pct * 40 / 100;
    for (int i = 0; i < 40; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[40] = 0;
    if (final) {
        printf("%s  %-11s [%s] %3d%% %u bytes in %.2f s\n", bd->tty ? "\r" : "", bd->phase, bar,
               pct, done, secs);
    } else {
        double left = done ? secs * (double)(total - done) / (double)done : 0.0;
        printf("\r  %-11s [%s] %3d%% %.1f s, about %.1f s left ", bd->phase, bar, pct, secs,
               left);
    }
    fflush(stdout);
}

static void progress_cb(void *ctx, const char *phase, uint32_t done, uint32_t total)
{
    struct hm2flash_board *bd = ctx;
    if (bd->phase && strcmp(bd->phase, phase) != 0) {
        print_line(bd, 1);
        /* mesaflash's header of the write's second phase (the caller
         * prints the first one before it starts) */
        if (strcmp(phase, "Programming") == 0)
            printf("%s FLASH memory sectors starting from 0x%X...\n", phase, bd->area_addr);
        bd->phase_start_ns = hm2flash_now_ns(bd);
    }
    bd->phase = phase;
    bd->last_done = done;
    bd->last_total = total;
    int pct = (int)((uint64_t)done * 100 / (total ? total : 1));
    if (bd->tty && pct != bd->last_pct)
        print_line(bd, 0);
    bd->last_pct = pct;
}

void hm2flash_progress_begin(struct hm2flash_board *bd)
{
    bd->phase = NULL;
    bd->last_pct = -1;
    bd->phase_start_ns = hm2flash_now_ns(bd);
}

void hm2flash_progress_end(struct hm2flash_board *bd)
{
    if (bd->phase)
        print_line(bd, 1);
    bd->phase = NULL;
}
