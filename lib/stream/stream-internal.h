/* Internal to the stream area: how the reader fills a header. */
#ifndef REFLECT_STREAM_INTERNAL_H
#define REFLECT_STREAM_INTERNAL_H

#include "util/util.h"

/* Header fields the reader fills while parsing. */
void rf__header_set_format(rf_header *h, enum rf_format format, int big_endian);
/* Adds a stored line as read, without the checks rf_header_set makes. */
int rf__header_push_line(rf_header *h, const char *line);
/* 1 when the key is one the writer makes from the header's fields. */
int rf__header_key_reserved(const char *key, size_t len);

#endif
