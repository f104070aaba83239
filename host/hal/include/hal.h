/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal.h - the HAL API for components (realtime modules and userspace
 * programs alike).  Names and semantics follow LinuxCNC 2.9's hal.h so a
 * LinuxCNC component author feels at home; see docs/hal.md.
 *
 * All HAL objects live in one POSIX shared-memory segment, linked by
 * offsets, guarded by one lock.  A pin is a pointer-to-storage that the
 * component owns (hal_pin_*_new stores into *data_ptr_addr); linking the pin
 * to a signal repoints it at the signal's storage, unlinking repoints it at
 * the pin's own dummy, so realtime code never tests for NULL.
 *
 * Return values: 0 or a positive id on success, a negative errno value on
 * failure (-EINVAL bad argument, -ENOMEM out of HAL memory, -EEXIST name in
 * use, -EPERM locked or wrong context, -ENOENT no such object).  Every
 * failure also prints an RTAPI_MSG_ERR line that says what failed, on which
 * object, and why.
 */
#ifndef HM_HAL_H
#define HM_HAL_H

#include <stdbool.h>
#include <stdint.h>

#include "rtapi.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HAL_NAME_LEN 47 /* longest name of any HAL object */

typedef enum {
    HAL_TYPE_UNSPECIFIED = -1,
    HAL_BIT = 1,
    HAL_FLOAT = 2,
    HAL_S32 = 3,
    HAL_U32 = 4,
    HAL_PORT = 5, /* reserved, not implemented */
    HAL_S64 = 6,
    HAL_U64 = 7,
} hal_type_t;

typedef enum {
    HAL_DIR_UNSPECIFIED = -1,
    HAL_IN = 16,
    HAL_OUT = 32,
    HAL_IO = (HAL_IN | HAL_OUT),
} hal_pin_dir_t;

typedef enum {
    HAL_RO = 64,
    HAL_RW = 192,
} hal_param_dir_t;

typedef volatile bool hal_bit_t;
typedef volatile rtapi_u32 hal_u32_t;
typedef volatile rtapi_s32 hal_s32_t;
typedef volatile rtapi_u64 hal_u64_t;
typedef volatile rtapi_s64 hal_s64_t;
typedef double real_t __attribute__((aligned(8)));
typedef volatile real_t hal_float_t;

/* Storage of a signal or of a pin's dummy: every type fits. */
typedef union {
    hal_bit_t b;
    hal_s32_t s;
    hal_u32_t u;
    hal_float_t f;
    hal_s64_t ls;
    hal_u64_t lu;
} hal_data_u;

/* ---- components -------------------------------------------------------- */

/* Register a component.  In rtapi_app the component is realtime (type RT),
 * elsewhere userspace (type User, with the caller's pid).  Returns the
 * component id (> 0). */
int hal_init(const char *name);
int hal_exit(int comp_id);
int hal_ready(int comp_id);
int hal_unready(int comp_id);
const char *hal_comp_name(int comp_id);
/* Allocate from HAL shared memory; never freed until the session ends.
 * Returns NULL (with an error message) when the segment is full. */
void *hal_malloc(long size);

/* ---- pins -------------------------------------------------------------- */

int hal_pin_new(const char *name, hal_type_t type, hal_pin_dir_t dir,
                void **data_ptr_addr, int comp_id);
int hal_pin_bit_new(const char *name, hal_pin_dir_t dir, hal_bit_t **data_ptr_addr,
                    int comp_id);
int hal_pin_float_new(const char *name, hal_pin_dir_t dir,
                      hal_float_t **data_ptr_addr, int comp_id);
int hal_pin_u32_new(const char *name, hal_pin_dir_t dir, hal_u32_t **data_ptr_addr,
                    int comp_id);
int hal_pin_s32_new(const char *name, hal_pin_dir_t dir, hal_s32_t **data_ptr_addr,
                    int comp_id);
int hal_pin_u64_new(const char *name, hal_pin_dir_t dir, hal_u64_t **data_ptr_addr,
                    int comp_id);
int hal_pin_s64_new(const char *name, hal_pin_dir_t dir, hal_s64_t **data_ptr_addr,
                    int comp_id);

int hal_pin_bit_newf(hal_pin_dir_t dir, hal_bit_t **data_ptr_addr, int comp_id,
                     const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_pin_float_newf(hal_pin_dir_t dir, hal_float_t **data_ptr_addr, int comp_id,
                       const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_pin_u32_newf(hal_pin_dir_t dir, hal_u32_t **data_ptr_addr, int comp_id,
                     const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_pin_s32_newf(hal_pin_dir_t dir, hal_s32_t **data_ptr_addr, int comp_id,
                     const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_pin_u64_newf(hal_pin_dir_t dir, hal_u64_t **data_ptr_addr, int comp_id,
                     const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_pin_s64_newf(hal_pin_dir_t dir, hal_s64_t **data_ptr_addr, int comp_id,
                     const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_pin_newf(hal_type_t type, hal_pin_dir_t dir, void **data_ptr_addr, int comp_id,
                 const char *fmt, ...) __attribute__((format(printf, 5, 6)));

int hal_pin_alias(const char *pin_name, const char *alias);

/* ---- signals ----------------------------------------------------------- */

int hal_signal_new(const char *name, hal_type_t type);
int hal_signal_delete(const char *name);
/* Link obeys the HAL rules: types must match, at most one OUT writer, IO
 * pins only while there is no OUT writer; linking does not copy the pin's
 * old value into the signal. */
int hal_link(const char *pin_name, const char *sig_name);
int hal_unlink(const char *pin_name);

/* ---- parameters -------------------------------------------------------- */

int hal_param_new(const char *name, hal_type_t type, hal_param_dir_t dir,
                  volatile void *data_addr, int comp_id);
int hal_param_bit_new(const char *name, hal_param_dir_t dir, hal_bit_t *data_addr,
                      int comp_id);
int hal_param_float_new(const char *name, hal_param_dir_t dir, hal_float_t *data_addr,
                        int comp_id);
int hal_param_u32_new(const char *name, hal_param_dir_t dir, hal_u32_t *data_addr,
                      int comp_id);
int hal_param_s32_new(const char *name, hal_param_dir_t dir, hal_s32_t *data_addr,
                      int comp_id);
int hal_param_u64_new(const char *name, hal_param_dir_t dir, hal_u64_t *data_addr,
                      int comp_id);
int hal_param_s64_new(const char *name, hal_param_dir_t dir, hal_s64_t *data_addr,
                      int comp_id);

int hal_param_bit_newf(hal_param_dir_t dir, hal_bit_t *data_addr, int comp_id,
                       const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_param_float_newf(hal_param_dir_t dir, hal_float_t *data_addr, int comp_id,
                         const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_param_u32_newf(hal_param_dir_t dir, hal_u32_t *data_addr, int comp_id,
                       const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_param_s32_newf(hal_param_dir_t dir, hal_s32_t *data_addr, int comp_id,
                       const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_param_u64_newf(hal_param_dir_t dir, hal_u64_t *data_addr, int comp_id,
                       const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_param_s64_newf(hal_param_dir_t dir, hal_s64_t *data_addr, int comp_id,
                       const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int hal_param_newf(hal_type_t type, hal_param_dir_t dir, volatile void *data_addr,
                   int comp_id, const char *fmt, ...) __attribute__((format(printf, 5, 6)));

int hal_param_bit_set(const char *name, int value);
int hal_param_float_set(const char *name, double value);
int hal_param_u32_set(const char *name, unsigned long value);
int hal_param_s32_set(const char *name, signed long value);
int hal_param_set(const char *name, hal_type_t type, void *value_addr);
int hal_param_alias(const char *param_name, const char *alias);

/* ---- functions and threads --------------------------------------------- */

/* A realtime function: called as funct(arg, period_ns) from its thread(s).
 * Exporting also creates the parameters/pins NAME.time and NAME.tmax like
 * LinuxCNC 2.9. */
int hal_export_funct(const char *name, void (*funct)(void *, long), void *arg,
                     int uses_fp, int reentrant, int comp_id);
int hal_export_functf(void (*funct)(void *, long), void *arg, int uses_fp,
                      int reentrant, int comp_id, const char *fmt, ...)
    __attribute__((format(printf, 6, 7)));

/* Only inside rtapi_app (the `threads` component uses it). */
int hal_create_thread(const char *name, unsigned long period_nsec, int uses_fp);
int hal_thread_delete(const char *name);
/* position > 0: 1-based from the start; < 0: from the end (-1 = last);
 * 0 is invalid.  Same as halcmd addf. */
int hal_add_funct_to_thread(const char *funct_name, const char *thread_name,
                            int position);
int hal_del_funct_from_thread(const char *funct_name, const char *thread_name);
int hal_start_threads(void);
int hal_stop_threads(void);

/* ---- locking ----------------------------------------------------------- */

#define HAL_LOCK_NONE 0
#define HAL_LOCK_LOAD 1
#define HAL_LOCK_CONFIG 2
#define HAL_LOCK_PARAMS 4
#define HAL_LOCK_RUN 8
#define HAL_LOCK_TUNE (HAL_LOCK_LOAD | HAL_LOCK_CONFIG)
#define HAL_LOCK_ALL 255
int hal_set_lock(unsigned char lock_type);
unsigned char hal_get_lock(void);

/* ---- helpers ----------------------------------------------------------- */

const char *hal_type_name(hal_type_t type);       /* "bit", "float", ... */
const char *hal_pin_dir_name(hal_pin_dir_t dir);  /* "IN", "OUT", "I/O" */
const char *hal_param_dir_name(hal_param_dir_t dir); /* "RO", "RW" */

#ifdef __cplusplus
}
#endif

#endif /* HM_HAL_H */
