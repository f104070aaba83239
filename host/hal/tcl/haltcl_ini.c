/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * haltcl_ini.c - an INI file as Tcl global arrays, the way LinuxCNC's
 * haltcl makes them: [SECTION] KEY = VALUE becomes the element
 * ::SECTION(KEY), a Tcl list of every VALUE the key has (in file order).
 * Lines starting with '#' or ';' are comments; keys and values are
 * trimmed; a value keeps everything after the first '=' (a trailing
 * "# ..." included, as LinuxCNC's haltcl keeps it).
 */
#define _GNU_SOURCE
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "haltcl.h"

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        s[--n] = '\0';
    return s;
}

static int append_value(Tcl_Interp *interp, const char *section, const char *key,
                        const char *value)
{
    Tcl_Obj *cur = Tcl_GetVar2Ex(interp, section, key, TCL_GLOBAL_ONLY);
    Tcl_Obj *list = cur == NULL ? Tcl_NewListObj(0, NULL)
                    : Tcl_IsShared(cur) ? Tcl_DuplicateObj(cur)
                                        : cur;
    if (Tcl_ListObjAppendElement(interp, list, Tcl_NewStringObj(value, -1)) != TCL_OK)
        return TCL_ERROR;
    if (Tcl_SetVar2Ex(interp, section, key, list, TCL_GLOBAL_ONLY | TCL_LEAVE_ERR_MSG) == NULL)
        return TCL_ERROR;
    return TCL_OK;
}

/* One line: a section header changes `section`; KEY = VALUE is stored. */
static int ini_line(Tcl_Interp *interp, char *line, char **section)
{
    char *s = trim(line);
    if (*s == '\0' || *s == '#' || *s == ';')
        return TCL_OK;
    size_t n = strlen(s);
    if (s[0] == '[' && s[n - 1] == ']') {
        s[n - 1] = '\0';
        free(*section);
        *section = strdup(trim(s + 1));
        return *section != NULL ? TCL_OK : TCL_ERROR;
    }
    char *eq = strchr(s, '=');
    if (eq == NULL || *section == NULL || **section == '\0')
        return TCL_OK;
    *eq = '\0';
    char *key = trim(s);
    if (*key == '\0' || strchr(key, '#') != NULL)
        return TCL_OK;
    return append_value(interp, *section, key, trim(eq + 1));
}

int haltcl_ini_arrays(Tcl_Interp *interp, const char *path)
{
    FILE *f = fopen(path, "re");
    if (f == NULL) {
        Tcl_SetObjResult(interp, Tcl_ObjPrintf("cannot read INI file '%s': %s", path,
                                               strerror(errno)));
        return TCL_ERROR;
    }
    char *line = NULL, *section = NULL;
    size_t cap = 0;
    int rc = TCL_OK;
    while (rc == TCL_OK && getline(&line, &cap, f) >= 0)
        rc = ini_line(interp, line, &section);
    if (rc == TCL_OK && ferror(f)) {
        Tcl_SetObjResult(interp, Tcl_ObjPrintf("cannot read INI file '%s': %s", path,
                                               strerror(errno)));
        rc = TCL_ERROR;
    }
    free(line);
    free(section);
    fclose(f);
    return rc;
}
