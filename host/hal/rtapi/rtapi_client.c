/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_client.c - halcmd's side of the rtapi_app socket: connect, start
 * rtapi_app on demand (bin/rtapi_app next to the calling program), send a
 * request, read the reply.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "hal_session.h"
#include "rtapi_proto.h"

static int try_connect(void)
{
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return -errno;
    struct sockaddr_un sa;
    memset(&sa, 0, sizeof(sa));
    sa.sun_family = AF_UNIX;
    char name[sizeof(sa.sun_path)];
    hal_priv_socket_name(name, sizeof(name));
    size_t n = 1 + strlen(name + 1);
    memcpy(sa.sun_path, name, n);
    if (connect(fd, (struct sockaddr *)&sa, (socklen_t)(offsetof(struct sockaddr_un, sun_path) + n)) != 0) {
        int e = errno;
        close(fd);
        return -e;
    }
    return fd;
}

static int rtapi_app_path(char *buf, size_t len)
{
    const char *env = getenv("HAL_RTAPI_APP");
    if (env != NULL && *env) {
        snprintf(buf, len, "%s", env);
        return 0;
    }
    char self[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
    if (n <= 0)
        return -errno;
    self[n] = '\0';
    char *slash = strrchr(self, '/');
    if (slash == NULL)
        return -ENOENT;
    *slash = '\0';
    if ((size_t)snprintf(buf, len, "%s/rtapi_app", self) < len && access(buf, X_OK) == 0)
        return 0;
    /* A program in another directory of the build (tests/, utils/): look
     * in ../bin. */
    if ((size_t)snprintf(buf, len, "%s/../bin/rtapi_app", self) < len && access(buf, X_OK) == 0)
        return 0;
    return -ENOENT;
}

/* In the daemon child: no descriptor of the caller survives (a lock or
 * a pipe held open by a daemon hangs whoever waits for it). */
static void close_inherited_fds(int keep)
{
    long max = sysconf(_SC_OPEN_MAX);
    if (max < 0 || max > 65536)
        max = 65536;
    for (int fd = 3; fd < max; fd++)
        if (fd != keep)
            close(fd);
}

static int start_rtapi_app(void)
{
    char path[PATH_MAX];
    int rc = rtapi_app_path(path, sizeof(path));
    if (rc != 0) {
        fprintf(stderr, "HAL: ERROR: cannot find rtapi_app next to this program\n");
        return rc;
    }
    /* Under halrun (which waits for rtapi_app at its end) the daemon
     * shares the session's terminal, as LinuxCNC's does.  A halcmd run on
     * its own may have pipes as stdout/stderr that its caller reads to
     * EOF; the daemon must not hold them open, so its messages go to the
     * session log in the private runtime directory instead. */
    const char *stdio = getenv("HAL_RTAPI_STDIO");
    int log = -1;
    if (stdio == NULL || strcmp(stdio, "inherit") != 0) {
        char logname[512];
        log = hal_priv_open_log(logname, sizeof(logname));
        if (log < 0)
            return log;
    }
    pid_t pid = fork();
    if (pid < 0) {
        int e = errno;
        if (log >= 0)
            close(log);
        return -e;
    }
    if (pid == 0) {
        /* Nothing of the caller's open files stays with us: even an _exit
         * may touch them (valgrind's libc cleanup seeks the shared offset
         * of halcmd's input file back). */
        close_inherited_fds(log);
        /* Grandchild becomes the daemon, so nobody has to reap it. */
        if (fork() != 0)
            _exit(0);
        setsid();
        int devnull = open("/dev/null", O_RDWR);
        if (devnull >= 0)
            dup2(devnull, 0);
        if (log >= 0) {
            dup2(log, 1);
            dup2(log, 2);
            close(log);
        }
        execl(path, "rtapi_app", (char *)NULL);
        fprintf(stderr, "HAL: ERROR: cannot run %s: %s\n", path, strerror(errno));
        _exit(127);
    }
    if (log >= 0)
        close(log);
    int st;
    waitpid(pid, &st, 0);
    return 0;
}

int rtapi_client_connect(int start)
{
    int fd = try_connect();
    if (fd >= 0 || !start)
        return fd;
    /* A fresh rtapi_app would run none of the components the dead one
     * left listed: refuse until the session is cleaned. */
    int dead = 0;
    if (hal_priv_attach() == 0 && hal_priv_rt_lost(&dead)) {
        fprintf(stderr,
                "HAL: ERROR: the realtime host of HAL session '%s' (rtapi_app, pid %d) is "
                "gone; its components no longer run.  Run 'halrun -U' to clean up the "
                "session.\n",
                hal_priv_instance(), dead);
        return -EOWNERDEAD;
    }
    int rc = start_rtapi_app();
    if (rc != 0)
        return rc;
    for (int i = 0; i < 5000; i++) {
        fd = try_connect();
        if (fd >= 0)
            return fd;
        struct timespec ts = {0, 1000000};
        nanosleep(&ts, NULL);
    }
    fprintf(stderr, "HAL: ERROR: rtapi_app did not start\n");
    return -ETIMEDOUT;
}

static int write_all(int fd, const void *buf, size_t len)
{
    const char *p = buf;
    while (len > 0) {
        ssize_t n = write(fd, p, len);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return -errno;
        }
        p += n;
        len -= (size_t)n;
    }
    return 0;
}

static int read_all(int fd, void *buf, size_t len)
{
    char *p = buf;
    while (len > 0) {
        ssize_t n = read(fd, p, len);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return -errno;
        }
        if (n == 0)
            return -EPIPE;
        p += n;
        len -= (size_t)n;
    }
    return 0;
}

static int request_once(int start, int argc, const char *const *argv, int *status,
                        char **messages, int timeout_ms);
int rtapi_client_request_timeout(int start, int argc, const char *const *argv, int *status,
                                 char **messages, int timeout_ms);

int rtapi_client_request(int start, int argc, const char *const *argv, int *status,
                         char **messages)
{
    return rtapi_client_request_timeout(start, argc, argv, status, messages, 0);
}

int rtapi_client_request_timeout(int start, int argc, const char *const *argv, int *status,
                                 char **messages, int timeout_ms)
{
    /* rtapi_app leaves when nothing is loaded; a request that raced with
     * its exit was never seen by it (the connection is reset before any
     * reply), so it is safe to try again with a fresh one. */
    int rc = -EPIPE;
    for (int attempt = 0; attempt < 5; attempt++) {
        rc = request_once(start, argc, argv, status, messages, timeout_ms);
        if (rc != -EPIPE && rc != -ECONNRESET && rc != -ECONNREFUSED)
            return rc;
        if (timeout_ms > 0 && rc != -ECONNREFUSED)
            return rc;
        if (rc == -ECONNREFUSED && !start)
            return rc;
        struct timespec ts = {0, 5000000};
        nanosleep(&ts, NULL);
    }
    return rc;
}

static int request_once(int start, int argc, const char *const *argv, int *status,
                        char **messages, int timeout_ms)
{
    if (messages)
        *messages = NULL;
    size_t len = 0;
    for (int i = 0; i < argc; i++)
        len += strlen(argv[i]) + 1;
    char *buf = malloc(len + 4);
    if (buf == NULL)
        return -ENOMEM;
    uint32_t l32 = (uint32_t)len;
    memcpy(buf, &l32, 4);
    char *p = buf + 4;
    for (int i = 0; i < argc; i++) {
        size_t n = strlen(argv[i]) + 1;
        memcpy(p, argv[i], n);
        p += n;
    }
    int fd = rtapi_client_connect(start);
    if (fd < 0) {
        free(buf);
        return fd;
    }
    if (timeout_ms > 0) {
        struct timeval tv = {timeout_ms / 1000, (timeout_ms % 1000) * 1000};
        setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
        setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof(tv));
    }
    int rc = write_all(fd, buf, len + 4);
    free(buf);
    int32_t st = 0;
    uint32_t mlen = 0;
    if (rc == 0)
        rc = read_all(fd, &st, 4);
    if (rc == 0)
        rc = read_all(fd, &mlen, 4);
    if (rc == 0 && mlen > 0) {
        char *m = malloc(mlen + 2);
        if (m == NULL) {
            rc = -ENOMEM;
        } else {
            rc = read_all(fd, m, mlen);
            m[mlen] = '\0'; /* NUL-separated records end with an empty one */
            m[mlen + 1] = '\0';
            if (rc == 0 && messages)
                *messages = m;
            else
                free(m);
        }
    }
    close(fd);
    if (rc == 0 && status)
        *status = st;
    return rc;
}
