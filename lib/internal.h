/* Internal to libreflect: nothing here is installed. */
#ifndef REFLECT_INTERNAL_H
#define REFLECT_INTERNAL_H

#include <stdarg.h>

#include "reflect/reflect.h"

#if defined(__GNUC__)
#define RF__PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define RF__PRINTF(a, b)
#endif

/* Header fields the reader fills while parsing. */
void rf__header_set_format(rf_header *h, enum rf_format format, int big_endian);
/* Adds a stored line as read, without the checks rf_header_set makes. */
int rf__header_push_line(rf_header *h, const char *line);
/* 1 when the key is one the writer makes from the header's fields. */
int rf__header_key_reserved(const char *key, size_t len);

/* Writes a message into buf; always terminated, silently truncated. */
void rf__format(char *buf, size_t size, const char *fmt, ...) RF__PRINTF(3, 4);

/* Big buffers (megabytes: cube levels, pyramids): on 2 MB pages where
 * the system allows, as faulting in and clearing 4 KB pages one by one
 * cost a stage a third of its start-up.  Free with free(). */
void *rf__alloc_big(size_t bytes, int zero);

/* RF_EINVAL with "cannot open 'path': not a regular file (a FIFO)" when
 * path exists and is no regular file; 0 otherwise (lib/file.c says why
 * decoders see only files). */
int rf__regular_file(const char *path, char *err, size_t errlen);

/* x * y * z without overflow; 0 and *out set on success. */
int rf__mul3(size_t x, size_t y, size_t z, size_t *out);

/* A face of a cube level with its one-texel border: (n + 2)^2 RGB
 * texels, rows top first, starting at border texel (-1, -1). */
struct rf_cubemap;
/* Fills level k of a cube from an N x 6N image of that level's size,
 * texel for texel (first 3 channels; non-finite values become 0 and are
 * counted). */
int rf__cube_level_from_pixels(struct rf_cubemap *c, size_t level, const float *px,
                               size_t w, size_t h, size_t nch, size_t *nonfinite,
                               char *err, size_t errlen);
const float *rf__cubemap_padded_face(const struct rf_cubemap *c, size_t level,
                                     int face);

/* A stage's parts for a pass that runs it row by row on its own threads
 * (the shading pass): the frame's row layout once rf_stage_run could run
 * rows y..y+nrows, its thread count, and one row on thread `thread`. */
struct rf_stage;
int rf__stage_ready(const struct rf_stage *s, size_t y, size_t nrows, size_t *in_ncomp,
                    size_t *out_ncomp);
int rf__stage_threads(const struct rf_stage *s);
void rf__stage_row(struct rf_stage *s, const float *in, float *out, size_t y, int thread);
/* Around a block of rf__stage_row calls: the invalid input they met
 * counted, and RF_EINVAL (rf_stage_error) for the first under ERROR. */
void rf__stage_block_begin(struct rf_stage *s);
int rf__stage_block_end(struct rf_stage *s);

#endif
