/*
 * libreflect: turning another renderer's passes into a G-buffer stream.
 */
#ifndef REFLECT_IMPORT_H
#define REFLECT_IMPORT_H

#include "reflect/reflect.h"

#ifdef __cplusplus
extern "C" {
#endif

enum rf_import_preset {
	RF_IMPORT_NONE = 0,
	RF_IMPORT_BLENDER = 1 /* Cycles and EEVEE pass names, any view layer */
};

/* Output channel `out` taken from input channel `in`: a channel name, or
 * FILE:NAME where FILE is a path as given, its base name or its index
 * (0 for the first file). */
struct rf_import_map {
	const char *out;
	const char *in;
};

struct rf_import_options {
	const struct rf_import_map *maps;
	size_t nmaps;
	enum rf_import_preset preset;
	int z_up;            /* 1: the passes have Z up; turned to reflect's Y up */
	const float *camera; /* camera position (in the passes' axes): derives V */
	const char *roughness; /* a number (constant) or an input channel */
};

typedef struct rf_import rf_import;

/* Builds the mapping for n images of one size.  Output channels: the -c
 * maps in order, then the preset's channels found in the input, then
 * every other input channel under its own name (names found in several
 * images are left out unless mapped), then V from the camera when no V
 * is given, then a constant roughness when asked for. */
RF_EXTERN int rf_import_create(rf_import **im, const rf_image *const *images,
                            const char *const *paths, size_t n,
                            const struct rf_import_options *o, char *err,
                            size_t errlen);
RF_EXTERN void rf_import_destroy(rf_import *im);
/* The output frame's header: size and channels. */
RF_EXTERN const rf_header *rf_import_header(const rf_import *im);
/* Rows y .. y+n-1 of the output, channels interleaved. */
RF_EXTERN void rf_import_rows(const rf_import *im, size_t y, size_t n,
                              float *out);

#ifdef __cplusplus
}
#endif

#endif
