/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * haltcl_hal.c - the HAL commands of haltcl (docs/haltcl.md): `hal CMD
 * ARGS...` runs halcmd's command CMD (host/hal/halcmd) in this process;
 * its output becomes the Tcl result, its error message the Tcl error
 * (with errorCode {HAL LOCATIONS}).  Each command that Tcl does not have
 * is also a Tcl command of its own; setp and sets take their value as a
 * Tcl expression.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "halcmd.h"
#include "haltcl.h"

typedef struct {
    const char *name;
    int prints; /* as a Tcl command of its own: print the output, return "" */
} tcl_cmd_t;

/* halcmd's commands that make sense in a script (not exit/quit: Tcl's
 * exit ends haltcl).  list, gets and source are Tcl's own commands; HAL's
 * are `hal list`, `hal gets`, `hal source`. */
static const tcl_cmd_t hal_cmds[] = {
    {"addf", 0},     {"alias", 0},    {"debug", 1},    {"delf", 0},
    {"delsig", 0},   {"echo", 0},     {"getp", 0},     {"gets", 0},
    {"help", 1},     {"linkpp", 0},   {"linkps", 0},   {"linksp", 0},
    {"list", 0},     {"loadrt", 0},   {"loadusr", 0},  {"lock", 0},
    {"net", 0},      {"newsig", 0},   {"print", 1},    {"ptype", 0},
    {"save", 1},     {"setexact_for_test_suite_only", 0},
    {"setp", 0},     {"sets", 0},     {"show", 1},     {"simrun", 0},
    {"source", 0},   {"start", 0},    {"status", 1},   {"stop", 0},
    {"stype", 0},    {"unalias", 0},  {"unecho", 0},   {"unlinkp", 0},
    {"unload", 0},   {"unloadrt", 0}, {"unloadusr", 0}, {"unlock", 0},
    {"waitusr", 0},
};
#define NCMDS ((int)(sizeof(hal_cmds) / sizeof(hal_cmds[0])))

/* Tcl commands of the same name that stay Tcl's. */
static int tcl_keeps(const char *name)
{
    return strcmp(name, "list") == 0 || strcmp(name, "gets") == 0 ||
           strcmp(name, "source") == 0;
}

static const tcl_cmd_t *find_cmd(const char *name)
{
    for (int i = 0; i < NCMDS; i++)
        if (strcmp(hal_cmds[i].name, name) == 0)
            return &hal_cmds[i];
    return NULL;
}

/* ---- where we are ------------------------------------------------------------ */

const char *haltcl_relative(const char *path, const char *cwd)
{
    size_t n = strlen(cwd);
    if (n > 1 && strncmp(path, cwd, n) == 0 && path[n] == '/')
        return path + n + 1;
    return path;
}

static int frame_location(Tcl_Interp *interp, int level, Tcl_Obj **file, int *line)
{
    char cmd[64];
    snprintf(cmd, sizeof(cmd), "info frame %d", level);
    if (Tcl_Eval(interp, cmd) != TCL_OK)
        return 0;
    Tcl_Obj *dict = Tcl_GetObjResult(interp), *key, *f = NULL, *l = NULL;
    key = Tcl_NewStringObj("file", -1);
    Tcl_IncrRefCount(key);
    int ok = Tcl_DictObjGet(interp, dict, key, &f) == TCL_OK && f != NULL;
    Tcl_SetStringObj(key, "line", -1);
    ok = ok && Tcl_DictObjGet(interp, dict, key, &l) == TCL_OK && l != NULL &&
         Tcl_GetIntFromObj(NULL, l, line) == TCL_OK;
    Tcl_DecrRefCount(key);
    if (ok) {
        *file = f;
        Tcl_IncrRefCount(f);
    }
    return ok;
}

Tcl_Obj *haltcl_location(Tcl_Interp *interp)
{
    Tcl_Obj *saved = Tcl_GetObjResult(interp);
    Tcl_IncrRefCount(saved);
    Tcl_Obj *out = Tcl_NewListObj(0, NULL);
    int n = 0;
    char cwd[4096];
    if (getcwd(cwd, sizeof(cwd)) == NULL)
        cwd[0] = '\0';
    if (Tcl_Eval(interp, "info frame") == TCL_OK &&
        Tcl_GetIntFromObj(NULL, Tcl_GetObjResult(interp), &n) == TCL_OK) {
        char last_file[4096] = "";
        int last_line = -1;
        for (int k = n; k >= 1; k--) {
            Tcl_Obj *file;
            int line;
            if (!frame_location(interp, k, &file, &line))
                continue;
            const char *name = haltcl_relative(Tcl_GetString(file), cwd);
            if (line != last_line || strcmp(name, last_file) != 0) {
                Tcl_Obj *pair[2] = {Tcl_NewStringObj(name, -1), Tcl_NewIntObj(line)};
                Tcl_ListObjAppendElement(NULL, out, Tcl_NewListObj(2, pair));
                snprintf(last_file, sizeof(last_file), "%s", name);
                last_line = line;
            }
            Tcl_DecrRefCount(file);
        }
    }
    Tcl_SetObjResult(interp, saved);
    Tcl_DecrRefCount(saved);
    return out;
}

/* ---- running a halcmd command ------------------------------------------------ */

static void chomp(char *s, size_t *len)
{
    if (*len > 0 && s[*len - 1] == '\n')
        s[--*len] = '\0';
}

/* Warnings a successful command printed (print, a deprecated form):
 * shown on stderr with the script's location. */
static void warn(Tcl_Interp *interp, const char *text)
{
    Tcl_Obj *loc = haltcl_location(interp), *first = NULL;
    Tcl_IncrRefCount(loc);
    Tcl_ListObjIndex(NULL, loc, 0, &first);
    fflush(stdout);
    if (first != NULL) {
        Tcl_Obj *f, *l;
        Tcl_ListObjIndex(NULL, first, 0, &f);
        Tcl_ListObjIndex(NULL, first, 1, &l);
        fprintf(stderr, "%s:%s: ", Tcl_GetString(f), Tcl_GetString(l));
    }
    fputs(text, stderr);
    fflush(stderr);
    Tcl_DecrRefCount(loc);
}

/* Run halcmd's command NAME with the arguments objv[1..objc-1] (objv[0],
 * the Tcl command's name, may differ: a renamed command). */
static int run_halcmd(Tcl_Interp *interp, const char *name, int objc, Tcl_Obj *const objv[],
                      int prints)
{
    char **argv = calloc((size_t)objc + 1, sizeof(char *));
    char *obuf = NULL, *ebuf = NULL;
    size_t olen = 0, elen = 0;
    FILE *o = NULL, *e = NULL;
    int rc = -1;
    if (argv == NULL)
        goto nomem;
    for (int i = 0; i < objc; i++)
        if ((argv[i] = strdup(i == 0 ? name : Tcl_GetString(objv[i]))) == NULL)
            goto nomem;
    o = open_memstream(&obuf, &olen);
    e = open_memstream(&ebuf, &elen);
    if (o == NULL || e == NULL)
        goto nomem;

    FILE *saved_out = hc.out, *saved_err = hc.err;
    const char *saved_file = hc.filename;
    int saved_line = hc.linenum;
    hc.out = o;
    hc.err = e;
    hc.filename = NULL;
    hc.linenum = 0;
    fflush(stdout);
    rc = halcmd_dispatch(objc, argv);
    hc.out = saved_out;
    hc.err = saved_err;
    hc.filename = saved_file;
    hc.linenum = saved_line;
    fclose(o);
    fclose(e);
    o = e = NULL;

    if (rc == 0) {
        if (elen > 0)
            warn(interp, ebuf);
        if (prints) {
            fwrite(obuf, 1, olen, stdout);
            fflush(stdout);
            Tcl_ResetResult(interp);
        } else {
            chomp(obuf, &olen);
            Tcl_SetObjResult(interp, Tcl_NewStringObj(obuf, (int)olen));
        }
    } else {
        if (olen > 0) {
            fwrite(obuf, 1, olen, stdout);
            fflush(stdout);
        }
        chomp(ebuf, &elen);
        Tcl_Obj *msg = elen > 0 ? Tcl_NewStringObj(ebuf, (int)elen)
                                : Tcl_ObjPrintf("%s failed", argv[0]);
        Tcl_IncrRefCount(msg);
        Tcl_Obj *code[2] = {Tcl_NewStringObj("HAL", -1), haltcl_location(interp)};
        Tcl_SetObjErrorCode(interp, Tcl_NewListObj(2, code));
        Tcl_SetObjResult(interp, msg);
        Tcl_DecrRefCount(msg);
    }
    goto done;
nomem:
    Tcl_SetObjResult(interp, Tcl_NewStringObj("haltcl: out of memory", -1));
    if (o != NULL)
        fclose(o);
    if (e != NULL)
        fclose(e);
done:
    if (argv != NULL)
        for (int i = 0; i < objc; i++)
            free(argv[i]);
    free(argv);
    free(obuf);
    free(ebuf);
    return rc == 0 ? TCL_OK : TCL_ERROR;
}

static int unknown_command(Tcl_Interp *interp, const char *name)
{
    Tcl_SetObjResult(interp, Tcl_ObjPrintf("Unknown command '%s'", name));
    Tcl_Obj *code[2] = {Tcl_NewStringObj("HAL", -1), haltcl_location(interp)};
    Tcl_SetObjErrorCode(interp, Tcl_NewListObj(2, code));
    return TCL_ERROR;
}

/* hal CMD ARGS... ; hal --commands */
static int hal_objcmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)cd;
    if (objc < 2) {
        Tcl_WrongNumArgs(interp, 1, objv, "command ...");
        return TCL_ERROR;
    }
    const char *name = Tcl_GetString(objv[1]);
    if (strcmp(name, "--commands") == 0) {
        Tcl_Obj *l = Tcl_NewListObj(0, NULL);
        for (int i = 0; i < NCMDS; i++)
            Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(hal_cmds[i].name, -1));
        Tcl_SetObjResult(interp, l);
        return TCL_OK;
    }
    if (find_cmd(name) == NULL)
        return unknown_command(interp, name);
    return run_halcmd(interp, name, objc - 1, objv + 1, 0);
}

/* A halcmd command as a Tcl command of its own. */
static int forward_objcmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const tcl_cmd_t *c = cd;
    return run_halcmd(interp, c->name, objc, objv, c->prints);
}

/* setp NAME VALUE, sets NAME VALUE: VALUE is a Tcl expression, evaluated
 * in the caller's scope ("6.28/360*$::JOINT_0(SCALE)"). */
static int set_objcmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const tcl_cmd_t *c = cd;
    if (objc != 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "name value");
        return TCL_ERROR;
    }
    Tcl_Obj *value;
    if (Tcl_ExprObj(interp, objv[2], &value) != TCL_OK)
        return TCL_ERROR;
    Tcl_Obj *args[3] = {objv[0], objv[1], value};
    int rc = run_halcmd(interp, c->name, 3, args, 0);
    Tcl_DecrRefCount(value);
    return rc;
}

int haltcl_hal_init(Tcl_Interp *interp)
{
    Tcl_CreateObjCommand(interp, "hal", hal_objcmd, NULL, NULL);
    for (int i = 0; i < NCMDS; i++) {
        const tcl_cmd_t *c = &hal_cmds[i];
        if (tcl_keeps(c->name))
            continue;
        if (strcmp(c->name, "setp") == 0 || strcmp(c->name, "sets") == 0)
            Tcl_CreateObjCommand(interp, c->name, set_objcmd, (ClientData)c, NULL);
        else
            Tcl_CreateObjCommand(interp, c->name, forward_objcmd, (ClientData)c, NULL);
    }
    return Tcl_PkgProvide(interp, "Hal", "1.0");
}
