/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_parse.h - halcmd's input handling, kept free of HAL so it can be
 * unit-tested and fuzzed on its own: reading logical lines from a file
 * (backslash continuation, bounded length), comments, substitution of
 * environment and INI variables, and tokenizing.
 */
#ifndef HM_HALCMD_PARSE_H
#define HM_HALCMD_PARSE_H

#include <stddef.h>
#include <stdio.h>

#define HALCMD_MAX_TOKENS 1024
/* Longest logical line (after joining continued lines), in bytes
 * including the terminating NUL. */
#define HALCMD_MAX_LINE 65536

/* Looks up KEY in SECTION of the INI file (SECTION "" = any section);
 * returns a malloc'd value or NULL. */
typedef char *(*halcmd_ini_lookup_fn)(const char *section, const char *key, void *ctx);

/* Read the next logical line from `f` into `buf` (NUL-terminated, at most
 * buflen-1 bytes): a line ending in a backslash continues on the next one,
 * joined with nothing in between (LinuxCNC's rule: `names=a\` + `,b` is
 * `names=a,b`).  The line end (LF or CR LF) is dropped.  *linenum counts
 * physical lines and ends on the last line read.
 * Returns 1 (a line), 0 (end of file) or -1 with a message in err: the line
 * is too long, contains a NUL byte (not a text file), or reading failed.
 * After -1 the rest of the file is not usable. */
int halcmd_read_line(FILE *f, char *buf, size_t buflen, int *linenum, char *err, size_t errlen);

/* Expand one logical line: strip the comment ('#' outside quotes), replace
 * $NAME and $(NAME) with environment variables and [SECTION]KEY and
 * [SECTION](KEY) with INI values.  NAME and the KEY of the first INI form
 * are letters, digits, '_', '-' and '.'; [](KEY) and []KEY search every
 * section.  `out` receives the result (NUL-terminated, at most outlen-1
 * chars).  Returns 0, or -1 with a message in err (LinuxCNC 2.9's
 * wording: "Empty variable name.", "Environment variable 'X' not
 * found.", "Ini variable '[S]K' not found.", ...). */
int halcmd_preprocess(const char *line, char *out, size_t outlen, halcmd_ini_lookup_fn ini,
                      void *ini_ctx, char *err, size_t errlen);

/* Split on blanks; single or double quotes group blanks into one token and
 * are kept (as LinuxCNC does).  Tokens point into `line`, which is
 * modified.  Returns the number of tokens, or -1 (too many tokens /
 * unbalanced quote) with a message in err. */
int halcmd_tokenize(char *line, char **tokens, int max, char *err, size_t errlen);

/* A simple INI reader: returns the malloc'd value of KEY in SECTION
 * (SECTION "" = the first KEY in any section), trimmed, or NULL. */
char *halcmd_ini_get(const char *path, const char *section, const char *key);

#endif /* HM_HALCMD_PARSE_H */
