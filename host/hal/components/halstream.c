/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halstream.c - shared-memory FIFO of sampler/streamer.  See halstream.h.
 */
#define _GNU_SOURCE
#include "halstream.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#define HALSTREAM_MAGIC 0x484d5354u /* "HMST" */
#define HALSTREAM_VERSION 1u

struct halstream_shm {
    uint32_t magic;
    uint32_t version;
    int32_t depth;
    int32_t npins;
    int32_t types[HALSTREAM_MAX_PINS];
    _Atomic uint32_t in;  /* written by the producer only */
    _Atomic uint32_t out; /* written by the consumer only */
    _Atomic int32_t peer_pid;
    _Atomic int32_t closed;
    /* records follow: depth * (npins + 1) values, the last being the
     * sample number */
    halstream_value_t data[];
};

static size_t record_len(int npins)
{
    return (size_t)npins + 1;
}

static size_t shm_bytes(int depth, int npins)
{
    return sizeof(halstream_shm_t) + (size_t)depth * record_len(npins) * sizeof(halstream_value_t);
}

char halstream_type_char(hal_type_t t)
{
    switch (t) {
    case HAL_BIT:
        return 'b';
    case HAL_FLOAT:
        return 'f';
    case HAL_S32:
        return 's';
    case HAL_U32:
        return 'u';
    case HAL_S64:
        return 'l';
    case HAL_U64:
        return 'k';
    default:
        return '?';
    }
}

int halstream_parse_cfg(const char *cfg, hal_type_t *types, char *err, size_t errlen)
{
    int n = 0;
    if (cfg == NULL || cfg[0] == '\0') {
        snprintf(err, errlen, "empty cfg string");
        return -EINVAL;
    }
    for (const char *c = cfg; *c; c++) {
        hal_type_t t;
        switch (tolower((unsigned char)*c)) {
        case 'b':
            t = HAL_BIT;
            break;
        case 'f':
            t = HAL_FLOAT;
            break;
        case 's':
            t = HAL_S32;
            break;
        case 'u':
            t = HAL_U32;
            break;
        case 'l':
            t = HAL_S64;
            break;
        case 'k':
            t = HAL_U64;
            break;
        default:
            snprintf(err, errlen, "unknown type '%c' at position %d, must be F, B, U, S, L or K",
                     isprint((unsigned char)*c) ? *c : '?', (int)(c - cfg) + 1);
            return -EINVAL;
        }
        if (n == HALSTREAM_MAX_PINS) {
            snprintf(err, errlen, "more than %d items", HALSTREAM_MAX_PINS);
            return -EINVAL;
        }
        types[n++] = t;
    }
    return n;
}

void halstream_shm_name(char *buf, size_t len, const char *kind, int chan)
{
    /* Same instance naming and sanitising as libhal's segment, so a session
     * (HAL_INSTANCE) owns every object it creates. */
    const char *inst = getenv("HAL_INSTANCE");
    char clean[64];
    size_t n = 0;
    if (inst == NULL || inst[0] == '\0')
        inst = "0";
    for (const char *p = inst; *p && n < sizeof(clean) - 1; p++)
        clean[n++] = (*p == '/') ? '_' : *p;
    clean[n] = '\0';
    snprintf(buf, len, "/hm2hal-%u-%s.%s.%d", (unsigned)getuid(), clean, kind, chan);
}

int halstream_create(halstream_t *s, const char *kind, int chan, int depth, int npins,
                     const hal_type_t *types, char *err, size_t errlen)
{
    memset(s, 0, sizeof(*s));
    if (depth <= 0 || npins <= 0 || npins > HALSTREAM_MAX_PINS) {
        snprintf(err, errlen, "bad depth %d or pin count %d", depth, npins);
        return -EINVAL;
    }
    /* The ring's index arithmetic is modulo 2^32 on free-running counters,
     * which needs the depth to stay far below that. */
    if (depth > (1 << 24)) {
        snprintf(err, errlen, "depth %d too large (at most %d)", depth, 1 << 24);
        return -EINVAL;
    }
    halstream_shm_name(s->name, sizeof(s->name), kind, chan);
    size_t size = shm_bytes(depth, npins);
    /* A leftover object of a crashed session with the same instance is
     * ours to replace: the instance name is the session's namespace. */
    shm_unlink(s->name);
    int fd = shm_open(s->name, O_RDWR | O_CREAT | O_EXCL, 0600);
    if (fd < 0) {
        snprintf(err, errlen, "cannot create shared memory %s: %s", s->name, strerror(errno));
        return -errno;
    }
    if (ftruncate(fd, (off_t)size) != 0) {
        int e = errno;
        snprintf(err, errlen, "cannot size shared memory %s to %zu bytes: %s", s->name, size,
                 strerror(e));
        close(fd);
        shm_unlink(s->name);
        return -e;
    }
    void *p = mmap(NULL, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    close(fd);
    if (p == MAP_FAILED) {
        int e = errno;
        snprintf(err, errlen, "cannot map shared memory %s: %s", s->name, strerror(e));
        shm_unlink(s->name);
        return -e;
    }
    s->shm = p;
    s->map_size = size;
    s->owner = 1;
    s->depth = depth;
    s->npins = npins;
    halstream_shm_t *h = s->shm;
    h->depth = depth;
    h->npins = npins;
    for (int i = 0; i < npins; i++)
        h->types[i] = types[i];
    atomic_store(&h->in, 0);
    atomic_store(&h->out, 0);
    atomic_store(&h->peer_pid, 0);
    atomic_store(&h->closed, 0);
    h->version = HALSTREAM_VERSION;
    atomic_thread_fence(memory_order_release);
    h->magic = HALSTREAM_MAGIC; /* last: a peer only trusts a complete header */
    return 0;
}

void halstream_destroy(halstream_t *s)
{
    if (s->shm == NULL)
        return;
    if (s->owner) {
        atomic_store(&s->shm->closed, 1);
        shm_unlink(s->name);
    }
    munmap(s->shm, s->map_size);
    s->shm = NULL;
}

static int pid_alive(pid_t pid)
{
    if (pid <= 0)
        return 0;
    if (kill(pid, 0) != 0 && errno == ESRCH)
        return 0;
    /* an exited but unreaped peer is a zombie: as good as gone */
    char path[64], buf[256];
    snprintf(path, sizeof(path), "/proc/%d/stat", (int)pid);
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return 1; /* cannot tell: assume alive (kill said so) */
    size_t n = fread(buf, 1, sizeof(buf) - 1, f);
    fclose(f);
    buf[n] = '\0';
    char *rp = strrchr(buf, ')');
    if (rp != NULL && rp[1] == ' ' && (rp[2] == 'Z' || rp[2] == 'X'))
        return 0;
    return 1;
}

int halstream_attach(halstream_t *s, const char *kind, int chan, char *err, size_t errlen)
{
    memset(s, 0, sizeof(*s));
    halstream_shm_name(s->name, sizeof(s->name), kind, chan);
    int fd = shm_open(s->name, O_RDWR, 0600);
    if (fd < 0) {
        int e = errno;
        if (e == ENOENT)
            snprintf(err, errlen, "no %s channel %d in this HAL session (is '%s' loaded with "
                     "that many channels?)", kind, chan, kind);
        else
            snprintf(err, errlen, "cannot open shared memory %s: %s", s->name, strerror(e));
        return -e;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || (size_t)st.st_size < sizeof(halstream_shm_t)) {
        close(fd);
        snprintf(err, errlen, "shared memory %s is truncated", s->name);
        return -EPROTO;
    }
    void *p = mmap(NULL, (size_t)st.st_size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    close(fd);
    if (p == MAP_FAILED) {
        int e = errno;
        snprintf(err, errlen, "cannot map shared memory %s: %s", s->name, strerror(e));
        return -e;
    }
    halstream_shm_t *h = p;
    if (h->magic != HALSTREAM_MAGIC || h->version != HALSTREAM_VERSION || h->depth <= 0 ||
        h->npins <= 0 || h->npins > HALSTREAM_MAX_PINS ||
        shm_bytes(h->depth, h->npins) > (size_t)st.st_size) {
        munmap(p, (size_t)st.st_size);
        snprintf(err, errlen, "shared memory %s is not a %s FIFO (bad header)", s->name, kind);
        return -EPROTO;
    }
    s->shm = h;
    s->map_size = (size_t)st.st_size;
    s->depth = h->depth;
    s->npins = h->npins;
    int32_t me = (int32_t)getpid();
    for (;;) {
        int32_t cur = atomic_load(&h->peer_pid);
        if (cur != 0 && cur != me && pid_alive(cur)) {
            munmap(p, s->map_size);
            s->shm = NULL;
            snprintf(err, errlen, "%s channel %d is already in use by process %d", kind, chan,
                     (int)cur);
            return -EBUSY;
        }
        if (atomic_compare_exchange_weak(&h->peer_pid, &cur, me))
            break;
    }
    return 0;
}

void halstream_detach(halstream_t *s)
{
    if (s->shm == NULL)
        return;
    int32_t me = (int32_t)getpid();
    atomic_compare_exchange_strong(&s->shm->peer_pid, &me, 0);
    munmap(s->shm, s->map_size);
    s->shm = NULL;
}

int halstream_pin_count(const halstream_t *s)
{
    return s->npins;
}

hal_type_t halstream_pin_type(const halstream_t *s, int i)
{
    return (hal_type_t)s->shm->types[i];
}

int halstream_capacity(const halstream_t *s)
{
    return s->depth;
}

int halstream_fill(const halstream_t *s)
{
    uint32_t in = atomic_load_explicit(&s->shm->in, memory_order_acquire);
    uint32_t out = atomic_load_explicit(&s->shm->out, memory_order_acquire);
    return (int)(in - out);
}

int halstream_closed(const halstream_t *s)
{
    return atomic_load(&s->shm->closed) != 0;
}

int halstream_peer_attached(halstream_t *s)
{
    int32_t pid = atomic_load(&s->shm->peer_pid);
    if (pid == 0)
        return 0;
    if (pid_alive(pid))
        return 1;
    atomic_compare_exchange_strong(&s->shm->peer_pid, &pid, 0);
    return 0;
}

int halstream_write(halstream_t *s, const halstream_value_t *vals, rtapi_u32 sampleno)
{
    halstream_shm_t *h = s->shm;
    uint32_t in = atomic_load_explicit(&h->in, memory_order_relaxed);
    uint32_t out = atomic_load_explicit(&h->out, memory_order_acquire);
    if ((int)(in - out) >= s->depth)
        return -ENOSPC;
    halstream_value_t *rec = &h->data[(size_t)(in % (uint32_t)s->depth) * record_len(s->npins)];
    memcpy(rec, vals, sizeof(*vals) * (size_t)s->npins);
    rec[s->npins].u = sampleno;
    atomic_store_explicit(&h->in, in + 1, memory_order_release);
    return 0;
}

int halstream_read(halstream_t *s, halstream_value_t *vals, rtapi_u32 *sampleno)
{
    halstream_shm_t *h = s->shm;
    uint32_t out = atomic_load_explicit(&h->out, memory_order_relaxed);
    uint32_t in = atomic_load_explicit(&h->in, memory_order_acquire);
    if (in == out)
        return -EAGAIN;
    const halstream_value_t *rec =
        &h->data[(size_t)(out % (uint32_t)s->depth) * record_len(s->npins)];
    memcpy(vals, rec, sizeof(*vals) * (size_t)s->npins);
    if (sampleno != NULL)
        *sampleno = rec[s->npins].u;
    atomic_store_explicit(&h->out, out + 1, memory_order_release);
    return 0;
}
