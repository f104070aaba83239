/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * llio.h - the low-level I/O interface between the hostmot2 core and a
 * board backend (virtual board socket, PCI BAR, EPP port, register image).
 *
 * The hostmot2 core sees a board only through this struct; see docs/llio.md.
 * A backend fills one hm2_llio_t per board and hands it to hm2_register().
 * The struct must stay valid (and at the same address) until
 * hm2_unregister() returns.
 *
 * Every function returns 0 on success and a negative errno value on failure
 * (-EIO bus error or timeout, -ENODEV board gone, -EINVAL bad argument).
 * Addresses are hm2 byte addresses (0..0xFFFF); sizes are byte counts, both
 * multiples of 4; buffers hold little-endian 32-bit words in host order
 * (the backend converts if its bus is big-endian).
 */
#ifndef HM2_LLIO_H
#define HM2_LLIO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define HM2_LLIO_NAME_LEN 31
#define HM2_LLIO_MAX_CONNECTORS 8
#define HM2_LLIO_MAX_IO_PINS 1000

struct hm2_bitfile;
typedef struct hm2_llio hm2_llio_t;

struct hm2_llio {
    /* Identity.  name is the board prefix used everywhere: "hm2_5i20.0".
     * Required. */
    char name[HM2_LLIO_NAME_LEN + 1];
    /* HAL component id the core exports the board's objects under (the
     * backend's component).  Ignored by hm2_probe(). */
    int comp_id;

    /* Connector geometry, checked against the IDROM.  Required. */
    int num_ioport_connectors;
    int pins_per_connector;
    const char *ioport_connector_name[HM2_LLIO_MAX_CONNECTORS];
    /* Optional per-pin names (boards like the 7i96 whose connectors are not
     * one header per port).  io_pin_names[i] replaces "<connector>-<pin>"
     * in the pin report; a NULL entry hides the pin from the report. */
    const char *const *io_pin_names;
    int num_io_pin_names;

    int num_leds;
    /* FPGA part as in a .BIT 'b' chunk ("2s200pq208"); "" when unknown. */
    const char *fpga_part_number;

    /* 1: read/write may be called from a fast thread concurrently with the
     * servo thread's calls (PCI): read_gpio/write_gpio are exported. */
    int threadsafe;

    /* ---- bus access (required) ---- */
    int (*read)(hm2_llio_t *self, uint32_t addr, void *buffer, size_t size);
    int (*write)(hm2_llio_t *self, uint32_t addr, const void *buffer, size_t size);

    /* ---- queued access (optional, all or none) ----
     * The core queues every per-period transfer and flushes once per servo
     * period: queue_read() records (addr, buffer, size) and returns; the
     * buffer is filled by send_queued_reads(), which performs every queued
     * read in order and clears the queue.  queue_write() copies the data at
     * once (the caller may reuse its buffer); send_queued_writes() performs
     * every queued write in order and clears the queue.  A backend with a
     * packet bus (socket, Ethernet) turns one flush into one round trip. */
    int (*queue_read)(hm2_llio_t *self, uint32_t addr, void *buffer, size_t size);
    int (*send_queued_reads)(hm2_llio_t *self);
    int (*queue_write)(hm2_llio_t *self, uint32_t addr, const void *buffer, size_t size);
    int (*send_queued_writes)(hm2_llio_t *self);

    /* ---- split queued reads (optional, both or none; need the queued
     * access above) ----
     * request_queued_reads() sends every queued read and returns without
     * waiting; receive_queued_reads() waits for the answer to that request
     * and fills the buffers (the two together do what send_queued_reads()
     * does).  With them the core exports <board>.read-request (hostmot2(9)):
     * the request goes out early in the thread and the reply travels while
     * other functions (other boards' requests) run. */
    int (*request_queued_reads)(hm2_llio_t *self);
    int (*receive_queued_reads)(hm2_llio_t *self);

    /* ---- FPGA configuration (optional; NULL = board cannot be programmed,
     * firmware= is then ignored) ----
     * reset(): put the FPGA into the unconfigured state and check it got
     * there (DONE low, /INIT high).  program_fpga(): send the bitstream
     * (the .BIT 'e' chunk, unmodified; the backend reverses bit order if
     * its configuration port needs it, see hm2_bitfile_reverse()) and check
     * DONE/INIT afterwards.  Both return -EIO with their own message on a
     * failed check. */
    int (*reset)(hm2_llio_t *self);
    int (*program_fpga)(hm2_llio_t *self, const struct hm2_bitfile *bitfile);

    /* Let `ns` nanoseconds of board time pass (optional; load-time waits
     * such as Smart Serial discovery).  A virtual board advances its
     * clocks; NULL: the core sleeps on the wall clock. */
    int (*delay)(hm2_llio_t *self, long ns);

    /* Period in ns of the thread that runs the board's read/write functions,
     * set by the core before each call (0 outside a thread).  Backends with
     * timeouts relative to the period (hm2_eth) read it. */
    long period_ns;

    /* Backend-private data. */
    void *priv;
    /* Owned by the hostmot2 core: the board registered on this llio (set
     * by hm2_register, cleared by hm2_unregister).  Backends leave it. */
    void *hm2;
};

/* Connector text for the pin report: "<connector>-<pin2>", or the llio's
 * per-pin name; returns NULL for a pin that the report must skip. */
const char *hm2_llio_pin_name(const hm2_llio_t *llio, int io_pin, char *buf, size_t len);

/* Check that an llio has everything the core needs; 0 or -EINVAL with a
 * message in err (len bytes). */
int hm2_llio_validate(const hm2_llio_t *llio, char *err, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* HM2_LLIO_H */
