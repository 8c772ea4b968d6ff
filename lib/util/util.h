/* Internal to libreflect, for every area: nothing here is installed. */
#ifndef REFLECT_UTIL_H
#define REFLECT_UTIL_H

#include <stdarg.h>
#include <stddef.h>

#include "reflect/reflect.h"

#if defined(__GNUC__)
#define RF__PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define RF__PRINTF(a, b)
/* The index of the name among names[n] that word most likely misspells
 * (a few edits away, the fewest; not word itself), or -1. */
int rf__closest(const char *word, const char *const *names, size_t n);

#endif

/* Writes a message into buf: one printable line whatever its arguments
 * quote (a header value's tab, a file's bytes), each control byte as
 * '?'; always terminated, silently truncated.  Text that is not a
 * message (a path, header lines) is made with snprintf. */
void rf__format(char *buf, size_t size, const char *fmt, ...) RF__PRINTF(3, 4);

/* Replaces each control byte of s by '?', as rf__format does. */
void rf__printable(char *s);

/* x * y * z without overflow; 0 and *out set on success. */
int rf__mul3(size_t x, size_t y, size_t z, size_t *out);

/* Big buffers (megabytes: cube levels, RGBA levels): on 2 MB pages where
 * the system allows, as faulting in and clearing 4 KB pages one by one
 * cost a stage a third of its start-up.  Free with free(). */
void *rf__alloc_big(size_t bytes, int zero);

/* RF_EINVAL with "cannot open 'path': not a regular file (a FIFO)" when
 * path exists and is no regular file; 0 otherwise (lib/util/file.c says
 * why decoders see only files). */
int rf__regular_file(const char *path, char *err, size_t errlen);
/* n finite numbers separated by spaces (or commas after the first) and
 * nothing else (n at most 32 for floats, each finite as a float too:
 * within +-FLT_MAX); 0, or -1. */
int rf__scan_doubles(const char *s, double *out, int n);
int rf__scan_floats(const char *s, float *out, int n);
/* What a file of this st_mode is, for messages: "a directory", "a FIFO"... */
const char *rf__file_kind(unsigned mode);

/* The index of the name among names[n] that word most likely misspells
 * (a few edits away, the fewest; not word itself), or -1. */
int rf__closest(const char *word, const char *const *names, size_t n);

#endif
