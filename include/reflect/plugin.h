/*
 * The reflect plugin ABI: the only header a plugin needs.
 *
 * A plugin is one shared object <name>.so exporting one function,
 * rf_plugin_entry(), that returns a constant descriptor.  The host checks
 * the descriptor's version and size before it reads anything else, maps
 * stream channels to the plugin's inputs and outputs by name, and calls
 * run() on spans of pixels.  Plugins link against nothing of ours: what
 * they need from the host comes through the rf_host table.
 *
 * Rules for plugins: never print, never exit, keep no global mutable
 * state (several instances run at once, one per thread), report errors
 * from create() through its message buffer.
 *
 * History of the ABI version:
 *   1.0  first version (reflect 0.1.0).
 *   1.1  the descriptor flag RF_PLUGIN_RADIANCE: a shade mode says that
 *        it writes radiance itself (a 1.0 mode's outputs still tell);
 *        host services for such modes: project_rays, sample_radiance,
 *        env_size, env_levels, dfg; optional_inputs in the descriptor;
 *        the accumulate kind's contract, with nvalues and count appended
 *        to rf_span; the filter kind, with band, radius and pass appended
 *        to rf_span and the host service filter_passes; sample() through
 *        the pass's kernels, and sample_many; fail, for run();
 *        the probe's bevel and bevel_grown, and declare_bevel;
 *        RF_PARAM_STRING parameters and param_string; face_size,
 *        texel_solid_angle, pixel_footprint and random_pairs; the
 *        probe list (nprobes, probes, probe_blend, probe_weights);
 *        the descriptor flag RF_PLUGIN_PREFILTERED.
 *   1.2  probe shapes: struct rf_probe grows the influence's shape and
 *        rotation and a proxy of its own (RF_SHAPE_*).  The host gives a
 *        1.1 plugin its probes array at the 1.1 stride, and refuses it
 *        a frame whose probes are not axis-aligned boxes projected onto
 *        themselves, which it could not see.
 *   1.3  a filter mode's outputs name rows it carries from pass to pass
 *        (a variance beside the values); before 1.3 they must be empty.
 * A minor bump only appends fields at the end of a struct, or defines new
 * flag bits or kinds; a major bump is anything else.  The host accepts a
 * plugin when its major equals the host's and its minor is not newer, and
 * never reads a descriptor past its size.  tests/unit/test-abi.c (in
 * reflect's source tree, not installed) pins the layout: a change that fails it needs a version bump and a new entry
 * here.  The full guide is reflect-plugin(7).
 */
#ifndef REFLECT_PLUGIN_H
#define REFLECT_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RF_PLUGIN_ABI_MAJOR 1
#define RF_PLUGIN_ABI_MINOR 3

#if defined(__GNUC__)
#define RF_PLUGIN_EXPORT __attribute__((visibility("default")))
#else
#define RF_PLUGIN_EXPORT
#endif

#define RF_PLUGIN_ENTRY "rf_plugin_entry"

/* A probe (world units): the plugins' view of it, and the library's
 * (reflect/probe.h reads, writes and blends it). */
struct rf_probe {
	float center[3];  /* capture point */
	float box_min[3]; /* influence and projection box */
	float box_max[3];
	int box_projection; /* 0: directions are used as they are */
	/* ABI 1.1: the shape the lookups leave by, when not the box itself:
	 * its edges and corners rounded by bevel (world units), its faces on
	 * the box, or with bevel_grown the box grown by bevel all round
	 * (the PROBE_BEVEL key; 0 for the box). */
	float bevel;
	int bevel_grown;
	/* ABI 1.2: the shapes engines give a probe.  The influence (where
	 * the probe weighs, and where its capture point must lie) is the
	 * box above, turned about its centre by rotation when rotated, or
	 * the sphere inscribed in that box (shape RF_SHAPE_SPHERE; the box
	 * is then a cube).  The proxy, the shape the lookups are projected
	 * onto, is the influence (proxy_shape RF_SHAPE_SAME, which a zeroed
	 * tail means), a box or sphere of its own given the same way, or
	 * RF_SHAPE_INFINITE (no projection: the lookup is R).  Rotations
	 * are row-major, orthonormal and right-handed, local to world:
	 * world = centre + rotation (local - centre). */
	uint32_t shape;
	uint32_t rotated;
	float rotation[9];
	uint32_t proxy_shape;
	uint32_t proxy_rotated;
	float proxy_min[3], proxy_max[3];
	float proxy_rotation[9];
};

/* Shapes of a probe's influence and proxy (ABI 1.2). */
#define RF_SHAPE_SAME 0     /* the proxy: the influence itself */
#define RF_SHAPE_BOX 1
#define RF_SHAPE_SPHERE 2
#define RF_SHAPE_INFINITE 3 /* the proxy only: no projection */

/* sizeof(struct rf_probe) in ABI 1.1, the stride of a 1.1 plugin's
 * probes array. */
#define RF_PROBE_SIZE_1_1 48

/* The most probes a frame has. */
#define RF_PROBES_MAX 16

/* What a plugin is for: the tool that loads it. */
enum rf_plugin_kind {
	/* reflect-project: lookup direction and distances.  A projection
	 * mode that reads no P.* has no parallax: the host writes its
	 * probes (every one the frame blends) with box projection off, and
	 * project_rays after it keeps the rays' directions. */
	RF_KIND_PROJECTION = 1,
	RF_KIND_SHADE = 2,      /* reflect-shade: roughness.eff, or spec.R G B */
	RF_KIND_OCCLUSION = 3,  /* reflect-occlude: specular occlusion term */
	RF_KIND_ACCUMULATE = 4, /* reflect-accumulate: combines frames */
	RF_KIND_FILTER = 5      /* reflect-filter: filters across pixels (ABI 1.1) */
};

/* What a kind writes, named once for hosts and plugins alike.  A shade
 * mode writes either the effective perceptual roughness, which the host
 * turns into a lod and samples, or (with RF_PLUGIN_RADIANCE) the
 * radiance itself. */
#define RF_SHADE_ROUGHNESS "roughness.eff"
#define RF_SHADE_SPEC_R "spec.R"
#define RF_SHADE_SPEC_G "spec.G"
#define RF_SHADE_SPEC_B "spec.B"

/* An occlusion mode (reflect-occlude) writes one output, the factor its
 * specular occlusion puts on the reflection (1: none, 0: all of it);
 * the host multiplies spec.R spec.G spec.B and R G B, those the stream
 * has, by it, and keeps in this channel the product with an occlusion
 * the stream had before. */
#define RF_OCCLUSION "occlusion"

/* An accumulate mode (reflect-accumulate) combines frames value by
 * value, whatever channel a value comes from: its descriptor lists no
 * inputs, and its outputs name the slots of its state per value, the
 * first two with a fixed meaning.  run() gets span.in, the frame's
 * values (span.nvalues a pixel), and span.out, the state (outputs x
 * nvalues floats a pixel, the slots of value 0 first), to update in
 * place; span.count is how many frames the state holds with this one
 * (1: the state is garbage, start afresh).  The host keeps the state
 * between frames and reads the two slots below; threads share it by
 * rows, so a mode keeps nothing per pixel of its own. */
#define RF_ACCUMULATE_VALUE "value"       /* the running result */
#define RF_ACCUMULATE_VARIANCE "variance" /* the variance of that result (its
                                             standard error squared); +inf
                                             when it cannot be told yet */

/* A filter mode (reflect-filter) filters values across pixels, whatever
 * channel a value comes from, guided by the channels its inputs (and
 * optional inputs) name.  It runs in passes, each over the output of the
 * one before; create() declares them through the host's filter_passes
 * (else one pass of radius 0).  run() gets the rows y - radius .. y +
 * radius of the pass's input in span.band (NULL for a row outside the
 * frame), each row whole and planar, for vector code: the row of guide
 * g is band[k] + g width, then the rows of the span.nvalues values;
 * span.in is band[radius].  It writes span.out planar too: value v of
 * pixel span.x + i at out[v npix + i].  Its outputs name no channel
 * but rows of its own a pixel, state a pass hands the next: NaN into
 * the first pass, written by every pass after the values (output k at
 * out[(nvalues + k) npix + i], in the band after the values' rows),
 * never written to the stream. */
#define RF_FILTER_PASSES_MAX 16
#define RF_FILTER_RADIUS_MAX 1024

/* Descriptor flags; a bit the host does not know makes it refuse the
 * plugin. */
#define RF_PLUGIN_RADIANCE 0x1u /* shade: writes spec.R spec.G spec.B itself
                                   (through the host's sample service), not
                                   roughness.eff (ABI 1.1) */
#define RF_PLUGIN_PREFILTERED 0x2u /* with RF_PLUGIN_RADIANCE: reads the
                                     GGX-prefiltered chain (sample,
                                     sample_many), so a raw environment is
                                     prefiltered for it as for a roughness
                                     mode; without it, such a mode gets the
                                     environment as it is (ABI 1.1) */
#define RF_PLUGIN_KNOWN_FLAGS (RF_PLUGIN_RADIANCE | RF_PLUGIN_PREFILTERED)

/* Parameter flags; a bit the host does not know makes it refuse the plugin. */
#define RF_PARAM_INTEGER 0x1u /* only whole numbers are accepted */
#define RF_PARAM_BOOL 0x2u    /* 0 or 1; min 0, max 1 */
#define RF_PARAM_CHOICE 0x4u  /* value is an index into `choices` */
/* ABI 1.1: a string (a table file a model loads in create(), say): its
 * default is `choices` (NULL: ""), min, max and def are 0, and create()
 * gets the string with the host's param_string(ctx, values[i]). */
#define RF_PARAM_STRING 0x8u
#define RF_PARAM_KNOWN_FLAGS (RF_PARAM_INTEGER | RF_PARAM_BOOL | RF_PARAM_CHOICE | \
                              RF_PARAM_STRING)

struct rf_param {
	const char *name;    /* [a-z][a-z0-9_]*, as in -m mode:name=value */
	const char *help;    /* one line, lowercase, no full stop */
	double min, max;     /* inclusive; -HUGE_VAL or HUGE_VAL for unbounded */
	double def;          /* default, inside [min, max] */
	unsigned flags;      /* RF_PARAM_* */
	const char *choices; /* with RF_PARAM_CHOICE: "a|b|c", value = index;
	                        with RF_PARAM_STRING: the default string */
};

/* Services of the host; a member is NULL when the tool cannot offer it.
 * The table and all it points to stay valid until the instance's
 * destroy().  Read a member added in a later minor version only when
 * size covers it. */
struct rf_host {
	uint32_t size; /* sizeof(struct rf_host) as the host was built */
	uint32_t abi_major, abi_minor;
	void *ctx; /* first argument of every callback below */
	/* The value of a stream header key, NULL when absent. */
	const char *(*header_get)(void *ctx, const char *key);
	/* The probe, from the tool's options or the stream's header keys. */
	const struct rf_probe *probe;
	/* Environment radiance in direction dir (need not be unit) at a lod;
	 * black where dir is not finite.  Since ABI 1.1 through the shading
	 * pass's own kernels: a mode reading at the pass's D and lod gets the
	 * pass's numbers (mode none's) to the bit. */
	void (*sample)(void *ctx, const float dir[3], float lod, float rgb[3]);
	/* The one roughness-to-lod mapping of the environment, and back. */
	float (*roughness_to_lod)(void *ctx, float roughness);
	float (*lod_to_roughness)(void *ctx, float lod);
	float lod_steps; /* index of the environment's last level */
	uint32_t seed;   /* --seed */

	/* ABI 1.1: for modes that trace the lobe themselves. */
	/* n rays from the shading point p along unit directions dirs
	 * (3 n floats), each taken to where it leaves the probe's projection
	 * shape as reflect-project's box mode does (bevel's, when the probe
	 * has a bevel): lookup (3 n) the unit
	 * direction from the capture point to that exit, dist (n) the
	 * distance from p to it, and jacobian (n) the solid angle at the
	 * capture point per solid angle at p there (dw_C / dw_P).  A ray with
	 * no exit (p outside the box, box projection off) keeps its
	 * direction, with dist +inf and jacobian 1.  NULL without a probe. */
	void (*project_rays)(void *ctx, uint32_t n, const float p[3], const float *dirs,
	                     float *lookup, float *dist, float *jacobian);
	/* n reads of the environment's radiance, box-filtered (not GGX
	 * convolved: a mode doing filtered importance sampling picks the
	 * lod, 0 the source texels): directions x, y, z (need not be unit)
	 * and lods (n floats each) in, rgba (4 n floats, a undefined) out.
	 * Several at a time go through the vector path of the host. */
	void (*sample_radiance)(void *ctx, uint32_t n, const float *x, const float *y,
	                        const float *z, const float *lod, float *rgba);
	uint32_t env_size;   /* texels across a face of level 0 */
	uint32_t env_levels; /* levels sample_radiance has, env_size down to 1 */
	/* The split-sum's directional albedo terms of GGX (white: A + B), as
	 * the host's --final multiplies spec by F0 A + B. */
	void (*dfg)(void *ctx, float n_dot_v, float roughness, float *a, float *b);
	/* For a filter mode's create(): its passes (1 to RF_FILTER_PASSES_MAX)
	 * and the band each reads, rows above and below (at most
	 * RF_FILTER_RADIUS_MAX); 0, or -1 when out of range. */
	int (*filter_passes)(void *ctx, uint32_t passes, const uint32_t *radius);
	/* n reads of the environment as sample() reads it (the GGX-prefiltered
	 * chain the pass samples), eight at a time through the pass's vector
	 * kernel where the CPU has it: directions x, y, z and lods (n floats
	 * each) in, rgba (4 n floats, a undefined) out.  NULL without an
	 * environment. */
	void (*sample_many)(void *ctx, uint32_t n, const float *x, const float *y,
	                    const float *z, const float *lod, float *rgba);
	/* For run(): the mode cannot go on (what it was given does not fit
	 * the frame, say).  The tool stops once the rows running now are
	 * done, exit status 1, with "mode 'NAME': message" (one line; the
	 * first call wins).  run() still returns as usual, its outputs
	 * written whatever they are. */
	void (*fail)(void *ctx, const char *message);
	/* For a projection mode's create(): the shape its D leaves by is
	 * the probe box rounded by radius (world units, 0: the box), its
	 * faces on the box or (grown) the box grown by radius.  The tool
	 * records it in the probe (PROBE_BEVEL), and the tools after it
	 * trace their rays to the same shape (project_rays).  0, or -1 when
	 * the radius is negative or more than the box's smallest half
	 * extent. */
	int (*declare_bevel)(void *ctx, float radius, int grown);
	/* The string of an RF_PARAM_STRING parameter, from its value in
	 * create()'s values: the text given (-m mode:table=t.txt; a file
	 * name is the plugin's to open, relative to the working directory)
	 * or the default.  Valid until the instance's destroy(). */
	const char *(*param_string)(void *ctx, double value);
	/* The prefiltered environment's geometry (the chain sample() and
	 * sample_many() read): texels across a face of a level (0 past the
	 * last), and the solid angle of a texel toward dir (need not be
	 * unit) at a lod, (2 / face_size(0))^2 4^lod / (1 + u^2 + v^2)^1.5
	 * for face coordinates u, v: what filtered importance sampling
	 * compares a sample's pdf with on plain box-filtered levels.  On
	 * the prefiltered chain a lod stands for a lobe, not a texel: read
	 * a share of a lobe at roughness_to_lod of the lobe as wide as the
	 * share (reflect-plugin(7), The prefiltered chain).  NULL without an
	 * environment. */
	uint32_t (*face_size)(void *ctx, uint32_t level);
	float (*texel_solid_angle)(void *ctx, const float dir[3], float lod);
	/* The pixel's footprint on its surface: where the camera rays through
	 * the centres of the pixels right of and below pixel (x, y) meet the
	 * plane through p with normal n, less p (dpdx, dpdy, world units).
	 * From the stream's CAMERA key and the frame's size, as
	 * reflect-gbuffer casts its rays; 0, or -1 when the stream has no
	 * camera or a ray runs along the plane (then both are 0). */
	int (*pixel_footprint)(void *ctx, uint32_t x, uint32_t y, const float p[3],
	                       const float n[3], float dpdx[3], float dpdy[3]);
	/* Pairs i0 .. i0 + n - 1 of pixel (x, y)'s sequence of n_all pairs
	 * in [0, 1)^2, the raytraced mode's for the same pattern, seed (the
	 * host's --seed) and frame: RF_SEQUENCE_WHITE a hash of pixel,
	 * index, frame and seed; RF_SEQUENCE_LOW_DISCREPANCY the Hammersley
	 * set of n_all points moved by frame steps of the R2 sequence;
	 * RF_SEQUENCE_BLUE that set moved again by the pixel's blue-noise
	 * values.  Frame 0 is a still: pass the stream's FRAME to animate. */
	void (*random_pairs)(void *ctx, int pattern, uint32_t x, uint32_t y, uint32_t frame,
	                     uint32_t i0, uint32_t n, uint32_t n_all, float *u0, float *u1);
	/* Every probe of the frame (PROBE_*, PROBE2_*, ...; the first is
	 * probe, as the tool's options have it), at most RF_PROBES_MAX, with
	 * their blend distances, and each one's weight at a point p (nprobes
	 * floats) as HDRP blends them: w = smoothstep(sat(the distance from p
	 * to the box's nearest face / blend)), 1 inside a probe without a
	 * blend distance, 0 outside its box; taken smallest box first, each
	 * clipped to what the ones before left, w' = min(w, 1 - sum); the
	 * return is the rest, 1 - sum, for the sky or an infinite probe. */
	uint32_t nprobes;
	const struct rf_probe *probes;
	const float *probe_blend;
	float (*probe_weights)(void *ctx, const float p[3], float *weights);
};

/* The patterns of random_pairs (the raytraced mode's pattern=). */
#define RF_SEQUENCE_WHITE 0
#define RF_SEQUENCE_BLUE 1
#define RF_SEQUENCE_LOW_DISCREPANCY 2

/* A span of pixels along one row, channels interleaved in the order the
 * descriptor declares them.  It need not be a whole row (x need not be
 * 0); run() writes every output of every pixel and keeps no pointer. */
struct rf_span {
	uint32_t size;          /* sizeof(struct rf_span) as the host was built */
	uint32_t npix;          /* pixels in this span */
	uint32_t x, y;          /* image position of the first pixel; top row 0 */
	uint32_t width, height; /* the frame */
	uint32_t frame;         /* index of the frame in the stream */
	const float *in;        /* npix * ninputs */
	float *out;             /* npix * noutputs */
	/* ABI 1.1, for the accumulate and filter kinds (0 for the others):
	 * values a pixel in `in` (after a filter's inputs), and for the
	 * accumulate kind frames in the state with this one. */
	uint32_t nvalues;
	uint32_t count;
	/* ABI 1.1, for the filter kind (NULL and 0 for the others): the
	 * band's rows, 2 radius + 1 of them, row span.y at band[radius]; the
	 * pass, from 0. */
	const float *const *band;
	uint32_t radius;
	uint32_t pass;
};

struct rf_plugin {
	/* These three come first and never move. */
	uint32_t abi_major;
	uint32_t abi_minor;
	uint32_t size; /* sizeof(struct rf_plugin) as the plugin was built */

	uint32_t kind;  /* enum rf_plugin_kind */
	uint32_t flags; /* RF_PLUGIN_* (ABI 1.0 defines none) */
	const char *name;    /* equal to the file name without ".so" */
	const char *summary; /* one line, lowercase, no full stop */
	const char *version;
	const char *author;
	const char *license;

	uint32_t nparams;
	const struct rf_param *params;
	const char *const *inputs;  /* channel names read, NULL-terminated */
	const char *const *outputs; /* channel names written, NULL-terminated */

	/* values[nparams] are validated against the table before the call.
	 * Returns 0, or non-zero with a message in err. */
	int (*create)(const struct rf_host *host, const double *values,
	              void **state, char *err, size_t errlen);
	void (*run)(void *state, const struct rf_span *span);
	void (*destroy)(void *state);

	/* ABI 1.1: channels read when the stream has them, NULL-terminated
	 * (or NULL), after the inputs in each pixel; one the stream lacks
	 * reads as NaN, and is not checked. */
	const char *const *optional_inputs;
};

/* The optional inputs of a descriptor of any minor version: NULL when it
 * has none, or predates them. */
static inline const char *const *
rf_plugin_optional_inputs(const struct rf_plugin *p)
{
	return p->size >= offsetof(struct rf_plugin, optional_inputs) +
	                          sizeof(p->optional_inputs)
	           ? p->optional_inputs
	           : NULL;
}

typedef const struct rf_plugin *(*rf_plugin_entry_fn)(void);

/* Declare the entry point in a plugin:
 *   RF_PLUGIN_DEFINE(my_descriptor)
 */
#ifdef __cplusplus
#define RF_PLUGIN_EXTERN_C extern "C"
#else
#define RF_PLUGIN_EXTERN_C
#endif
#define RF_PLUGIN_DEFINE(descriptor)                                       \
	RF_PLUGIN_EXTERN_C RF_PLUGIN_EXPORT const struct rf_plugin *        \
	rf_plugin_entry(void);                                              \
	RF_PLUGIN_EXTERN_C const struct rf_plugin *rf_plugin_entry(void)    \
	{                                                                   \
		return &(descriptor);                                       \
	}

#ifdef __cplusplus
}
#endif

#endif
