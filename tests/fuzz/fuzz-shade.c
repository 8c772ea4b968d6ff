/*
 * libFuzzer harness for the shading pass's own reads: the input's bytes
 * are a few option bits and then the floats of a row of every channel
 * the pass reads (P, N, V, the material, mask, emission, D, the
 * effective roughness, a mode's radiance: any bit pattern), shaded with
 * --final and the diffuse light or without, under each --invalid.  With
 * clamp and zero the row must be taken; with error it is taken or
 * refused with a printable message; whatever is taken must be finite in
 * every channel the pass writes, and the vector and plain reads must
 * agree (as fuzz-numeric.c asks of D alone).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/envmap.h"
#include "reflect/plugin.h"
#include "reflect/reflect.h"
#include "reflect/shading.h"

#define HARNESS "fuzz-shade"
#include "harness.h"

#define NCOLS_MAX 32
#define OPTION_BYTES 4
#define CHANNELS 25

static const char *const channels[CHANNELS] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z",
	"roughness", "metallic", "albedo.R", "albedo.G", "albedo.B", "mask",
	"emission.R", "emission.G", "emission.B", "D.X", "D.Y", "D.Z",
	RF_SHADE_ROUGHNESS, RF_SHADE_SPEC_R, RF_SHADE_SPEC_G, RF_SHADE_SPEC_B
};

struct run {
	float *px;     /* the output row, or NULL when the row was refused */
	size_t ncomp;
	int col[16];   /* the channels the pass writes, -1 after the last */
};

/* The row shaded with the options of the first bytes, with or without
 * the vector reads. */
static struct run
shade(const uint8_t *opt, const rf_header *in, const float *row, size_t ncols,
      const float *sh, int vector)
{
	const struct rf_probe probe = { { 0, 1.5f, 0 }, { -3, 0, -2 }, { 3, 3, 2 }, 1, 0.0f, 0 };
	const float center[3] = { 0, 1.5f, 0 };
	struct rf_shade_options o;
	enum rf_invalid policy = (enum rf_invalid)(opt[1] % 3);
	struct run r = { NULL, 0, { -1 } };
	char err[512];
	rf_header *out;
	rf_shade *s;
	const char *msg;
	size_t i;
	int rc;

	if (vector)
		unsetenv("REFLECT_SIMD");
	else
		setenv("REFLECT_SIMD", "off", 1);
	memset(&o, 0, sizeof(o));
	o.final = opt[0] % 4;
	o.nthreads = 1;
	o.mode_radiance = (opt[2] & 1) != 0;
	o.diffuse = (opt[2] & 2) != 0;
	o.diffuse_box = (opt[2] & 4) != 0;
	o.force_lod = (opt[2] & 8) != 0;
	o.lod = (float)(opt[3] % 5);
	check(rf_shade_create(&s, &o) == 0, "shade_create");
	rf_shade_set_invalid(s, policy);
	rf_shade_set_probe(s, (opt[2] & 16) ? &probe : NULL);
	if (rf_shade_begin_frame(s, in, center, &out, err, sizeof(err)) < 0) {
		rf_shade_destroy(s);
		return r;
	}
	check(rf_shade_set_environment(s, environment(), RF_MAPPING_LINEAR, 3.0f) == 0,
	      "set_environment");
	if (sh)
		rf_shade_set_irradiance(s, sh);
	r.ncomp = rf_header_nchannels(out);
	for (i = 0; i < 15 && rf_shade_channel(s, i); i++)
		r.col[i] = rf_header_find_channel(out, rf_shade_channel(s, i));
	r.col[i] = -1;
	check((r.px = calloc(ncols * r.ncomp, sizeof(float))) != NULL, "calloc");
	rc = rf_shade_run(s, row, r.px, 1);
	if (rc < 0) {
		check(policy == RF_INVALID_ERROR && rc == RF_EINVAL,
		      "a row refused under clamp or zero");
		msg = rf_shade_error(s);
		check(msg[0] != '\0', "an invalid pixel without a message");
		for (i = 0; msg[i]; i++)
			check((unsigned char)msg[i] >= 0x20 && msg[i] != 0x7f,
			      "a control character in a message");
		free(r.px);
		r.px = NULL;
	}
	rf_shade_destroy(s);
	return r;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	size_t ncols, c, x;
	const float *sh = NULL;
	float shv[27], *row;
	rf_header *in;
	struct run a, b;

	if (size < OPTION_BYTES + CHANNELS * sizeof(float))
		return 0;
	ncols = (size - OPTION_BYTES) / (CHANNELS * sizeof(float));
	if (ncols > NCOLS_MAX)
		ncols = NCOLS_MAX;
	check((row = malloc(ncols * CHANNELS * sizeof(float))) != NULL, "malloc");
	memcpy(row, data + OPTION_BYTES, ncols * CHANNELS * sizeof(float));
	/* the irradiance given, as a chain's key gives it, from the last
	 * floats when there are enough after the row */
	if ((data[2] & 32) && size >= OPTION_BYTES + (ncols * CHANNELS + 27) * sizeof(float)) {
		memcpy(shv, data + OPTION_BYTES + ncols * CHANNELS * sizeof(float), sizeof(shv));
		sh = shv;
	}
	check(rf_header_create(&in) == 0, "header_create");
	rf_header_set_size(in, ncols, 1);
	for (c = 0; c < CHANNELS; c++)
		check(rf_header_add_channel(in, channels[c]) >= 0, "add_channel");
	a = shade(data, in, row, ncols, sh, 1);
	b = shade(data, in, row, ncols, sh, 0);
	check((a.px == NULL) == (b.px == NULL), "one path took the row, the other not");
	if (a.px) {
		check(a.ncomp == b.ncomp, "the paths write different channels");
		for (x = 0; x < ncols; x++)
			for (c = 0; a.col[c] >= 0; c++) {
				float u = a.px[x * a.ncomp + (size_t)a.col[c]];
				float v = b.px[x * b.ncomp + (size_t)a.col[c]];

				check(isfinite(u) && isfinite(v), "an output that is not finite");
				check(fabsf(u - v) <= 1e-3f * (1.0f + fabsf(v)),
				      "the vector and plain reads disagree");
			}
	}
	free(a.px);
	free(b.px);
	free(row);
	rf_header_destroy(in);
	return 0;
}
