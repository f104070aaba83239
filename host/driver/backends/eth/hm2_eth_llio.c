/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2_eth_llio.c - hm2 over LBP16/UDP (hm2_eth_llio.h). */
#define _GNU_SOURCE
#include "hm2_eth_llio.h"

#include <arpa/inet.h>
#include <ctype.h>
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define PROBE_TIMEOUT_US 200000
#define PROBE_TRIES 3
#define SYNC_TIMEOUT_US 100000
#define SYNC_TRIES 3
#define MIN_TIMEOUT_NS 100000L
#define LOAD_TIME_READ_TIMEOUT_NS 1000000000L /* a servo read outside a thread */
#define DEFAULT_PERIOD_NS 1000000L

/* Messages go to the board's log sink (hm2_log_printf, hostmot2/msg.c). */
#define logf_(board, ...) hm2_log_printf((board)->log, (board)->log_ctx, __VA_ARGS__)

static int64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

const struct hm2_board_info *hm2_eth_board_of(const char *lbp16_name)
{
    char n[17];
    size_t i = 0;
    for (; lbp16_name[i] && lbp16_name[i] != '-' && i < sizeof(n) - 1; i++)
        n[i] = (char)tolower((unsigned char)lbp16_name[i]);
    n[i] = '\0';
    const struct hm2_board_info *info = hm2_board_lookup(n);
    return info && info->ethernet ? info : NULL;
}

long hm2_eth_read_timeout_ns(int32_t param, long period_ns)
{
    if (period_ns <= 0)
        period_ns = DEFAULT_PERIOD_NS;
    long t;
    if (param <= 0)
        t = period_ns * 8 / 10;
    else if (param < 100)
        t = period_ns / 100 * param;
    else
        t = param;
    return t < MIN_TIMEOUT_NS ? MIN_TIMEOUT_NS : t;
}

/* A datagram that is the reply to the pending servo read (a synchronous
 * request made between read-request and read meets it first) is kept for
 * the read; true if it was. */
static bool keep_pending_reply(struct hm2_eth_board *b, const uint8_t *buf, ssize_t n)
{
    if (!b->req.pending || b->req.kept > 0 || n <= 0 ||
        lbp16_check_read_reply(buf, (size_t)n, b->rpkt.reply_len, b->read_seq, NULL))
        return false;
    memcpy(b->req.reply, buf, (size_t)n);
    b->req.kept = n;
    return true;
}

static void drain(struct hm2_eth_board *b)
{
    uint8_t junk[LBP16_MAX_PACKET + 1];
    for (;;) {
        ssize_t n = recv(b->fd, junk, sizeof(junk), MSG_DONTWAIT | MSG_TRUNC);
        if (n < 0 && errno != EINTR)
            return;
        if (n >= 0 && !keep_pending_reply(b, junk, n))
            b->stats.stale++;
    }
}

static int send_pkt(struct hm2_eth_board *b, const struct lbp16_pkt *p)
{
    ssize_t n = send(b->fd, p->buf, p->len, 0);
    if (n == (ssize_t)p->len)
        return 0;
    return n < 0 ? -errno : -EIO;
}

/* Wait until deadline (monotonic ns) for a datagram; its length, or
 * -ETIMEDOUT.  A refused/unreachable error (nobody listens) waits on. */
static ssize_t recv_until(struct hm2_eth_board *b, uint8_t *buf, size_t cap, int64_t deadline)
{
    for (;;) {
        ssize_t n = recv(b->fd, buf, cap, MSG_DONTWAIT | MSG_TRUNC);
        if (n >= 0)
            return n;
        if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR &&
            errno != ECONNREFUSED && errno != EHOSTUNREACH)
            return -errno;
        int64_t left = deadline - mono_ns();
        if (left <= 0)
            return -ETIMEDOUT;
        struct timespec ts = {left / 1000000000, left % 1000000000};
        struct pollfd pf = {b->fd, POLLIN, 0};
        ppoll(&pf, 1, &ts, NULL);
    }
}

int hm2_eth_transact(struct hm2_eth_board *b, const struct lbp16_pkt *p, uint8_t *reply,
                     int timeout_us, int tries)
{
    if (p->reply_len == 0) {
        drain(b);
        return send_pkt(b, p);
    }
    /* the request plus a tag: a late reply to an earlier try or request
     * of the same size is not taken for this one */
    struct lbp16_pkt q = *p;
    uint32_t tag = ++b->sync_tag;
    if (lbp16_add_sync_tag(&q, tag))
        return -ENOSPC;
    uint8_t buf[LBP16_MAX_PACKET + 1];
    for (int t = 0; t < tries; t++) {
        drain(b);
        int r = send_pkt(b, &q);
        if (r)
            return r;
        int64_t deadline = mono_ns() + (int64_t)timeout_us * 1000;
        for (;;) {
            ssize_t n = recv_until(b, buf, sizeof(buf), deadline);
            if (n == -ETIMEDOUT)
                break;
            if (n < 0)
                return (int)n;
            if (lbp16_check_sync_reply(buf, (size_t)n, q.reply_len, tag) == 0) {
                memcpy(reply, buf, p->reply_len);
                b->stats.replies++;
                return 0;
            }
            if (!keep_pending_reply(b, buf, n))
                b->stats.stale++;
        }
        b->stats.timeouts++;
    }
    return -ETIMEDOUT;
}

/* ---- synchronous hm2 access (load time, tools) ------------------------ */

static int eth_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size)
{
    struct hm2_eth_board *b = (struct hm2_eth_board *)llio;
    uint8_t *dst = buffer;
    if (size % 4 || addr % 4)
        return -EINVAL;
    if (b->running)
        b->stats.rt_reads++;
    while (size > 0) {
        struct lbp16_pkt p;
        lbp16_reset(&p);
        size_t done = 0;
        while (done < size) {
            unsigned words = (unsigned)((size - done) / 4);
            if (words > LBP16_MAX_COUNT)
                words = LBP16_MAX_COUNT;
            /* room left for the tag (hm2_eth_transact) */
            if (p.reply_len + words * 4u + 64 > LBP16_MAX_PACKET ||
                lbp16_add_read(&p, LBP16_SPACE_HM2, 4, (uint16_t)(addr + done), words, 1))
                break;
            done += words * 4u;
        }
        uint8_t reply[LBP16_MAX_PACKET];
        int r = hm2_eth_transact(b, &p, reply, SYNC_TIMEOUT_US, SYNC_TRIES);
        if (r) {
            logf_(b, HM2_ERR, "hm2_eth: %s: no reply to a read of %zu bytes at 0x%04x", b->ip,
                  done, addr);
            return -EIO;
        }
        memcpy(dst, reply, done);
        dst += done;
        addr += (uint32_t)done;
        size -= done;
    }
    return 0;
}

static int eth_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size)
{
    struct hm2_eth_board *b = (struct hm2_eth_board *)llio;
    const uint8_t *src = buffer;
    if (size % 4 || addr % 4)
        return -EINVAL;
    while (size > 0) {
        struct lbp16_pkt p;
        lbp16_reset(&p);
        size_t done = 0;
        while (done < size) {
            unsigned words = (unsigned)((size - done) / 4);
            if (words > LBP16_MAX_COUNT)
                words = LBP16_MAX_COUNT;
            if (lbp16_add_write(&p, LBP16_SPACE_HM2, 4, (uint16_t)(addr + done), words, 1,
                                src + done))
                break;
            done += words * 4u;
        }
        if (done == 0 || send_pkt(b, &p)) {
            logf_(b, HM2_ERR, "hm2_eth: %s: cannot send a write of %zu bytes at 0x%04x: %s",
                  b->ip, size, addr, strerror(errno));
            return -EIO;
        }
        src += done;
        addr += (uint32_t)done;
        size -= done;
    }
    return 0;
}

/* Load-time waits (llio delay, e.g. Smart Serial discovery): the board's
 * own wait register (LBP16 timer space 0x02, microseconds) holds its
 * command processing, so the tagged reply comes after the board time has
 * passed, on a real card as on a virtual one in lockstep.  The reply may
 * take long on a simulated board: the timeout allows 200 times the wait. */
#define DELAY_SLOWDOWN 200
static int eth_delay(hm2_llio_t *llio, long ns)
{
    struct hm2_eth_board *b = (struct hm2_eth_board *)llio;
    long us = (ns + 999) / 1000;
    while (us > 0) {
        uint16_t chunk = (uint16_t)(us > 0xFFFF ? 0xFFFF : us);
        struct lbp16_pkt p;
        uint8_t reply[LBP16_MAX_PACKET];
        lbp16_reset(&p);
        lbp16_add_write(&p, LBP16_SPACE_TIMERS, 2, LBP16_TIMER_WAIT_US, 1, 0, &chunk);
        lbp16_add_read(&p, LBP16_SPACE_TIMERS, 2, 0, 1, 0); /* a reply to wait for */
        int r = hm2_eth_transact(b, &p, reply, SYNC_TIMEOUT_US + chunk * DELAY_SLOWDOWN, 1);
        if (r) {
            logf_(b, HM2_ERR, "hm2_eth: %s: no reply to a %u us board wait", b->ip,
                  (unsigned)chunk);
            return -EIO;
        }
        us -= chunk;
    }
    return 0;
}

/* ---- the servo cycle ---------------------------------------------------- */

static int eth_queue_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size)
{
    struct hm2_eth_board *b = (struct hm2_eth_board *)llio;
    if (b->nrq == 0)
        lbp16_reset(&b->rpkt);
    if (b->nrq >= HM2_ETH_MAX_QUEUED || size == 0 || size % 4 || size / 4 > LBP16_MAX_COUNT ||
        lbp16_add_read(&b->rpkt, LBP16_SPACE_HM2, 4, (uint16_t)addr, (unsigned)(size / 4), 1) ||
        b->rpkt.len + 16 > LBP16_MAX_PACKET ||
        b->rpkt.reply_len + LBP16_READ_TAIL_REPLY > LBP16_MAX_PACKET) {
        logf_(b, HM2_ERR,
              "hm2_eth: %s: queued read of %zu bytes at 0x%04x does not fit in one datagram",
              b->ip, size, addr);
        return -ENOSPC;
    }
    b->rq[b->nrq].dest = buffer;
    b->rq[b->nrq].size = size;
    b->nrq++;
    b->running = true;
    return 0;
}

static void account(struct hm2_eth_board *b, bool bad)
{
    struct hm2_eth_errpins *e = b->pins;
    int32_t limit = *e->limit > 0 ? *e->limit : 1;
    *e->error = bad;
    if (bad) {
        (*e->total)++;
        int32_t lv = *e->level + (*e->increment > 0 ? *e->increment : 0);
        *e->level = lv > limit ? limit : lv;
    } else {
        int32_t lv = *e->level - (*e->decrement > 0 ? *e->decrement : 0);
        *e->level = lv < 0 ? 0 : lv;
    }
    *e->exceeded = *e->level >= limit;
}

static int eth_request_queued_reads(hm2_llio_t *llio)
{
    struct hm2_eth_board *b = (struct hm2_eth_board *)llio;
    if (*b->pins->exceeded) {
        /* io_error was cleared (the core calls again): start afresh */
        *b->pins->exceeded = false;
        *b->pins->level = 0;
        logf_(b, HM2_PRINT, "hm2_eth: %s: packet error level reset, trying again", b->ip);
    }
    b->req.pending = false;
    b->req.nrq = b->nrq;
    b->nrq = 0;
    b->read_seq++;
    if (lbp16_add_read_tail(&b->rpkt, b->read_seq)) {
        logf_(b, HM2_ERR, "hm2_eth: %s: the servo-cycle read does not fit in one datagram",
              b->ip);
        return -ENOSPC;
    }
    drain(b);
    b->req.send_err = send_pkt(b, &b->rpkt);
    b->stats.read_packets++;
    /* outside a thread (the core's first transfers at load time) a read
     * may wait as long as a synchronous one */
    b->req.timeout_ns = llio->period_ns > 0
                            ? hm2_eth_read_timeout_ns(*b->pins->read_timeout, llio->period_ns)
                            : LOAD_TIME_READ_TIMEOUT_NS;
    b->req.deadline = mono_ns() + b->req.timeout_ns;
    b->req.kept = 0;
    b->req.pending = true;
    return 0;
}

/* Wait for the pending request's reply; its length in b->req.reply or
 * -ETIMEDOUT (-errno: the request was not sent). */
static ssize_t await_reply(struct hm2_eth_board *b, struct lbp16_reply_check *c)
{
    if (b->req.send_err)
        return b->req.send_err;
    ssize_t n = b->req.kept;
    while (n <= 0) {
        n = recv_until(b, b->req.reply, sizeof(b->req.reply), b->req.deadline);
        if (n < 0)
            return n;
        if (lbp16_check_read_reply(b->req.reply, (size_t)n, b->rpkt.reply_len, b->read_seq,
                                   NULL)) {
            b->stats.stale++;
            n = 0;
        }
    }
    lbp16_check_read_reply(b->req.reply, (size_t)n, b->rpkt.reply_len, b->read_seq, c);
    return n;
}

static int eth_receive_queued_reads(hm2_llio_t *llio)
{
    struct hm2_eth_board *b = (struct hm2_eth_board *)llio;
    if (!b->req.pending) {
        logf_(b, HM2_ERR, "hm2_eth: %s: receive without a read request", b->ip);
        return -EINVAL;
    }
    struct lbp16_reply_check c = {0, 0, 0};
    ssize_t n = await_reply(b, &c);
    b->req.pending = false;
    bool lost = n < 0, wlost = false;
    if (!lost) {
        b->stats.replies++;
        size_t off = 0;
        for (int i = 0; i < b->req.nrq; i++) {
            memcpy(b->rq[i].dest, b->req.reply + off, b->rq[i].size);
            off += b->rq[i].size;
        }
        wlost = c.write_seq != b->write_seq;
        if (wlost) {
            b->stats.write_losses++;
            logf_(b, HM2_DBG, "hm2_eth: %s: write datagram %u lost (the board saw %u)", b->ip,
                  (unsigned)b->write_seq, (unsigned)c.write_seq);
        }
        if (b->silent)
            logf_(b, HM2_PRINT, "hm2_eth: %s: the board answers again", b->ip);
        b->silent = false;
    } else {
        b->stats.timeouts++;
        int e = b->req.send_err;
        if (!b->silent)
            logf_(b, HM2_ERR,
                  "hm2_eth: %s: no reply to the servo-cycle read within %ld us%s%s; keeping the "
                  "last data (reported once until it answers again)",
                  b->ip, b->req.timeout_ns / 1000, e ? ": " : "", e ? strerror(-e) : "");
        b->silent = true;
    }
    account(b, lost || wlost);
    if (*b->pins->exceeded) {
        logf_(b, HM2_ERR,
              "hm2_eth: %s: packet error level reached packet-error-limit %d: stopping (clear "
              "io_error to retry)",
              b->ip, (int)*b->pins->limit);
        return -EIO;
    }
    return 0;
}

static int eth_send_queued_reads(hm2_llio_t *llio)
{
    int r = eth_request_queued_reads(llio);
    return r ? r : eth_receive_queued_reads(llio);
}

static int eth_queue_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size)
{
    struct hm2_eth_board *b = (struct hm2_eth_board *)llio;
    if (size == 0 || size % 4 || size / 4 > LBP16_MAX_COUNT ||
        b->wpkt.len + 4 + size + 8 > LBP16_MAX_PACKET ||
        lbp16_add_write(&b->wpkt, LBP16_SPACE_HM2, 4, (uint16_t)addr, (unsigned)(size / 4), 1,
                        buffer)) {
        logf_(b, HM2_ERR,
              "hm2_eth: %s: queued write of %zu bytes at 0x%04x does not fit in one datagram",
              b->ip, size, addr);
        return -ENOSPC;
    }
    return 0;
}

static int eth_send_queued_writes(hm2_llio_t *llio)
{
    struct hm2_eth_board *b = (struct hm2_eth_board *)llio;
    b->write_seq++;
    int r = lbp16_add_write_tail(&b->wpkt, b->write_seq);
    if (r == 0)
        r = send_pkt(b, &b->wpkt);
    lbp16_reset(&b->wpkt);
    b->stats.write_packets++;
    /* a send that fails (no route, buffer full) is a lost packet: the next
     * read reply shows it */
    (void)r;
    return 0;
}

/* ---- setup ------------------------------------------------------------------ */

static int probe(struct hm2_eth_board *b)
{
    struct lbp16_pkt p;
    uint8_t reply[LBP16_MAX_PACKET];
    lbp16_reset(&p);
    lbp16_add_read(&p, LBP16_SPACE_INFO, 2, 0, 8, 1);
    lbp16_add_read(&p, LBP16_SPACE_EEPROM, 2, 2, 3, 1);
    if (hm2_eth_transact(b, &p, reply, PROBE_TIMEOUT_US, PROBE_TRIES)) {
        logf_(b, HM2_ERR, "hm2_eth: no board answers at %s (UDP port %d): no reply to %d tries",
              b->ip, LBP16_PORT, PROBE_TRIES);
        return -ENODEV;
    }
    memcpy(b->lbp16_name, reply, 16);
    b->lbp16_name[16] = '\0';
    for (int i = 0; i < 6; i++) /* low word first on the wire, printable order reversed */
        b->mac[i] = reply[16 + 5 - i];
    logf_(b, HM2_INFO, "hm2_eth: %s: INFO: Hardware address (MAC): %02x:%02x:%02x:%02x:%02x:%02x",
          b->ip, b->mac[0], b->mac[1], b->mac[2], b->mac[3], b->mac[4], b->mac[5]);
    /* both sequence numbers start at 0 */
    lbp16_reset(&p);
    uint8_t zero[8] = {0};
    lbp16_add_write(&p, LBP16_SPACE_TIMERS, 2, LBP16_SCRATCH_READ_SEQ, 4, 1, zero);
    lbp16_add_read(&p, LBP16_SPACE_TIMERS, 2, LBP16_SCRATCH_READ_SEQ, 4, 1);
    if (hm2_eth_transact(b, &p, reply, PROBE_TIMEOUT_US, PROBE_TRIES)) {
        logf_(b, HM2_ERR, "hm2_eth: %s: no reply while clearing the sequence numbers", b->ip);
        return -ENODEV;
    }
    return 0;
}

int hm2_eth_setup(struct hm2_eth_board *b, const char *ip, int index, hm2_log_fn log,
                  void *log_ctx)
{
    memset(b, 0, sizeof(*b));
    b->fd = -1;
    b->log = log;
    b->log_ctx = log_ctx;
    snprintf(b->ip, sizeof(b->ip), "%s", ip ? ip : "");
    struct hm2_eth_errvals *v = &b->local;
    v->limit = 10;
    v->increment = 2;
    v->decrement = 1;
    v->read_timeout = 80;
    b->pins = &b->local_pins;
    b->local_pins = (struct hm2_eth_errpins){&v->error,     &v->exceeded,  &v->level,
                                       &v->total,     &v->limit,     &v->increment,
                                       &v->decrement, &v->read_timeout};
    b->peer.sin_family = AF_INET;
    b->peer.sin_port = htons(LBP16_PORT);
    if (!ip || inet_pton(AF_INET, ip, &b->peer.sin_addr) != 1) {
        logf_(b, HM2_ERR, "hm2_eth: board_ip '%s' is not an IPv4 address (like 192.168.1.121)",
              ip ? ip : "");
        return -EINVAL;
    }
    b->fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (b->fd < 0 || connect(b->fd, (struct sockaddr *)&b->peer, sizeof(b->peer)) < 0) {
        int e = errno;
        logf_(b, HM2_ERR, "hm2_eth: %s: cannot open a UDP socket to port %d: %s", ip, LBP16_PORT,
              strerror(e));
        hm2_eth_teardown(b, false);
        return -e;
    }
    int r = probe(b);
    if (r) {
        hm2_eth_teardown(b, false);
        return r;
    }
    b->info = hm2_eth_board_of(b->lbp16_name);
    if (!b->info) {
        logf_(b, HM2_ERR,
              "hm2_eth: %s: board '%.16s' is not an Ethernet board this driver knows (7I76E, 7I92, "
              "7I96, 7I96S)",
              ip, b->lbp16_name);
        hm2_eth_teardown(b, false);
        return -ENODEV;
    }
    logf_(b, HM2_PRINT, "hm2_eth: discovered %.16s", b->lbp16_name);
    hm2_board_fill_llio(b->info, index, &b->llio);
    b->llio.read = eth_read;
    b->llio.write = eth_write;
    b->llio.queue_read = eth_queue_read;
    b->llio.send_queued_reads = eth_send_queued_reads;
    b->llio.request_queued_reads = eth_request_queued_reads;
    b->llio.receive_queued_reads = eth_receive_queued_reads;
    b->llio.delay = eth_delay;
    b->llio.queue_write = eth_queue_write;
    b->llio.send_queued_writes = eth_send_queued_writes;
    b->llio.priv = b;
    lbp16_reset(&b->wpkt);
    return 0;
}

void hm2_eth_teardown(struct hm2_eth_board *b, bool bite)
{
    if (b->fd >= 0 && bite) {
        /* the watchdog bites at once: the board's outputs go safe */
        uint32_t one = 1;
        eth_write(&b->llio, 0x0C00, &one, 4);
    }
    if (b->fd >= 0)
        close(b->fd);
    b->fd = -1;
}
