/* Internal to the stream area: how the reader fills a header. */
#ifndef REFLECT_STREAM_INTERNAL_H
#define REFLECT_STREAM_INTERNAL_H

#include "util/util.h"

/* The first line of every frame: the magic string and the format's
 * version, as the writer writes them and the reader expects them. */
#define RF__STREAM_MAGIC "#?REFLECT"
#define RF__STREAM_VERSION 1
#define RF__STREAM_IDENT RF__STREAM_MAGIC "1"

/* Header fields the reader fills while parsing. */
void rf__header_set_format(rf_header *h, enum rf_format format, int big_endian);
/* Adds a stored line as read, without the checks rf_header_set makes. */
int rf__header_push_line(rf_header *h, const char *line);
/* 1 when the key is one the writer makes from the header's fields. */
int rf__header_key_reserved(const char *key, size_t len);

/* n numbers as "%.9g %.9g ..." (keys.c). */
int rf__header_set_numbers(rf_header *h, const char *key, const double *v, size_t n);

#endif
