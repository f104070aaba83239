/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_app - the realtime host of a HAL session.
 *
 * Started on demand by halcmd (one per HAL_INSTANCE), it listens on the
 * session's abstract unix socket (rtapi_server.c), loads realtime
 * components (NAME.so) with their module parameters (rtapi_modules.c),
 * owns the HAL threads (rtapi_threads.c), and exits once nothing is
 * loaded any more.  See docs/rtapi.md.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include "rtapi_app.h"

volatile sig_atomic_t rtapi_got_signal;

static void on_signal(int sig)
{
    (void)sig;
    rtapi_got_signal = 1;
}

int main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    /* Process name hm2-rtapi_app: an installed LinuxCNC counts every
     * process named exactly `rtapi_app` as its own realtime (its halrun
     * then refuses to start), so the two can run side by side. */
    prctl(PR_SET_NAME, "hm2-rtapi_app", 0, 0, 0);
    signal(SIGPIPE, SIG_IGN);
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);

    int lfd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (lfd < 0) {
        perror("rtapi_app: socket");
        return 1;
    }
    struct sockaddr_un addr;
    memset(&addr, 0, sizeof(addr));
    addr.sun_family = AF_UNIX;
    char name[sizeof(addr.sun_path)];
    hal_priv_socket_name(name, sizeof(name));
    size_t n = 1 + strlen(name + 1);
    memcpy(addr.sun_path, name, n);
    if (bind(lfd, (struct sockaddr *)&addr,
             (socklen_t)(offsetof(struct sockaddr_un, sun_path) + n)) != 0) {
        /* Another rtapi_app of this session got there first. */
        close(lfd);
        return errno == EADDRINUSE ? 0 : 1;
    }
    if (listen(lfd, 16) != 0) {
        perror("rtapi_app: listen");
        return 1;
    }
    hal_priv_set_realtime_host(1);
    rtapi_priv_set_msg_hook(rtapi_msg_hook);
    if (hal_priv_attach() != 0)
        return 1;
    hal_priv_set_thread_hooks(&rtapi_thread_hooks);
    hal_hdr->rtapi_start = hal_priv_self_start_time();
    __atomic_store_n(&hal_hdr->rtapi_pid, getpid(), __ATOMIC_RELEASE);
    int rc = rtapi_threads_init(hal_hdr->simclock);
    if (rc != 0) {
        fprintf(stderr, "rtapi_app: cannot start the simulated-clock scheduler: %s\n",
                strerror(-rc));
        return 1;
    }
    rtapi_serve(lfd);
    /* Stop taking requests before tearing down. */
    close(lfd);
    rtapi_unload_all();
    rtapi_threads_exit();
    if (hal_hdr->rtapi_pid == getpid()) {
        hal_hdr->rtapi_pid = 0;
        hal_hdr->rtapi_start = 0;
    }
    rtapi_server_exit();
    return 0;
}
