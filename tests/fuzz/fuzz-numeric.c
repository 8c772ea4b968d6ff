/*
 * libFuzzer harness for the numeric path: the input's bytes are the
 * floats of a G-buffer row (P, N, V and roughness: any bit pattern, so
 * NaN, infinities, denormals and zero vectors come often) through the box
 * projection plugin and then the shading pass, once with the vector
 * reads and once with the plain ones.  The shaded radiance must be
 * finite, and the two paths must agree (both under --invalid=clamp, as
 * the projection is after it was run under error, where a refusal must
 * come with a printable message); memory errors are the
 * sanitizers' to find.  The plugin is found as the tools find it
 * (REFLECT_PLUGIN_PATH); without it, D is taken from the input too.
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

#define HARNESS "fuzz-numeric"
#include "harness.h"

#define NCOLS_MAX 64
/* In per pixel: P N V roughness; the projection adds R D hit.dist
 * probe.dist. */
#define IN_FLOATS 10

static const char *const gbuffer_channels[IN_FLOATS] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", "roughness",
};

static const char *const direction_channels[3] = { "D.X", "D.Y", "D.Z" };

static const char *
no_key(void *ctx, const char *key)
{
	(void)ctx;
	(void)key;
	return NULL;
}

/* The projected row shaded with or without the vector reads; the pass's
 * output, or NULL. */
static float *
shade(const rf_header *in, const float *row, int vector, size_t *ncomp)
{
	struct rf_shade_options o = { 0, 1, 0 };
	char err[512];
	rf_header *out;
	rf_shade *s;
	float *px;

	if (vector)
		unsetenv("REFLECT_SIMD");
	else
		setenv("REFLECT_SIMD", "off", 1);
	check(rf_shade_create(&s, &o) == 0, "shade_create");
	/* Clamped, as reflect-shade --invalid=clamp: every pixel is shaded. */
	rf_shade_set_invalid(s, RF_INVALID_CLAMP);
	if (rf_shade_begin_frame(s, in, NULL, &out, err, sizeof(err)) < 0) {
		rf_shade_destroy(s);
		return NULL;
	}
	check(rf_shade_set_environment(s, environment(), RF_MAPPING_LINEAR, 3.0f) == 0,
	      "set_environment");
	*ncomp = rf_header_nchannels(out);
	check((px = calloc(rf_header_ncols(out) * *ncomp, sizeof(float))) != NULL, "calloc");
	check(rf_shade_run(s, row, px, 1) == 0, "shade_run");
	rf_shade_destroy(s);
	return px;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static rf_module *box;
	static int tried;
	struct rf_probe probe = { { 0, 1.5f, 0 }, { -3, 0, -2 }, { 3, 3, 2 }, 1, 0.0f, 0 };
	struct rf_host host;
	size_t ncols = size / (IN_FLOATS * sizeof(float)), i, c, nv, np, spec;
	rf_header *in, *proj = NULL;
	const float *row;
	float *gb, *projected = NULL, *a, *b;
	char err[512];
	double values[8];

	if (!ncols)
		return 0;
	if (ncols > NCOLS_MAX)
		ncols = NCOLS_MAX;
	check((gb = malloc(ncols * IN_FLOATS * sizeof(float))) != NULL, "malloc");
	memcpy(gb, data, ncols * IN_FLOATS * sizeof(float));
	check(rf_header_create(&in) == 0, "header_create");
	rf_header_set_size(in, ncols, 1);
	for (c = 0; c < IN_FLOATS; c++)
		check(rf_header_add_channel(in, gbuffer_channels[c]) >= 0, "add_channel");
	if (!tried++ && rf_module_load(&box, "box", RF_KIND_PROJECTION, err, sizeof(err)) < 0)
		box = NULL;
	row = gb;
	if (box) {
		const struct rf_plugin *p = rf_module_plugin(box);
		rf_stage *st;

		memset(&host, 0, sizeof(host));
		host.size = sizeof(host);
		host.abi_major = RF_PLUGIN_ABI_MAJOR;
		host.abi_minor = RF_PLUGIN_ABI_MINOR;
		host.header_get = no_key;
		host.probe = &probe;
		check(p->nparams < 8, "box has more parameters than the harness holds");
		check(rf_plugin_parse_params(p, "", values, err, sizeof(err)) == 0, "params");
		check(rf_stage_create(&st, p, values, &host, 1, err, sizeof(err)) == 0,
		      "stage_create");
		check(rf_stage_begin_frame(st, in, &proj, err, sizeof(err)) == 0, "begin_frame");
		check(rf_header_dup(&proj, proj) == 0, "header_dup");
		check((projected = malloc(ncols * rf_header_nchannels(proj) * sizeof(float))) != NULL,
		      "malloc");
		/* Refused, with a message, or taken; then clamped, always taken. */
		if (rf_stage_run(st, gb, projected, 0, 1) < 0) {
			const char *msg = rf_stage_error(st);

			check(msg[0] != '\0', "an invalid pixel without a message");
			for (i = 0; msg[i]; i++)
				check((unsigned char)msg[i] >= 0x20 && msg[i] != 0x7f,
				      "a control character in a message");
		}
		rf_stage_set_invalid(st, RF_INVALID_CLAMP);
		check(rf_stage_run(st, gb, projected, 0, 1) == 0, "stage_run with clamp");
		rf_stage_destroy(st);
		row = projected;
	} else {
		/* No plugin: the input's P stands in for D, N for hit.dist. */
		rf_header_destroy(in);
		check(rf_header_create(&in) == 0, "header_create");
		rf_header_set_size(in, ncols, 1);
		for (c = 0; c < IN_FLOATS; c++)
			check(rf_header_add_channel(in, c < 3 ? direction_channels[c]
			                                      : gbuffer_channels[c]) >= 0,
			      "add_channel");
	}
	/* The pass reads the effective roughness: the input's, renamed. */
	{
		rf_header *h = proj ? proj : in;
		size_t n = rf_header_nchannels(h);
		rf_header *sh;

		check(rf_header_create(&sh) == 0, "header_create");
		rf_header_set_size(sh, ncols, 1);
		for (c = 0; c < n; c++)
			check(rf_header_add_channel(sh, strcmp(rf_header_channel(h, c), "roughness")
			                                    ? rf_header_channel(h, c)
			                                    : RF_SHADE_ROUGHNESS) >= 0,
			      "add_channel");
		a = shade(sh, row, 1, &nv);
		b = shade(sh, row, 0, &np);
		check((a == NULL) == (b == NULL), "one path took the frame, the other not");
		if (a) {
			check(nv == np, "the paths write different channels");
			spec = n; /* spec.R G B follow the input's channels */
			for (i = 0; i < ncols; i++)
				for (c = spec; c < spec + 3; c++) {
					float x = a[i * nv + c], y = b[i * np + c];

					check(isfinite(x) && isfinite(y), "radiance that is not finite");
					check(fabsf(x - y) <= 1e-3f * (1.0f + fabsf(y)),
					      "the vector and plain reads disagree");
				}
		}
		free(a);
		free(b);
		rf_header_destroy(sh);
	}
	rf_header_destroy(proj);
	rf_header_destroy(in);
	free(projected);
	free(gb);
	return 0;
}
