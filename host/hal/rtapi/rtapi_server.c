/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_server.c - rtapi_app's request server on the session's abstract
 * unix socket (protocol: rtapi_proto.h), and the capture of the messages
 * modules print while a request runs, sent back to the halcmd that asked.
 *
 * An abstract socket has no file permissions, so every peer is checked
 * (SO_PEERCRED): the session's owner, root, our own user, or a member of
 * the session's HAL group; anybody else gets -EACCES and is disconnected.
 * Clients are served from one poll() loop with non-blocking sockets: a
 * client that connects and sends nothing (or half a request), or does not
 * read its reply, holds up nobody, and is dropped after
 * HAL_RTAPI_CLIENT_TIMEOUT_MS (default 5000) ms.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include "rtapi_app.h"

/* ---- captured messages ------------------------------------------------------ */

#define MSG_CAPTURE_MAX (1u << 20)

static pthread_mutex_t msg_lock = PTHREAD_MUTEX_INITIALIZER;
static char *msg_buf;
static size_t msg_len, msg_cap;
static int capturing;

static void msg_append(const char *text)
{
    size_t n = strlen(text) + 1; /* keep the NUL as separator */
    if (msg_len + n + 1 > MSG_CAPTURE_MAX)
        return; /* a module flooding messages: the reply stays bounded */
    if (msg_len + n + 1 > msg_cap) {
        size_t cap = (msg_cap ? msg_cap * 2 : 1024) + n;
        char *nb = realloc(msg_buf, cap);
        if (nb == NULL)
            return;
        msg_buf = nb;
        msg_cap = cap;
    }
    memcpy(msg_buf + msg_len, text, n);
    msg_len += n;
}

/* Captured messages are sent as lines "E<text>" (for stderr: errors and
 * warnings) or "O<text>" (for stdout: info and debug, where LinuxCNC's
 * rtapi_app prints them), each ended by a NUL. */
void rtapi_msg_hook(int level, const char *text)
{
    pthread_mutex_lock(&msg_lock);
    if (capturing) {
        char tagged[1100];
        snprintf(tagged, sizeof(tagged), "%c%s", level <= RTAPI_MSG_WARN ? 'E' : 'O', text);
        msg_append(tagged);
    } else {
        FILE *f = level <= RTAPI_MSG_WARN ? stderr : stdout;
        fputs(text, f);
        fflush(f);
    }
    pthread_mutex_unlock(&msg_lock);
}

/* ---- requests ------------------------------------------------------------------ */

static int quit_requested;

static int handle(int argc, char **argv, char **listing)
{
    *listing = NULL;
    if (argc == 0)
        return -EINVAL;
    if (strcmp(argv[0], "load") == 0)
        return rtapi_do_load(argc, argv);
    if (strcmp(argv[0], "unload") == 0)
        return rtapi_do_unload(argc, argv);
    if (strcmp(argv[0], "simrun") == 0)
        return rtapi_do_simrun(argc, argv);
    if (strcmp(argv[0], "ping") == 0)
        return 0;
    if (strcmp(argv[0], "list") == 0) {
        *listing = rtapi_module_list();
        return *listing != NULL ? 0 : -ENOMEM;
    }
    if (strcmp(argv[0], "exit") == 0) {
        rtapi_unload_all();
        quit_requested = 1;
        return 0;
    }
    rtapi_print_msg(RTAPI_MSG_ERR, "rtapi_app: unknown request '%s'\n", argv[0]);
    return -EINVAL;
}

/* Run one request (`len` bytes of NUL-ended strings); returns the reply
 * (status, length, messages) in a malloc'd buffer. */
static char *run_request(char *buf, uint32_t len, size_t *replylen)
{
    char *argv[512];
    int argc = 0;
    for (char *p = buf; p < buf + len && argc < 511; p += strlen(p) + 1)
        argv[argc++] = p;
    argv[argc] = NULL;
    pthread_mutex_lock(&msg_lock);
    capturing = 1;
    msg_len = 0;
    pthread_mutex_unlock(&msg_lock);
    char *listing = NULL;
    int32_t st = handle(argc, argv, &listing);
    pthread_mutex_lock(&msg_lock);
    capturing = 0;
    const char *out = listing ? listing : (msg_buf ? msg_buf : "");
    uint32_t olen = listing ? (uint32_t)strlen(listing) : (uint32_t)msg_len;
    char *reply = malloc(8 + (size_t)olen);
    if (reply != NULL) {
        memcpy(reply, &st, 4);
        memcpy(reply + 4, &olen, 4);
        memcpy(reply + 8, out, olen);
        *replylen = 8 + (size_t)olen;
    }
    msg_len = 0;
    pthread_mutex_unlock(&msg_lock);
    free(listing);
    return reply;
}

/* ---- peers ---------------------------------------------------------------------- */

/* 1 when /proc/PID/status lists gid among the process's groups. */
static int pid_in_group(pid_t pid, gid_t gid)
{
    char path[64], line[4096];
    snprintf(path, sizeof(path), "/proc/%d/status", (int)pid);
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return 0;
    int found = 0;
    while (!found && fgets(line, sizeof(line), f) != NULL) {
        if (strncmp(line, "Groups:", 7) != 0)
            continue;
        for (char *p = line + 7, *end; *p; p = end) {
            unsigned long g = strtoul(p, &end, 10);
            if (end == p)
                break;
            if ((gid_t)g == gid)
                found = 1;
        }
    }
    fclose(f);
    return found;
}

static int peer_allowed(const struct ucred *cr)
{
    if (cr->uid == 0 || cr->uid == geteuid() || cr->uid == (uid_t)hal_hdr->owner_uid)
        return 1;
    if (hal_hdr->group_gid >= 0) {
        gid_t g = (gid_t)hal_hdr->group_gid;
        if (cr->gid == g || pid_in_group(cr->pid, g))
            return 1;
    }
    return 0;
}

/* ---- clients -------------------------------------------------------------------- */

#define MAX_CLIENTS 64
#define MAX_REFUSED 8
#define MAX_REQUEST (1u << 20)

typedef struct {
    int fd;
    pid_t pid;
    uid_t uid;
    int refused;     /* not allowed: answered with -EACCES only */
    long long deadline; /* ms on CLOCK_MONOTONIC */
    int sending;
    uint32_t len;    /* request length, once its header is in */
    size_t got;      /* bytes received (header included) */
    char hdr[4];
    char *req;       /* request body */
    char *reply;     /* pending reply */
    size_t replylen, sent;
} client_t;

static client_t clients[MAX_CLIENTS];
static int nclients;
static int requests_run;
static long long client_timeout_ms = 5000;

static long long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static void client_close(int i)
{
    close(clients[i].fd);
    free(clients[i].req);
    free(clients[i].reply);
    clients[i] = clients[--nclients];
}

/* Write what the socket takes; 1 when the reply is out, 0 when more is
 * pending, -1 on error. */
static int client_flush(client_t *c)
{
    while (c->sent < c->replylen) {
        ssize_t n = send(c->fd, c->reply + c->sent, c->replylen - c->sent, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            return 0;
        if (n <= 0)
            return -1;
        c->sent += (size_t)n;
    }
    return 1;
}

/* A refused peer's request is read (so the connection is not reset)
 * and answered with -EACCES and a message it can show. */
static char *refusal(uid_t uid, size_t *replylen)
{
    char text[256];
    int n = snprintf(text, sizeof(text),
                     "Ertapi_app: permission denied: uid %u may not use the HAL session of "
                     "uid %u (see HAL_GROUP in docs/hal.md)\n",
                     (unsigned)uid, (unsigned)hal_hdr->owner_uid);
    int32_t st = -EACCES;
    uint32_t len = (uint32_t)n + 1;
    char *reply = malloc(8 + (size_t)len);
    if (reply == NULL)
        return NULL;
    memcpy(reply, &st, 4);
    memcpy(reply + 4, &len, 4);
    memcpy(reply + 8, text, len);
    *replylen = 8 + (size_t)len;
    return reply;
}

static void accept_client(int lfd)
{
    int fd = accept4(lfd, NULL, NULL, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0)
        return;
    struct ucred cr;
    socklen_t crlen = sizeof(cr);
    if (getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cr, &crlen) != 0) {
        close(fd);
        return;
    }
    int refused = !peer_allowed(&cr), nrefused = 0;
    for (int i = 0; i < nclients; i++)
        nrefused += clients[i].refused;
    if (refused && nrefused >= MAX_REFUSED) {
        close(fd); /* strangers cannot crowd out the session's own clients */
        return;
    }
    if (nclients >= MAX_CLIENTS) {
        fprintf(stderr, "rtapi_app: too many clients, dropping pid %d\n", (int)cr.pid);
        close(fd);
        return;
    }
    client_t *c = &clients[nclients++];
    memset(c, 0, sizeof(*c));
    c->fd = fd;
    c->pid = cr.pid;
    c->uid = cr.uid;
    c->refused = refused;
    if (c->refused)
        fprintf(stderr, "rtapi_app: refused a client of uid %u (pid %d)\n", (unsigned)cr.uid,
                (int)cr.pid);
    c->deadline = now_ms() + client_timeout_ms;
}

/* Read what has arrived; returns 1 when a whole request is in, 0 when
 * more is expected, -1 when the client must go. */
static int client_read(client_t *c)
{
    for (;;) {
        char *dst;
        size_t want;
        if (c->got < 4) {
            dst = c->hdr + c->got;
            want = 4 - c->got;
        } else {
            dst = c->req + (c->got - 4);
            want = c->len - (c->got - 4);
        }
        if (want == 0)
            return 1;
        ssize_t n = recv(c->fd, dst, want, 0);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            return 0;
        if (n <= 0)
            return -1;
        c->got += (size_t)n;
        if (c->got == 4) {
            memcpy(&c->len, c->hdr, 4);
            if (c->len > MAX_REQUEST) {
                fprintf(stderr, "rtapi_app: request of %u bytes from pid %d refused\n",
                        (unsigned)c->len, (int)c->pid);
                return -1;
            }
            c->req = malloc((size_t)c->len + 1);
            if (c->req == NULL)
                return -1;
        }
    }
}

/* Serve client i after poll() saw activity; 0 keeps it, -1 drops it. */
static int client_service(int i)
{
    client_t *c = &clients[i];
    if (!c->sending) {
        int r = client_read(c);
        if (r <= 0)
            return r;
        c->req[c->len] = '\0';
        if (c->refused) {
            c->reply = refusal(c->uid, &c->replylen);
            if (c->reply == NULL)
                return -1;
            c->sending = 1;
            c->sent = 0;
            return client_flush(c) == 0 ? 0 : -1;
        }
        long long t0 = now_ms();
        c->reply = run_request(c->req, c->len, &c->replylen);
        requests_run++;
        /* The others waited for us, not the other way round. */
        long long took = now_ms() - t0;
        for (int k = 0; k < nclients; k++)
            clients[k].deadline += took;
        if (c->reply == NULL)
            return -1;
        c->sending = 1;
        c->sent = 0;
        c->deadline = now_ms() + client_timeout_ms;
    }
    int w = client_flush(c);
    return w == 0 ? 0 : -1; /* sent (or failed): one request per connection */
}

static void drop_late_clients(void)
{
    long long now = now_ms();
    for (int i = 0; i < nclients;) {
        if (now > clients[i].deadline) {
            fprintf(stderr, "rtapi_app: client pid %d %s within %lld ms, dropped\n",
                    (int)clients[i].pid,
                    clients[i].sending ? "did not read its reply" : "sent no request",
                    client_timeout_ms);
            client_close(i);
        } else {
            i++;
        }
    }
}

static int replies_pending(void)
{
    for (int i = 0; i < nclients; i++)
        if (clients[i].sending)
            return 1;
    return 0;
}

int rtapi_serve(int lfd)
{
    const char *to = getenv("HAL_RTAPI_CLIENT_TIMEOUT_MS");
    if (to != NULL && *to) {
        long v;
        if (rtapi_parse_long(to, &v) == 0 && v > 0 && v <= 3600000)
            client_timeout_ms = v;
    }
    /* Serve until nothing is loaded any more (checked after each request,
     * so the request that started us is served first). */
    int idle = 0;
    while (!quit_requested && !rtapi_got_signal) {
        struct pollfd pfd[MAX_CLIENTS + 1];
        pfd[0].fd = lfd;
        pfd[0].events = POLLIN;
        for (int i = 0; i < nclients; i++) {
            pfd[i + 1].fd = clients[i].fd;
            pfd[i + 1].events = clients[i].sending ? POLLOUT : POLLIN;
        }
        int n = nclients;
        int r = poll(pfd, (nfds_t)n + 1, 200);
        if (r > 0) {
            /* Back to front: closing swaps the last client into slot i. */
            for (int i = n - 1; i >= 0; i--) {
                if (pfd[i + 1].revents == 0)
                    continue;
                if (client_service(i) != 0)
                    client_close(i);
            }
            if (pfd[0].revents & POLLIN)
                accept_client(lfd);
        } else if (requests_run == 0 && nclients == 0 && ++idle > 50) {
            /* Started but nobody asked anything for 10 s: give up. */
            break;
        }
        drop_late_clients();
        if (requests_run > 0 && !rtapi_modules_loaded() && !rtapi_threads_exist() &&
            !replies_pending())
            break;
        /* The session was destroyed under us (halrun -U): leave. */
        if (hal_priv_session_state() == HAL_SESSION_NONE)
            break;
    }
    /* Replies already computed still go out (the `exit` request's). */
    for (int t = 0; t < 100 && replies_pending(); t++) {
        for (int i = nclients - 1; i >= 0; i--)
            if (clients[i].sending && client_flush(&clients[i]) != 0)
                client_close(i);
        if (replies_pending()) {
            struct timespec ts = {0, 10000000};
            nanosleep(&ts, NULL);
        }
    }
    while (nclients > 0)
        client_close(nclients - 1);
    return 0;
}

void rtapi_server_exit(void) { free(msg_buf); }
