/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_proto.h - the request protocol between halcmd and rtapi_app over
 * the session's abstract unix socket (see docs/rtapi.md).
 *
 * request:  u32 length, then `length` bytes: argv strings, each NUL-ended
 *           ("load", "and2", "count=2") ...
 * reply:    i32 status (0 or -errno), u32 length, then the messages that
 *           modules printed while the request ran (to be shown by halcmd):
 *           records "E<text>" (for stderr) or "O<text>" (for stdout), each
 *           ended by a NUL.  `list` replies with module names, one a line.
 *
 * Requests: load NAME [ARGS...] | unload NAME | list | simrun NS | ping |
 *           exit (unload everything and quit).
 */
#ifndef HM_RTAPI_PROTO_H
#define HM_RTAPI_PROTO_H

#include <stddef.h>

/* Client side (halcmd). */
/* Connect to the session's rtapi_app, starting it when `start` is set.
 * Returns a socket fd or -errno. */
int rtapi_client_connect(int start);
/* Send argv, receive status and messages (malloc'd, NUL-terminated, may be
 * NULL).  Returns 0 when the exchange worked (the request's own status is
 * in *status), -errno when it did not. */
int rtapi_client_request(int start, int argc, const char *const *argv, int *status,
                         char **messages);

/* The same with a receive/send timeout (ms, 0 = none): -EAGAIN when
 * rtapi_app does not answer in time. */
int rtapi_client_request_timeout(int start, int argc, const char *const *argv, int *status,
                                 char **messages, int timeout_ms);

#endif /* HM_RTAPI_PROTO_H */
