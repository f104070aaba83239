/* SPDX-License-Identifier: GPL-2.0-or-later */
/* vboard_client.c - see vboard_client.h. */
#define _GNU_SOURCE
#include "vboard_client.h"

#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

static int64_t now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static int grow(uint8_t **buf, size_t *cap, size_t need)
{
    if (need <= *cap)
        return 0;
    size_t n = *cap ? *cap : 4096;
    while (n < need)
        n *= 2;
    uint8_t *p = realloc(*buf, n);
    if (!p)
        return -ENOMEM;
    *buf = p;
    *cap = n;
    return 0;
}

/* Transport failure: remember why, drop the connection. */
static int fail(vbc_t *c, int rc, const char *what)
{
    snprintf(c->err, sizeof c->err, "virtual board %s: %s", c->path, what);
    c->posted = 0;
    if (c->fd >= 0) {
        close(c->fd);
        c->fd = -1;
    }
    return rc;
}

int vbc_open(vbc_t *c, const char *path)
{
    memset(c, 0, sizeof *c);
    c->fd = -1;
    c->timeout_ms = 5000;
    if (!path || !*path || strlen(path) >= sizeof c->path) {
        snprintf(c->err, sizeof c->err, "virtual board socket path '%s' is empty or too long",
                 path ? path : "");
        return -EINVAL;
    }
    snprintf(c->path, sizeof c->path, "%s", path);
    return vbc_reconnect(c);
}

int vbc_reconnect(vbc_t *c)
{
    if (c->fd >= 0) {
        close(c->fd);
        c->fd = -1;
    }
    c->posted = 0;
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        int e = errno;
        snprintf(c->err, sizeof c->err, "virtual board %s: socket: %s", c->path, strerror(e));
        return -e;
    }
    struct sockaddr_un sa;
    memset(&sa, 0, sizeof sa);
    sa.sun_family = AF_UNIX;
    memcpy(sa.sun_path, c->path, strlen(c->path));
    if (connect(fd, (struct sockaddr *)&sa, sizeof sa) < 0) {
        int e = errno;
        snprintf(c->err, sizeof c->err, "virtual board %s: cannot connect: %s", c->path,
                 strerror(e));
        close(fd);
        return e == ENOENT || e == ECONNREFUSED ? -ENODEV : -e;
    }
    c->fd = fd;
    c->err[0] = 0;
    return 0;
}

void vbc_close(vbc_t *c)
{
    if (c->fd >= 0)
        close(c->fd);
    c->fd = -1;
    c->posted = 0;
    free(c->rx);
    free(c->tx);
    c->rx = c->tx = NULL;
    c->rx_cap = c->tx_cap = c->rx_len = c->tx_len = 0;
}

void vbc_req_start(vbc_t *c)
{
    c->tx_len = sizeof(struct vb_header);
}

int vbc_req_put(vbc_t *c, const void *data, size_t n)
{
    if (c->tx_len < sizeof(struct vb_header))
        c->tx_len = sizeof(struct vb_header);
    if (grow(&c->tx, &c->tx_cap, c->tx_len + n) < 0) {
        snprintf(c->err, sizeof c->err, "virtual board %s: out of memory for a %zu-byte request",
                 c->path, c->tx_len + n);
        return -ENOMEM;
    }
    memcpy(c->tx + c->tx_len, data, n);
    c->tx_len += n;
    return 0;
}

/* Send everything, but never wait longer than the call timeout for buffer
 * space: a hung board that stops reading must not block the caller. */
static int send_all(vbc_t *c, const uint8_t *p, size_t n)
{
    int64_t deadline = now_ms() + c->timeout_ms;
    while (n) {
        ssize_t w = send(c->fd, p, n, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            if (errno == EAGAIN || errno == EWOULDBLOCK) {
                int left = (int)(deadline - now_ms());
                struct pollfd pfd = {.fd = c->fd, .events = POLLOUT};
                if (left <= 0 || (poll(&pfd, 1, left) == 0))
                    return fail(c, -ETIMEDOUT, "the board does not take requests (send timeout)");
                continue;
            }
            char m[96];
            snprintf(m, sizeof m, "send failed: %s (board gone?)", strerror(errno));
            return fail(c, -ENODEV, m);
        }
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

static int64_t now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* Busy-poll for up to spin_us before sleeping in poll(): a sleeping
 * process needs a scheduler wake-up (tens of us on a VM) that a fast
 * board reply does not have to wait for.  1 when data is there. */
static int spin_wait(vbc_t *c)
{
    if (c->spin_us <= 0)
        return 0;
    int64_t end = now_us() + c->spin_us;
    do {
        struct pollfd pfd = {.fd = c->fd, .events = POLLIN};
        if (poll(&pfd, 1, 0) > 0)
            return 1;
    } while (now_us() < end);
    return 0;
}

static int recv_all(vbc_t *c, uint8_t *p, size_t n, int64_t deadline)
{
    int spun = 0;
    while (n) {
        if (!spun) {
            spun = 1;
            if (spin_wait(c))
                goto ready;
        }
        int left = (int)(deadline - now_ms());
        if (left <= 0)
            return fail(c, -ETIMEDOUT, "no reply within the timeout");
        struct pollfd pfd = {.fd = c->fd, .events = POLLIN};
        int r = poll(&pfd, 1, left);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return fail(c, -ETIMEDOUT, "no reply within the timeout");
    ready:;
        ssize_t got = recv(c->fd, p, n, 0);
        if (got == 0)
            return fail(c, -ENODEV, "connection closed by the board (board gone?)");
        if (got < 0) {
            if (errno == EINTR || errno == EAGAIN)
                continue;
            char m[96];
            snprintf(m, sizeof m, "receive failed: %s", strerror(errno));
            return fail(c, -ENODEV, m);
        }
        p += got;
        n -= (size_t)got;
    }
    return 0;
}

/* Frame and send the assembled request; its sequence number in *seq. */
static int send_request(vbc_t *c, uint16_t type, uint64_t host_time_ns, uint32_t *seq)
{
    if (c->fd < 0) {
        if (!c->err[0])
            snprintf(c->err, sizeof c->err, "virtual board %s: not connected", c->path);
        return -ENODEV;
    }
    /* a request without payload never went through vbc_req_put(): the
     * buffer may not exist yet */
    if (grow(&c->tx, &c->tx_cap, sizeof(struct vb_header)) < 0) {
        snprintf(c->err, sizeof c->err, "virtual board %s: out of memory for a request", c->path);
        return -ENOMEM;
    }
    if (c->tx_len < sizeof(struct vb_header))
        c->tx_len = sizeof(struct vb_header);
    struct vb_header h = {.magic = VB_REQ_MAGIC,
                          .type = type,
                          .status = 0,
                          .length = (uint32_t)(c->tx_len - sizeof h),
                          .seq = ++c->seq,
                          .time_ns = host_time_ns};
    memcpy(c->tx, &h, sizeof h);
    int rc = send_all(c, c->tx, c->tx_len);
    c->tx_len = sizeof h;
    *seq = h.seq;
    return rc;
}

/* Receive the reply to request (type, seq) into c->rx. */
static int recv_reply(vbc_t *c, uint16_t type, uint32_t seq)
{
    struct vb_header r;
    int64_t deadline = now_ms() + c->timeout_ms;
    int rc = recv_all(c, (uint8_t *)&r, sizeof r, deadline);
    if (rc < 0)
        return rc;
    if (r.magic != VB_REP_MAGIC || r.seq != seq || r.type != type || r.length > VB_MAX_PAYLOAD)
        return fail(c, -EPROTO, "reply does not match the request (bad magic, seq or type)");
    if (grow(&c->rx, &c->rx_cap, (size_t)r.length + 1) < 0)
        return fail(c, -ENOMEM, "out of memory for the reply");
    if ((rc = recv_all(c, c->rx, r.length, deadline)) < 0)
        return rc;
    c->rx_len = r.length;
    c->board_time_ns = r.time_ns;
    if (r.status < 0) {
        c->rx[r.length] = 0;
        snprintf(c->err, sizeof c->err, "virtual board %s: %s", c->path, (const char *)c->rx);
        return r.status;
    }
    return 0;
}

int vbc_collect(vbc_t *c)
{
    if (!c->posted)
        return 0;
    c->posted = 0;
    int rc = recv_reply(c, c->posted_type, c->posted_seq);
    if (rc < 0 && c->fd >= 0) {
        /* a board-side error of the posted request: say which request */
        static const char note[] = " (reply to an earlier request sent without waiting)";
        size_t n = strlen(c->err);
        if (n + sizeof note <= sizeof c->err)
            memcpy(c->err + n, note, sizeof note);
    }
    return rc;
}

int vbc_post(vbc_t *c, uint16_t type, uint64_t host_time_ns)
{
    int rc = vbc_collect(c);
    if (rc < 0) {
        c->tx_len = sizeof(struct vb_header);
        return rc;
    }
    uint32_t seq;
    if ((rc = send_request(c, type, host_time_ns, &seq)) < 0)
        return rc;
    c->posted = 1;
    c->posted_type = type;
    c->posted_seq = seq;
    return 0;
}

int vbc_send(vbc_t *c, uint16_t type, uint64_t host_time_ns)
{
    int rc = vbc_collect(c);
    if (rc < 0) {
        c->tx_len = sizeof(struct vb_header);
        return rc;
    }
    uint32_t seq;
    if ((rc = send_request(c, type, host_time_ns, &seq)) < 0)
        return rc;
    return recv_reply(c, type, seq);
}

int vbc_call(vbc_t *c, uint16_t type, uint64_t host_time_ns, const void *payload, size_t n)
{
    vbc_req_start(c);
    if (n && vbc_req_put(c, payload, n) < 0)
        return -ENOMEM;
    return vbc_send(c, type, host_time_ns);
}

int vbc_hello(vbc_t *c, struct vb_hello *out)
{
    int rc = vbc_call(c, VB_HELLO, 0, NULL, 0);
    if (rc < 0)
        return rc;
    if (c->rx_len < sizeof *out) {
        snprintf(c->err, sizeof c->err, "virtual board %s: short HELLO reply (%zu bytes)", c->path,
                 c->rx_len);
        return -EPROTO;
    }
    memcpy(out, c->rx, sizeof *out);
    return 0;
}

int vbc_check_clock(vbc_t *c, const struct vb_hello *h, int client_on_simclock)
{
    if (!h->lockstep || client_on_simclock)
        return 0;
    snprintf(c->err, sizeof c->err,
             "the virtual board at %s runs in lockstep (the vboard default) but this HAL "
             "session runs on the wall clock, so the board would fall behind real time; run "
             "the session on the simulated clock (halrun -S) or start the board with "
             "vboard --freerun",
             c->path);
    return -EINVAL;
}

int vbc_remove_stale(const char *path)
{
    struct sockaddr_un sa;
    struct stat st;
    if (!path || !*path || strlen(path) >= sizeof sa.sun_path)
        return 0;
    if (lstat(path, &st) != 0 || !S_ISSOCK(st.st_mode))
        return 0;
    memset(&sa, 0, sizeof sa);
    sa.sun_family = AF_UNIX;
    memcpy(sa.sun_path, path, strlen(path) + 1);
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return 0;
    int refused = connect(fd, (struct sockaddr *)&sa, sizeof sa) != 0 && errno == ECONNREFUSED;
    close(fd);
    return refused && unlink(path) == 0;
}
