/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_lib_int.h - what the parts of libhal's object code (hal_objects.c,
 * hal_comp.c, hal_signal.c, hal_pin_param.c, hal_thread.c) share.  Hidden:
 * nothing here is exported from libhal.so.  Functions named *_locked
 * expect the HAL mutex held.
 *
 * The rule of every public function of these files: take the mutex, check
 * everything needed before changing anything (a failed call changes
 * nothing), and print one "HAL: ERROR: ..." line that names the object and
 * the reason, in LinuxCNC 2.9's wording where it has one.
 */
#ifndef HM_HAL_LIB_INT_H
#define HM_HAL_LIB_INT_H

#include <stdarg.h>
#include <stddef.h>

#include "hal_priv.h"

#pragma GCC visibility push(hidden)

#define ERR(...) rtapi_print_msg(RTAPI_MSG_ERR, __VA_ARGS__)

/* rtapi_app's thread hooks (hal_priv_set_thread_hooks), or NULL. */
extern const hal_thread_hooks_t *hal_thread_hooks;

/* ---- hal_objects.c: memory, lists, names ---- */
/* An object from its free list or carved from the bottom (zeroed). */
void *alloc_obj(size_t size, hal_off_t *free_list, int *recycled);
void free_obj(void *p, hal_off_t *free_list, int *recycled);
/* hal_malloc memory, carved from the top (zeroed), never freed. */
void *shmalloc_dn(size_t size);
/* Lists per kind (HAL_IDX_*) in show order, with their name index. */
void list_insert_sorted(int kind, void *obj);
void list_insert_front(int kind, void *obj);
void list_remove(int kind, void *obj);
void list_remove_at(int kind, hal_off_t *prev, void *obj);
int check_name(const char *what, const char *name);
int name_in_use_pin(const char *name);
int valid_type(int type);
/* Format an object name into buf (HAL_NAME_LEN + 1 bytes). */
int vformat_name(char *buf, const char *what, const char *fmt, va_list ap);

/* ---- hal_comp.c ---- */
int comp_create_locked(const char *name, int type, int ready);
void comp_delete_locked(hal_comp_t *c);
void funct_delete_locked(hal_funct_t *f);

/* ---- hal_signal.c ---- */
/* Point the pin's owner variable at target (as the owner maps it). */
void set_pin_ptr(hal_pin_t *pin, hal_data_u *target);
void unlink_pin_locked(hal_pin_t *pin);

/* ---- hal_pin_param.c ---- */
hal_comp_t *comp_for_new_object(int comp_id, const char *what, const char *name);
int pin_new_locked(const char *name, hal_type_t type, hal_pin_dir_t dir, void **data_ptr_addr,
                   int comp_id);
int param_new_locked(const char *name, hal_type_t type, hal_param_dir_t dir,
                     volatile void *data_addr, int comp_id);

/* ---- hal_q_values.c ---- */
/* Copy a value of `type` between HAL storage and a hal_data_u. */
void read_typed(hal_type_t type, const volatile void *src, hal_data_u *out);
void write_typed(hal_type_t type, volatile void *dst, const hal_data_u *in);

#pragma GCC visibility pop

#endif /* HM_HAL_LIB_INT_H */
