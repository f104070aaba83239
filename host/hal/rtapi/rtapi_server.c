/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_server.c - rtapi_app's request server on the session's abstract
 * unix socket (protocol: rtapi_proto.h), and the capture of the messages
 * modules print while a request runs, sent back to the halcmd that asked.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <sched.h>
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

static pthread_mutex_t msg_lock = PTHREAD_MUTEX_INITIALIZER;
static char *msg_buf;
static size_t msg_len, msg_cap;
static int capturing;

/* Captured messages are sent as lines "E<text>" (for stderr: errors and
 * warnings) or "O<text>" (for stdout: info and debug, where LinuxCNC's
 * rtapi_app prints them), each ended by a NUL. */
void rtapi_msg_hook(int level, const char *text)
{
    pthread_mutex_lock(&msg_lock);
    if (capturing) {
        char tagged[1100];
        snprintf(tagged, sizeof(tagged), "%c%s", level <= RTAPI_MSG_WARN ? 'E' : 'O', text);
        text = tagged;
        size_t n = strlen(text) + 1; /* keep the NUL as separator */
        if (msg_len + n + 1 > msg_cap) {
            size_t cap = (msg_cap ? msg_cap * 2 : 1024) + n;
            char *nb = realloc(msg_buf, cap);
            if (nb != NULL) {
                msg_buf = nb;
                msg_cap = cap;
            }
        }
        if (msg_len + n + 1 <= msg_cap) {
            memcpy(msg_buf + msg_len, text, n);
            msg_len += n;
        }
    } else {
        FILE *f = level <= RTAPI_MSG_WARN ? stderr : stdout;
        fputs(text, f);
        fflush(f);
    }
    pthread_mutex_unlock(&msg_lock);
}

/* ---- server --------------------------------------------------------------------- */

static int read_full(int fd, void *buf, size_t len)
{
    char *p = buf;
    while (len) {
        ssize_t n = read(fd, p, len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return -1;
        p += n;
        len -= (size_t)n;
    }
    return 0;
}

static void write_full(int fd, const void *buf, size_t len)
{
    const char *p = buf;
    while (len) {
        ssize_t n = write(fd, p, len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return;
        p += n;
        len -= (size_t)n;
    }
}

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

static void serve_one(int cfd)
{
    uint32_t len;
    if (read_full(cfd, &len, 4) != 0 || len > (1u << 20))
        return;
    char *buf = malloc(len + 1);
    if (buf == NULL)
        return;
    if (read_full(cfd, buf, len) != 0) {
        free(buf);
        return;
    }
    buf[len] = '\0';
    char *argv[512];
    int argc = 0;
    for (char *p = buf; p < buf + len && argc < 511; p += strlen(p) + 1)
        argv[argc++] = p;
    argv[argc] = NULL;
    pthread_mutex_lock(&msg_lock);
    capturing = 1;
    msg_len = 0;
    if (msg_buf)
        msg_buf[0] = '\0';
    pthread_mutex_unlock(&msg_lock);
    char *listing = NULL;
    int32_t st = handle(argc, argv, &listing);
    pthread_mutex_lock(&msg_lock);
    capturing = 0;
    const char *out = listing ? listing : (msg_buf ? msg_buf : "");
    uint32_t olen = listing ? (uint32_t)strlen(listing) : (uint32_t)msg_len;
    write_full(cfd, &st, 4);
    write_full(cfd, &olen, 4);
    write_full(cfd, out, olen);
    msg_len = 0;
    pthread_mutex_unlock(&msg_lock);
    free(listing);
    free(buf);
}

int rtapi_serve(int lfd)
{
    /* Serve until nothing is loaded any more (checked after each request,
     * so the request that started us is served first). */
    int served = 0;
    while (!quit_requested && !rtapi_got_signal) {
        struct timeval tv = {0, 200000};
        fd_set rfds;
        FD_ZERO(&rfds);
        FD_SET(lfd, &rfds);
        int r = select(lfd + 1, &rfds, NULL, NULL, &tv);
        if (r > 0) {
            int cfd = accept4(lfd, NULL, NULL, SOCK_CLOEXEC);
            if (cfd >= 0) {
                serve_one(cfd);
                close(cfd);
                served++;
            }
        } else if (served == 0) {
            /* Started but nobody asked anything for 10 s: give up. */
            static int idle;
            if (++idle > 50)
                break;
        }
        if (served > 0 && !rtapi_modules_loaded() && !rtapi_threads_exist())
            break;
        /* The session was destroyed under us (halrun -U): leave. */
        if (hal_priv_session_state() == 0)
            break;
    }
    return 0;
}

void rtapi_server_exit(void) { free(msg_buf); }
