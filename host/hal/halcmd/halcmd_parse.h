/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_parse.h - halcmd's line preprocessing and tokenizing, kept free of
 * HAL so it can be unit-tested and fuzzed on its own.
 */
#ifndef HM_HALCMD_PARSE_H
#define HM_HALCMD_PARSE_H

#include <stddef.h>

#define HALCMD_MAX_TOKENS 1024
#define HALCMD_MAX_LINE 65536

/* Looks up [section]key in the INI file; returns a malloc'd value or NULL. */
typedef char *(*halcmd_ini_lookup_fn)(const char *section, const char *key, void *ctx);

/* Expand one logical line in place: strip the '#' comment, replace $NAME,
 * $(NAME) with environment variables and [SECTION]KEY with INI values.
 * `out` receives the result (NUL-terminated, at most outlen-1 chars).
 * Returns 0, or -1 with a message in err (LinuxCNC's wording). */
int halcmd_preprocess(const char *line, char *out, size_t outlen, halcmd_ini_lookup_fn ini,
                      void *ini_ctx, char *err, size_t errlen);

/* Split on blanks; double quotes group blanks into one token and are kept
 * (as LinuxCNC does).  Tokens point into `line`, which is modified.
 * Returns the number of tokens, or -1 (too many tokens / unbalanced
 * quote) with a message in err. */
int halcmd_tokenize(char *line, char **tokens, int max, char *err, size_t errlen);

/* A simple INI reader: returns malloc'd value of [section]key (first
 * match, trimmed), or NULL. */
char *halcmd_ini_get(const char *path, const char *section, const char *key);

#endif /* HM_HALCMD_PARSE_H */
