/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * haltcl.h - HAL in a Tcl interpreter (see docs/haltcl.md): the `hal`
 * command and the halcmd commands as Tcl commands (haltcl_hal.c), INI
 * files as global arrays (haltcl_ini.c), and where an error happened.
 */
#ifndef HM_HALTCL_H
#define HM_HALTCL_H

#include <tcl.h>

/* Create `hal`, the halcmd commands that do not collide with Tcl's own
 * (list, gets and source stay Tcl's; `hal list`, `hal gets`, `hal source`
 * reach HAL's), setp/sets that take an expression, and provide the
 * package Hal.  The HAL session must be attached and halcmd's component
 * registered (hc.comp_id) before a command runs. */
int haltcl_hal_init(Tcl_Interp *interp);

/* One global array per INI section, one element per key; the element is
 * the Tcl list of the key's values (a key may repeat).  TCL_ERROR with a
 * message when the file cannot be read. */
int haltcl_ini_arrays(Tcl_Interp *interp, const char *path);

/* The file locations of the commands being run, innermost first, as a
 * list of {file line} pairs (frames of code read from no file are
 * skipped).  File names under the working directory are made relative. */
Tcl_Obj *haltcl_location(Tcl_Interp *interp);

/* PATH relative to the working directory DIR when it is inside it. */
const char *haltcl_relative(const char *path, const char *dir);

#endif /* HM_HALTCL_H */
