/* SPDX-License-Identifier: GPL-2.0-or-later */
/* fake_board.c - see fake_board.h.  Requests are validated only as far as
 * the tests need; READ/WRITE/CONFIG/HELLO follow vboard/proto.h. */
#define _GNU_SOURCE
#include "fake_board.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

static int read_full(int fd, void *buf, size_t n)
{
    uint8_t *p = buf;
    while (n) {
        ssize_t r = read(fd, p, n);
        if (r <= 0)
            return -1;
        p += r;
        n -= (size_t)r;
    }
    return 0;
}

static void reply(int fd, const struct vb_header *rq, int16_t status, const void *data,
                  uint32_t len, int bad_seq)
{
    struct vb_header h = {VB_REP_MAGIC, rq->type, status, len, rq->seq + (bad_seq ? 7u : 0u),
                          rq->time_ns};
    if (write(fd, &h, sizeof(h)) != (ssize_t)sizeof(h))
        return;
    if (len && write(fd, data, len) != (ssize_t)len)
        return;
}

static void error_reply(int fd, const struct vb_header *rq, int err, const char *msg)
{
    reply(fd, rq, (int16_t)-err, msg, (uint32_t)strlen(msg), 0);
}

static int xfer_ok(const struct vb_xfer *x)
{
    return x->addr % 4 == 0 && x->size % 4 == 0 && (uint64_t)x->addr + x->size <= 65536;
}

static void do_read(struct fake_board *fb, int fd, const struct vb_header *h, const uint8_t *p)
{
    uint32_t n = h->length / sizeof(struct vb_xfer), total = 0;
    const struct vb_xfer *x = (const void *)p;
    for (uint32_t i = 0; i < n; i++) {
        if (!xfer_ok(&x[i]))
            return error_reply(fd, h, EINVAL, "read outside the register window");
        total += x[i].size;
    }
    uint8_t *out = malloc(total ? total : 1), *o = out;
    for (uint32_t i = 0; i < n; i++) {
        memcpy(o, fb->regs + x[i].addr, x[i].size);
        o += x[i].size;
    }
    fb->reads++;
    fb->last_xfers = n;
    reply(fd, h, 0, out, total, 0);
    free(out);
}

static void do_write(struct fake_board *fb, int fd, const struct vb_header *h, const uint8_t *p)
{
    uint32_t off = 0, n = 0;
    while (off + sizeof(struct vb_xfer) <= h->length) {
        struct vb_xfer x;
        memcpy(&x, p + off, sizeof(x));
        off += sizeof(x);
        if (!xfer_ok(&x) || off + x.size > h->length)
            return error_reply(fd, h, EINVAL, "write outside the register window");
        memcpy(fb->regs + x.addr, p + off, x.size);
        off += x.size;
        n++;
    }
    fb->writes++;
    fb->last_xfers = n;
    reply(fd, h, 0, NULL, 0, 0);
}

static void do_config(struct fake_board *fb, int fd, const struct vb_header *h, const uint8_t *p)
{
    struct vb_config c;
    struct vb_config_status st = {0, 1, ""};
    fb->configs++;
    memcpy(&c, p, sizeof(c));
    if (c.op == VB_CONFIG_RESET) {
        fb->state = VB_STATE_BLANK;
    } else if (c.op == VB_CONFIG_PROGRAM) {
        uint32_t n = h->length - (uint32_t)sizeof(c);
        if (n < 4 || memcmp(p + sizeof(c), "GOOD", 4) != 0) {
            fb->state = VB_STATE_BLANK;
            return error_reply(fd, h, EINVAL, "image is not for this board (fake)");
        }
        fb->state = VB_STATE_CONFIGURED;
        snprintf(st.firmware, sizeof(st.firmware), "FAKEFW");
    }
    st.done = fb->state == VB_STATE_CONFIGURED;
    reply(fd, h, 0, &st, sizeof(st), 0);
}

static void serve(struct fake_board *fb, int fd)
{
    for (;;) {
        struct vb_header h;
        if (fb->fault == FAKE_STALL && fb->fault_at && fb->requests + 1 >= fb->fault_at) {
            while (!fb->stall_release)
                usleep(1000);
            return;
        }
        if (read_full(fd, &h, sizeof(h)))
            return;
        uint8_t *p = malloc(h.length + 16u);
        if (!p || read_full(fd, p, h.length)) {
            free(p);
            return;
        }
        fb->requests++;
        fb->last_time_ns = h.time_ns;
        enum fake_fault f = fb->fault_at && fb->requests >= fb->fault_at ? fb->fault : FAKE_OK;
        if (f == FAKE_CLOSE) {
            free(p);
            return;
        }
        if (f == FAKE_SILENT) {
            free(p);
            continue;
        }
        if (f == FAKE_BAD_SEQ) {
            reply(fd, &h, 0, NULL, 0, 1);
        } else if (h.type == VB_HELLO) {
            struct vb_hello he = {VB_PROTO_VERSION, fb->bus, fb->state, 72, 33333333, 100000000,
                                  1, 0, "", "", "2s200pq208"};
            snprintf(he.board, sizeof(he.board), "%s", fb->board);
            reply(fd, &h, 0, &he, sizeof(he), 0);
        } else if (h.type == VB_READ) {
            do_read(fb, fd, &h, p);
        } else if (h.type == VB_WRITE) {
            do_write(fb, fd, &h, p);
        } else if (h.type == VB_CONFIG) {
            do_config(fb, fd, &h, p);
        } else {
            error_reply(fd, &h, EPROTO, "unknown request");
        }
        free(p);
    }
}

static void *run(void *arg)
{
    struct fake_board *fb = arg;
    for (;;) {
        int fd = accept(fb->listen_fd, NULL, NULL);
        if (fd < 0)
            return NULL;
        serve(fb, fd);
        close(fd);
    }
}

int fake_board_start(struct fake_board *fb, const char *board, uint32_t bus, uint32_t state)
{
    memset(fb, 0, sizeof(*fb));
    snprintf(fb->board, sizeof(fb->board), "%s", board);
    fb->bus = bus;
    fb->state = state;
    snprintf(fb->path, sizeof(fb->path), "/tmp/fakeboard-%d-%p.sock", (int)getpid(), (void *)fb);
    unlink(fb->path);
    fb->listen_fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    struct sockaddr_un sa = {.sun_family = AF_UNIX};
    memcpy(sa.sun_path, fb->path, strlen(fb->path));
    if (fb->listen_fd < 0 || bind(fb->listen_fd, (struct sockaddr *)&sa, sizeof(sa)) < 0 ||
        listen(fb->listen_fd, 4) < 0) {
        perror("fake_board");
        return -1;
    }
    return pthread_create(&fb->thread, NULL, run, fb) ? -1 : 0;
}

void fake_board_stop(struct fake_board *fb)
{
    shutdown(fb->listen_fd, SHUT_RDWR);
    close(fb->listen_fd);
    pthread_join(fb->thread, NULL);
    unlink(fb->path);
}
