/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of halstream (cfg strings, the shared-memory ring between a
 * sampler/streamer channel and its peer), against expectations written from
 * sampler(9).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "halstream.h"

static void test_cfg(void)
{
    hal_type_t t[HALSTREAM_MAX_PINS];
    char err[128];
    CHECK_EQ_INT(halstream_parse_cfg("bfsu", t, err, sizeof(err)), 4);
    CHECK(t[0] == HAL_BIT && t[1] == HAL_FLOAT && t[2] == HAL_S32 && t[3] == HAL_U32);
    CHECK_EQ_INT(halstream_parse_cfg("BFSULK", t, err, sizeof(err)), 6);
    CHECK(t[4] == HAL_S64 && t[5] == HAL_U64);
    CHECK_EQ_INT(halstream_parse_cfg("bx", t, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "unknown type 'x' at position 2") != NULL);
    CHECK_EQ_INT(halstream_parse_cfg("", t, err, sizeof(err)), -EINVAL);
    CHECK_EQ_INT(halstream_parse_cfg(NULL, t, err, sizeof(err)), -EINVAL);
    char many[32];
    memset(many, 'f', 22);
    many[22] = '\0';
    CHECK_EQ_INT(halstream_parse_cfg(many, t, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "more than 21") != NULL);
    many[21] = '\0';
    CHECK_EQ_INT(halstream_parse_cfg(many, t, err, sizeof(err)), 21);
    CHECK_EQ_INT(halstream_parse_cfg("b f", t, err, sizeof(err)), -EINVAL);
}

static void test_ring(void)
{
    hal_type_t types[2] = {HAL_S32, HAL_FLOAT};
    char err[256];
    halstream_t rt, peer, other;
    CHECK_EQ_INT(halstream_create(&rt, "sampler", 3, 4, 2, types, err, sizeof(err)), 0);
    CHECK_EQ_INT(halstream_capacity(&rt), 4);
    CHECK_EQ_INT(halstream_fill(&rt), 0);
    CHECK(!halstream_peer_attached(&rt));
    CHECK_EQ_INT(halstream_attach(&peer, "sampler", 3, err, sizeof(err)), 0);
    CHECK(halstream_peer_attached(&rt));
    CHECK_EQ_INT(halstream_pin_count(&peer), 2);
    CHECK(halstream_pin_type(&peer, 1) == HAL_FLOAT);
    /* a second live peer (a child process) is refused */
    pid_t pid = fork();
    if (pid == 0) {
        int r = halstream_attach(&other, "sampler", 3, err, sizeof(err));
        _exit(r == -EBUSY && strstr(err, "already in use") ? 0 : 1);
    }
    int st = 0;
    waitpid(pid, &st, 0);
    CHECK(WIFEXITED(st) && WEXITSTATUS(st) == 0);

    halstream_value_t v[2], out[2];
    rtapi_u32 num = 99;
    CHECK_EQ_INT(halstream_read(&peer, out, &num), -EAGAIN);
    /* wrap the ring several times against a model queue: a write succeeds
     * exactly when fewer than 4 are queued, reads return FIFO order */
    rtapi_u32 model[64];
    int head = 0, tail = 0;
    for (rtapi_u32 k = 0; k < 40; k++) {
        v[0].s = -(rtapi_s32)k;
        v[1].f = k * 0.5;
        int r = halstream_write(&rt, v, k);
        if (tail - head < 4) {
            CHECK_EQ_INT(r, 0);
            model[tail++] = k;
        } else {
            CHECK_EQ_INT(r, -ENOSPC);
        }
        CHECK_EQ_INT(halstream_fill(&rt), tail - head);
        if (k % 7 == 6) {
            while (tail - head > 1) {
                CHECK_EQ_INT(halstream_read(&peer, out, &num), 0);
                rtapi_u32 w = model[head++];
                CHECK_EQ_INT(num, w);
                CHECK_EQ_INT(out[0].s, -(rtapi_s32)w);
                CHECK(out[1].f == w * 0.5);
            }
        }
    }
    halstream_detach(&peer);
    CHECK(!halstream_peer_attached(&rt));
    CHECK(!halstream_closed(&rt));
    /* the realtime side goes away: a peer attached later sees no channel */
    halstream_destroy(&rt);
    CHECK_EQ_INT(halstream_attach(&peer, "sampler", 3, err, sizeof(err)), -ENOENT);
    CHECK(strstr(err, "no sampler channel 3") != NULL);
}

static void test_full_and_order(void)
{
    hal_type_t types[1] = {HAL_U32};
    char err[256];
    halstream_t rt, peer;
    CHECK_EQ_INT(halstream_create(&rt, "streamer", 0, 3, 1, types, err, sizeof(err)), 0);
    CHECK_EQ_INT(halstream_attach(&peer, "streamer", 0, err, sizeof(err)), 0);
    halstream_value_t v, out;
    for (rtapi_u32 k = 0; k < 3; k++) {
        v.u = 100 + k;
        CHECK_EQ_INT(halstream_write(&peer, &v, k), 0);
    }
    v.u = 7;
    CHECK_EQ_INT(halstream_write(&peer, &v, 3), -ENOSPC); /* capacity is exactly depth */
    for (rtapi_u32 k = 0; k < 3; k++) {
        rtapi_u32 n;
        CHECK_EQ_INT(halstream_read(&rt, &out, &n), 0);
        CHECK_EQ_INT(out.u, 100 + k);
        CHECK_EQ_INT(n, k);
    }
    CHECK_EQ_INT(halstream_read(&rt, &out, NULL), -EAGAIN);
    halstream_destroy(&rt);
    CHECK(halstream_closed(&peer)); /* the peer's mapping stays valid */
    halstream_detach(&peer);
}

static void test_bad_create(void)
{
    hal_type_t types[1] = {HAL_BIT};
    char err[256];
    halstream_t s;
    CHECK_EQ_INT(halstream_create(&s, "sampler", 0, 0, 1, types, err, sizeof(err)), -EINVAL);
    CHECK_EQ_INT(halstream_create(&s, "sampler", 0, 4, 0, types, err, sizeof(err)), -EINVAL);
    CHECK_EQ_INT(halstream_create(&s, "sampler", 0, 1 << 25, 1, types, err, sizeof(err)),
                 -EINVAL);
    CHECK(strstr(err, "too large") != NULL);
}

int main(void)
{
    char inst[64];
    snprintf(inst, sizeof(inst), "unit-halstream-%d", (int)getpid());
    setenv("HAL_INSTANCE", inst, 1);
    RUN(test_cfg);
    RUN(test_ring);
    RUN(test_full_and_order);
    RUN(test_bad_create);
    return check_summary();
}
