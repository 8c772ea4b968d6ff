/*
 * The host services of plugin.h, once for every tool: reflect-project
 * and reflect-shade, and every tool that runs plugins after them, give
 * their modes the same table with the same meanings.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "plugin/plugin-internal.h"
#include "envmap/rgba_levels.h"
#include "envmap/rgba_levels_simd.h"
#include "util/util.h"
#include "reflect/host.h"
#include "reflect/probe.h"
#include "reflect/surface.h"
#include "reflect/scene.h"
/* The box's geometry as the projection plugins have it, to the bit. */
#include "probe/projection.h"
#include "probe/bevel.h"
#include "probe/shape.h"
#include "maths/sequences.h"
#include "maths/soa.h"

struct rf_plugin_host {
	struct rf_host table; /* its ctx is this host */
	const rf_header *frame;
	struct rf_probe probe;
	const rf_cubemap *env;
	enum rf_mapping mapping;
	float steps;
	/* For sample and sample_many: the environment as the shading pass
	 * reads it, RGBA vectors, so a one-tap mode gets its bytes. */
	struct rf__rgba_levels env_levels;
	int env_vector;
	/* For sample_radiance: level 0 of the environment and its plain
	 * box-filtered levels, as RGBA vectors. */
	rf_cubemap *plain;
	struct rf__rgba_levels levels;
	int vector;
	struct rf__box box;     /* the proxy's box, in its frame; the capture point */
	struct rf__proxy proxy; /* the shape rays leave by */
	int wide_rays; /* project_rays in eight lanes (AVX2) */
	struct rf__bevel bevel; /* the proxy's rounded box, when probe.bevel > 0 */
	/* The first fail() of a block: set once (failed), read after the
	 * block's threads are joined. */
	int failed;
	char failure[256];
	/* The frame's probes (probe_weights): the first is probe. */
	struct rf_blend blend;
	int distant; /* every probe's box projection off (take_distant) */
	/* The frame's camera (CAMERA), for pixel_footprint. */
	int has_camera;
	struct rf_camera camera;
	size_t width, height;
	/* What the last filter mode's create() declared (filter_passes). */
	uint32_t filter_npasses;
	uint32_t filter_radius[RF_FILTER_PASSES_MAX];
	/* The table a plugin built for ABI 1.1 or 1.0 gets: the same but
	 * for its probes array, at that ABI's stride (kept in step by every
	 * setter, sync_legacy). */
	struct rf_host legacy;
	unsigned char legacy_probes[RF_PROBES_MAX][RF_PROBE_SIZE_1_1];
};

/* A probe a plugin of ABI 1.1 would misread: anything but an axis-aligned
 * box that is its own proxy. */
static int
probe_shaped(const struct rf_probe *p)
{
	return (p->shape != 0 && p->shape != RF_SHAPE_BOX) || p->rotated ||
	       p->proxy_shape != RF_SHAPE_SAME;
}

static void
sync_legacy(rf_plugin_host *h)
{
	uint32_t i;

	h->legacy = h->table;
	for (i = 0; i < h->blend.nprobes && i < RF_PROBES_MAX; i++)
		memcpy(h->legacy_probes[i], &h->blend.probes[i], RF_PROBE_SIZE_1_1);
	h->legacy.probes = (const struct rf_probe *)(const void *)h->legacy_probes;
}

static const char *
header_get(void *ctx, const char *key)
{
	const rf_plugin_host *h = ctx;

	return h->frame ? rf_header_get(h->frame, key) : NULL;
}

/* n reads of levels, the plugin's directions guarded: one that is not
 * finite reads black (the kernels index texels by it; zero and denormal
 * directions they take, as the pass does).  In chunks on the stack,
 * copied only when a chunk has such a direction. */
static void
guarded_fetch(const struct rf__rgba_levels *levels, int vector, uint32_t n, const float *x,
              const float *y, const float *z, const float *lod, float *rgba)
{
	uint32_t i0, k;

	for (i0 = 0; i0 < n; i0 += 64) {
		uint32_t m = n - i0 < 64 ? n - i0 : 64, any = 0;
		float cx[64], cy[64], cz[64];
		unsigned char bad[64];

		/* Whether any is inf or NaN (all exponent bits set), four at a
		 * time without a branch: one by one, the test cost a third as
		 * much as the reads. */
		typedef uint32_t u4 __attribute__((vector_size(16)));
		const u4 e = { 0x7F800000u, 0x7F800000u, 0x7F800000u, 0x7F800000u };
		u4 v4 = { 0, 0, 0, 0 };

		for (k = 0; k + 4 <= m; k += 4) {
			u4 a, b, c;

			memcpy(&a, x + i0 + k, sizeof(a));
			memcpy(&b, y + i0 + k, sizeof(b));
			memcpy(&c, z + i0 + k, sizeof(c));
			v4 |= (u4)((a & e) == e) | (u4)((b & e) == e) | (u4)((c & e) == e);
		}
		any = v4[0] | v4[1] | v4[2] | v4[3];
		for (; k < m; k++) {
			uint32_t a, b, c;

			memcpy(&a, x + i0 + k, sizeof(a));
			memcpy(&b, y + i0 + k, sizeof(b));
			memcpy(&c, z + i0 + k, sizeof(c));
			any |= ((a & 0x7F800000u) == 0x7F800000u) | ((b & 0x7F800000u) == 0x7F800000u) |
			       ((c & 0x7F800000u) == 0x7F800000u);
		}
		for (k = 0; any && k < m; k++)
			bad[k] = !isfinite(x[i0 + k]) || !isfinite(y[i0 + k]) || !isfinite(z[i0 + k]);
		if (!any) {
			rf__rgba_levels_fetch_many(levels, vector, m, x + i0, y + i0, z + i0, lod + i0,
			                           (rf__v4 *)(void *)(rgba + 4 * (size_t)i0));
			continue;
		}
		for (k = 0; k < m; k++) {
			cx[k] = bad[k] ? 1.0f : x[i0 + k];
			cy[k] = bad[k] ? 0.0f : y[i0 + k];
			cz[k] = bad[k] ? 0.0f : z[i0 + k];
		}
		rf__rgba_levels_fetch_many(levels, vector, m, cx, cy, cz, lod + i0,
		                           (rf__v4 *)(void *)(rgba + 4 * (size_t)i0));
		for (k = 0; k < m; k++)
			if (bad[k])
				memset(rgba + 4 * (size_t)(i0 + k), 0, 4 * sizeof(float));
	}
}

/* One read through the pass's own kernels (rf__rgba_levels_fetch_many,
 * which pads a batch's tail to its vector width): a mode reading at the
 * pass's D and lod gets the pass's numbers to the bit. */
static void
sample(void *ctx, const float dir[3], float lod, float rgb[3])
{
	const rf_plugin_host *h = ctx;
	float rgba[4];

	guarded_fetch(&h->env_levels, h->env_vector, 1, dir, dir + 1, dir + 2, &lod, rgba);
	memcpy(rgb, rgba, 3 * sizeof(float));
}

static void
sample_many(void *ctx, uint32_t n, const float *x, const float *y, const float *z,
            const float *lod, float *rgba)
{
	const rf_plugin_host *h = ctx;

	guarded_fetch(&h->env_levels, h->env_vector, n, x, y, z, lod, rgba);
}

static float
roughness_to_lod(void *ctx, float roughness)
{
	const rf_plugin_host *h = ctx;

	return rf_roughness_to_lod(h->mapping, h->steps, roughness);
}

static float
lod_to_roughness(void *ctx, float lod)
{
	const rf_plugin_host *h = ctx;

	return rf_lod_to_roughness(h->mapping, h->steps, lod);
}

/* project_rays' loop for p inside the box, whole vectors of rays at a
 * time (project-lanes.h), by the same operations in the same order (the
 * same bits as one at a time). */
#define RF__LANES_BODY "plugin/project-lanes.h"
#include "maths/lanes-widths.h"

/* How many rays from p inside the box the vector loops did. */
static uint32_t
project_rays_vector(const rf_plugin_host *h, uint32_t n, const float p[3], const float *dirs,
                    float *lookup, float *dist, float *jacobian)
{
	uint32_t i = 0;

#if defined(RF__LANES_WIDE)
	if (h->wide_rays)
		i = project_lanes_8(&h->box, i, n, p, dirs, lookup, dist, jacobian);
#endif
#if defined(__SSE2__)
	i = project_lanes_4(&h->box, i, n, p, dirs, lookup, dist, jacobian);
#endif
	return i;
}

/* A ray without an exit keeps its direction, dist +inf, Jacobian 1. */
static void
ray_kept(const float dir[3], float d[3], float *dist, float *jacobian)
{
	d[0] = dir[0];
	d[1] = dir[1];
	d[2] = dir[2];
	*dist = INFINITY;
	*jacobian = 1.0f;
}

/* A ray from p that leaves the shape at t, where its outward normal is
 * nrm: the lookup from the capture point, and dw_C / dw_P =
 * |x - P|^2 cos_C / (|x - C|^2 cos_P), the cosines taken to nrm. */
static void
ray_leaves(const rf_plugin_host *h, const float p[3], const float dir[3], float t,
           const float nrm[3], float d[3], float *dist, float *jacobian)
{
	float reach, cos_c, cos_p;

	rf__lookup_from_hit(&h->box, p, dir, t, d, &reach);
	*dist = t;
	cos_c = fabsf(d[0] * nrm[0] + d[1] * nrm[1] + d[2] * nrm[2]);
	cos_p = fabsf(dir[0] * nrm[0] + dir[1] * nrm[1] + dir[2] * nrm[2]);
	*jacobian = reach > 0.0f && cos_p > 0.0f ? t * t * cos_c / (reach * reach * cos_p) : 1.0f;
}

/* The rays' exits from the rounded box, as the bevel mode finds them
 * (rf__bevel_exit) in the box's frame, each normal taken back out. */
static void
project_rays_bevel(const rf_plugin_host *h, uint32_t n, const float p[3], const float *dirs,
                   float *lookup, float *dist, float *jacobian)
{
	const struct rf__frame *frame = &h->proxy.frame;
	float q[3];
	uint32_t i;

	if (h->proxy.rotated)
		rf__frame_point_in(frame, p, q);
	else
		q[0] = p[0], q[1] = p[1], q[2] = p[2];
	for (i = 0; i < n; i++) {
		const float *dir = dirs + 3 * i;
		float t, nrm[3], e[3];

		if (h->proxy.rotated)
			rf__frame_vector_in(frame, dir, e);
		else
			e[0] = dir[0], e[1] = dir[1], e[2] = dir[2];
		if (!h->probe.box_projection || rf__bevel_exit(&h->bevel, q, e, &t, nrm) < 0) {
			ray_kept(dir, lookup + 3 * i, dist + i, jacobian + i);
			continue;
		}
		if (h->proxy.rotated) {
			float local[3] = { nrm[0], nrm[1], nrm[2] };

			rf__frame_vector_out(frame, local, nrm);
		}
		ray_leaves(h, p, dir, t, nrm, lookup + 3 * i, dist + i, jacobian + i);
	}
}

/* The rays' exits from an oriented box or a sphere, as rf__proxy_exit
 * finds them for reflect-project; an infinite proxy keeps every
 * direction. */
static void
project_rays_shape(const rf_plugin_host *h, uint32_t n, const float p[3], const float *dirs,
                   float *lookup, float *dist, float *jacobian)
{
	uint32_t i;

	for (i = 0; i < n; i++) {
		const float *dir = dirs + 3 * i;
		float t, nrm[3];

		if (!h->probe.box_projection || rf__proxy_exit(&h->proxy, p, dir, &t) < 0) {
			ray_kept(dir, lookup + 3 * i, dist + i, jacobian + i);
			continue;
		}
		rf__proxy_normal(&h->proxy, p, dir, t, nrm);
		ray_leaves(h, p, dir, t, nrm, lookup + 3 * i, dist + i, jacobian + i);
	}
}

/* The rays' exits from the box, as rf__box_exit and rf__lookup_from_hit find
 * them (the same quotients, so the same bits), with the face each leaves
 * by, which rf__box_exit does not say: the axis of the nearest wall. */
static void
project_rays(void *ctx, uint32_t n, const float p[3], const float *dirs, float *lookup,
             float *dist, float *jacobian)
{
	const rf_plugin_host *h = ctx;
	const struct rf__box *b = &h->box;
	int inside = h->probe.box_projection, k;
	uint32_t i;

	if (h->probe.bevel > 0.0f) {
		project_rays_bevel(h, n, p, dirs, lookup, dist, jacobian);
		return;
	}
	if (h->proxy.kind != RF_SHAPE_BOX || h->proxy.rotated) {
		project_rays_shape(h, n, p, dirs, lookup, dist, jacobian);
		return;
	}
	for (k = 0; k < 3; k++)
		if (p[k] < b->outer_lo[k] || p[k] > b->outer_hi[k])
			inside = 0;
	i = inside ? project_rays_vector(h, n, p, dirs, lookup, dist, jacobian) : 0;
	for (; i < n; i++) {
		const float *dir = dirs + 3 * i;
		float *d = lookup + 3 * i, t = INFINITY, reach;
		int axis = 0;

		for (k = 0; inside && k < 3; k++) {
			float tk;

			if (!(fabsf(dir[k]) > RF__AXIS_EPSILON))
				continue;
			tk = ((dir[k] > 0.0f ? b->hi[k] : b->lo[k]) - p[k]) / dir[k];
			if (tk < t) {
				t = tk;
				axis = k;
			}
		}
		if (!(t < INFINITY)) {
			ray_kept(dir, d, dist + i, jacobian + i);
			continue;
		}
		if (t < 0.0f)
			t = 0.0f; /* on a face (within the slack), leaving it */
		rf__lookup_from_hit(b, p, dir, t, d, &reach);
		dist[i] = t;
		/* dw_C / dw_P = |x - P|^2 cos_C / (|x - C|^2 cos_P), the cosines to
		 * the face's normal: a wall patch seen from both points. */
		jacobian[i] = reach > 0.0f ? t * t * fabsf(d[axis]) / (reach * reach * fabsf(dir[axis]))
		                           : 1.0f;
	}
}

static void
sample_radiance(void *ctx, uint32_t n, const float *x, const float *y, const float *z,
                const float *lod, float *rgba)
{
	const rf_plugin_host *h = ctx;

	guarded_fetch(&h->levels, h->vector, n, x, y, z, lod, rgba);
}

static void
fail(void *ctx, const char *message)
{
	rf_plugin_host *h = ctx;
	char *c;

	if (__atomic_exchange_n(&h->failed, 1, __ATOMIC_ACQ_REL))
		return; /* the first one wins */
	snprintf(h->failure, sizeof(h->failure), "%s",
	         message && *message ? message : "it cannot go on");
	for (c = h->failure; *c; c++)
		if ((unsigned char)*c < 0x20 || *c == 0x7f)
			*c = ' ';
}

int
rf__host_take_failure(const struct rf_host *table, const char *mode, char *err,
                      size_t errlen)
{
	rf_plugin_host *h;

	if (!table || !(h = table->ctx) || !__atomic_load_n(&h->failed, __ATOMIC_ACQUIRE))
		return 0;
	rf__format(err, errlen, "mode '%s': %s", mode, h->failure);
	__atomic_store_n(&h->failed, 0, __ATOMIC_RELEASE);
	return 1;
}

static const char *
param_string(void *ctx, double value)
{
	(void)ctx;
	return rf_plugin_param_string(NULL, value);
}

static uint32_t
face_size(void *ctx, uint32_t level)
{
	const rf_plugin_host *h = ctx;

	if (!h->env || level >= rf_cubemap_levels(h->env))
		return 0;
	return (uint32_t)rf_cubemap_level_size(h->env, level);
}

static float
texel_solid_angle(void *ctx, const float dir[3], float lod)
{
	const rf_plugin_host *h = ctx;
	const double size = (double)rf_cubemap_size(h->env);
	float u, v;
	double x, y;

	if (!isfinite(dir[0]) || !isfinite(dir[1]) || !isfinite(dir[2]) ||
	    !(dir[0] != 0.0f || dir[1] != 0.0f || dir[2] != 0.0f))
		return 0.0f;
	if (h->env_levels.turned) {
		float local[3];

		rf__turn_in(h->env_levels.turn, dir[0], dir[1], dir[2], local);
		rf_cube_face(local, &u, &v);
	} else
		rf_cube_face(dir, &u, &v);
	x = 2.0 * u - 1.0;
	y = 2.0 * v - 1.0;
	return (float)(4.0 / (size * size) / pow(1.0 + x * x + y * y, 1.5) * exp2(2.0 * lod));
}

/* The hit of the camera ray through image point (px, py) with the plane
 * (p, n), less p; 0, or -1 when the ray runs along the plane. */
static int
ray_on_plane(const rf_plugin_host *h, double px, double py, const float p[3], const float n[3],
             float out[3])
{
	double d[3], dn, t;
	int k;

	rf_camera_ray(&h->camera, h->width, h->height, px, py, d);
	dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
	if (!(fabs(dn) > 1e-9))
		return -1;
	t = ((p[0] - h->camera.position[0]) * n[0] + (p[1] - h->camera.position[1]) * n[1] +
	     (p[2] - h->camera.position[2]) * n[2]) / dn;
	for (k = 0; k < 3; k++)
		out[k] = (float)(h->camera.position[k] + t * d[k] - p[k]);
	return 0;
}

static int
pixel_footprint(void *ctx, uint32_t x, uint32_t y, const float p[3], const float n[3],
                float dpdx[3], float dpdy[3])
{
	const rf_plugin_host *h = ctx;
	float c[3];
	int k;

	/* each neighbour's hit less the pixel's own on the same plane, so
	 * that p need not lie on the centre ray exactly */
	if (!h->has_camera || ray_on_plane(h, x + 0.5, y + 0.5, p, n, c) < 0 ||
	    ray_on_plane(h, x + 1.5, y + 0.5, p, n, dpdx) < 0 ||
	    ray_on_plane(h, x + 0.5, y + 1.5, p, n, dpdy) < 0) {
		for (k = 0; k < 3; k++)
			dpdx[k] = dpdy[k] = 0.0f;
		return -1;
	}
	for (k = 0; k < 3; k++) {
		dpdx[k] -= c[k];
		dpdy[k] -= c[k];
	}
	return 0;
}

static void
random_pairs(void *ctx, int pattern, uint32_t x, uint32_t y, uint32_t frame, uint32_t i0,
             uint32_t n, uint32_t n_all, float *u0, float *u1)
{
	const rf_plugin_host *h = ctx;
	float ham0[64], ham1[64];
	uint32_t k, m, j;

	if (pattern == RF_SEQUENCE_WHITE) {
		rf__sequence_pairs(SEQUENCE_WHITE, h->table.seed, frame, 0, x, y, i0, n, NULL, NULL, u0,
		               u1);
		return;
	}
	/* the set's points, 64 at a time on the stack */
	for (k = 0; k < n; k += m) {
		m = n - k < 64 ? n - k : 64;
		for (j = 0; j < m; j++)
			rf__hammersley(i0 + k + j, n_all ? n_all : n, &ham0[j], &ham1[j]);
		rf__sequence_pairs(pattern == RF_SEQUENCE_BLUE ? SEQUENCE_BLUE : SEQUENCE_LOW_DISCREPANCY,
		               h->table.seed, frame, frame, x, y, i0 + k, m, ham0, ham1, u0 + k,
		               u1 + k);
	}
}

static float
probe_weights(void *ctx, const float p[3], float *weights)
{
	const rf_plugin_host *h = ctx;

	return rf_blend_weights(&h->blend, p, NULL, weights);
}

static int
declare_bevel(void *ctx, float radius, int grown)
{
	rf_plugin_host *h = ctx;
	struct rf_probe aligned;
	struct rf__frame frame;
	int rotated;

	if (!(radius >= 0.0f) || !h->table.probe ||
	    rf__probe_proxy_aligned(&h->probe, &aligned, &frame, &rotated) != RF_SHAPE_BOX ||
	    radius > rf__bevel_max_radius(&aligned))
		return -1;
	h->probe.bevel = radius;
	h->probe.bevel_grown = radius > 0.0f && grown;
	h->bevel = rf__bevel_of_probe(&aligned, radius, grown);
	sync_legacy(h);
	return 0;
}

const struct rf_probe *
rf_plugin_host_probe(const rf_plugin_host *h)
{
	return h->table.probe;
}

static int
filter_passes(void *ctx, uint32_t passes, const uint32_t *radius)
{
	rf_plugin_host *h = ctx;
	uint32_t i;

	if (passes < 1 || passes > RF_FILTER_PASSES_MAX || !radius)
		return -1;
	for (i = 0; i < passes; i++)
		if (radius[i] > RF_FILTER_RADIUS_MAX)
			return -1;
	h->filter_npasses = passes;
	memcpy(h->filter_radius, radius, passes * sizeof(*radius));
	return 0;
}

int
rf__host_is_own(const struct rf_host *table)
{
	return table && table->probe_weights == probe_weights && table->ctx;
}

uint32_t
rf__host_filter_passes(const struct rf_host *table, uint32_t *radius)
{
	rf_plugin_host *h = table->ctx;

	if (!h->filter_npasses) {
		radius[0] = 0;
		return 1;
	}
	memcpy(radius, h->filter_radius, h->filter_npasses * sizeof(*radius));
	return h->filter_npasses;
}

void
rf__host_filter_reset(const struct rf_host *table)
{
	((rf_plugin_host *)table->ctx)->filter_npasses = 0;
}

/* Box projection off in every probe of the frame's, as take_distant
 * asked, the first (probe) included. */
static void
distant_probes(rf_plugin_host *h)
{
	uint32_t i;

	for (i = 0; i < h->blend.nprobes; i++)
		h->blend.probes[i].box_projection = 0;
	sync_legacy(h);
}

void
rf__host_take_distant(const struct rf_host *table)
{
	rf_plugin_host *h;

	/* a table of the caller's own has no probe of this file's to mend */
	if (!rf__host_is_own(table) || !(h = table->ctx)->table.probe)
		return;
	h->distant = 1;
	h->probe.box_projection = 0;
	distant_probes(h);
}

static void
dfg(void *ctx, float n_dot_v, float roughness, float *a, float *b)
{
	(void)ctx;
	rf_dfg_lookup(n_dot_v, roughness, a, b);
}

int
rf_plugin_host_create(rf_plugin_host **hp)
{
	rf_plugin_host *h;

	if (!(*hp = h = calloc(1, sizeof(*h))))
		return RF_ENOMEM;
	h->table.size = sizeof(h->table);
	h->wide_rays = rf__lanes_wide();
	h->table.abi_major = RF_PLUGIN_ABI_MAJOR;
	h->table.abi_minor = RF_PLUGIN_ABI_MINOR;
	h->table.ctx = h;
	h->table.header_get = header_get;
	h->table.dfg = dfg;
	h->table.filter_passes = filter_passes;
	h->table.fail = fail;
	h->table.declare_bevel = declare_bevel;
	h->table.param_string = param_string;
	h->table.pixel_footprint = pixel_footprint;
	h->table.random_pairs = random_pairs;
	h->table.probes = h->blend.probes;
	h->table.probe_blend = h->blend.blend;
	h->table.probe_weights = probe_weights;
	h->mapping = RF_MAPPING_DEFAULT;
	sync_legacy(h);
	return 0;
}

static void
drop_radiance(rf_plugin_host *h)
{
	rf__rgba_levels_destroy(&h->levels);
	memset(&h->levels, 0, sizeof(h->levels));
	rf_cubemap_destroy(h->plain);
	h->plain = NULL;
	h->table.sample_radiance = NULL;
	h->table.env_size = h->table.env_levels = 0;
	sync_legacy(h);
}

void
rf_plugin_host_destroy(rf_plugin_host *h)
{
	if (!h)
		return;
	drop_radiance(h);
	rf__rgba_levels_destroy(&h->env_levels);
	free(h);
}

void
rf_plugin_host_set_frame(rf_plugin_host *h, const rf_header *frame)
{
	const char *v = frame ? rf_header_get(frame, RF_KEY_CAMERA) : NULL;
	struct rf_region full;
	double c[10];
	int k;

	h->frame = frame;
	h->has_camera = 0;
	/* the probe list, its first replaced by set_probe's */
	if (frame) {
		int n = rf_blend_read(&h->blend, frame, NULL, 0);

		h->table.nprobes = h->blend.nprobes = n > 0 ? (uint32_t)n : 0;
		if (h->table.nprobes && h->table.probe)
			h->blend.probes[0] = h->probe;
		rf_blend_order(&h->blend);
		if (h->distant)
			distant_probes(h);
		else
			sync_legacy(h);
	}
	if (!v || rf__scan_doubles(v, c, 10) < 0)
		return;
	for (k = 0; k < 3; k++) {
		h->camera.position[k] = c[k];
		h->camera.target[k] = c[3 + k];
		h->camera.up[k] = c[6 + k];
	}
	h->camera.fov = c[9];
	if (rf_camera_check(&h->camera, NULL, 0) < 0)
		return;
	/* a tile's rays are the full frame's: its size, not the tile's */
	if (rf_header_region(frame, &full) < 0)
		return;
	h->width = full.width;
	h->height = full.height;
	h->has_camera = 1;
}

/* A turned probe's environment is in its box's frame: its reads, the
 * raw radiance's too, take their directions there. */
static void
env_frame(rf_plugin_host *h)
{
	const float *turn = h->table.probe && h->probe.rotated ? h->probe.rotation : NULL;

	rf__rgba_levels_turn(&h->env_levels, turn);
	rf__rgba_levels_turn(&h->levels, turn);
}

void
rf_plugin_host_set_probe(rf_plugin_host *h, const struct rf_probe *probe)
{
	if (probe) {
		struct rf_probe aligned;
		struct rf__frame frame;
		int rotated;

		h->probe = *probe;
		h->proxy = rf__proxy_of_probe(probe);
		h->box = h->proxy.box;
		rf__probe_proxy_aligned(probe, &aligned, &frame, &rotated);
		h->bevel = rf__bevel_of_probe(&aligned, probe->bevel, probe->bevel_grown);
	}
	h->table.probe = probe ? &h->probe : NULL;
	if (probe) {
		h->blend.probes[0] = *probe;
		if (!h->table.nprobes) {
			h->table.nprobes = h->blend.nprobes = 1;
			h->blend.blend[0] = 0.0f;
			memset(h->blend.face_blend[0], 0, sizeof(h->blend.face_blend[0]));
			h->blend.importance[0] = 0.0f;
		}
		rf_blend_order(&h->blend);
	}
	h->table.project_rays = probe ? project_rays : NULL;
	env_frame(h);
	sync_legacy(h);
}

int
rf_plugin_host_set_environment(rf_plugin_host *h, const rf_cubemap *env,
                               enum rf_mapping mapping, float steps)
{
	int rc = 0;

	rf__rgba_levels_destroy(&h->env_levels);
	memset(&h->env_levels, 0, sizeof(h->env_levels));
	if (env && (rc = rf__rgba_levels_from_cube(&h->env_levels, env)) < 0)
		env = NULL;
	env_frame(h);
	h->env_vector = env ? rf__rgba_levels_simd_usable(&h->env_levels) : 0;
	h->env = env;
	h->mapping = mapping;
	h->steps = steps;
	h->table.sample = env ? sample : NULL;
	h->table.sample_many = env ? sample_many : NULL;
	h->table.face_size = env ? face_size : NULL;
	h->table.texel_solid_angle = env ? texel_solid_angle : NULL;
	h->table.roughness_to_lod = env ? roughness_to_lod : NULL;
	h->table.lod_to_roughness = env ? lod_to_roughness : NULL;
	h->table.lod_steps = env ? steps : 0.0f;
	sync_legacy(h);
	return rc;
}

int
rf_plugin_host_set_radiance(rf_plugin_host *h, const rf_cubemap *env)
{
	size_t size, levels;
	int rc;

	drop_radiance(h);
	if (!env)
		return 0;
	/* Level 0 as it is, then halved down to one texel. */
	size = rf_cubemap_size(env);
	for (levels = 1; (size >> (levels - 1)) > 1 && !((size >> (levels - 1)) & 1); levels++)
		;
	if ((rc = rf_cubemap_create(&h->plain, size, levels)) < 0)
		return rc;
	rf__cubemap_copy_level(h->plain, 0, env, 0);
	rf_cubemap_box_chain(h->plain, 0);
	if ((rc = rf__rgba_levels_from_cube(&h->levels, h->plain)) < 0) {
		drop_radiance(h);
		return rc;
	}
	h->vector = rf__rgba_levels_simd_usable(&h->levels);
	env_frame(h);
	h->table.sample_radiance = sample_radiance;
	h->table.env_size = (uint32_t)size;
	h->table.env_levels = (uint32_t)levels;
	sync_legacy(h);
	return 0;
}

void
rf_plugin_host_set_seed(rf_plugin_host *h, uint32_t seed)
{
	h->table.seed = seed;
	sync_legacy(h);
}

const struct rf_host *
rf__host_for_plugin(const struct rf_host *table, const struct rf_plugin *p, char *err,
                    size_t errlen)
{
	const rf_plugin_host *h;
	uint32_t i;

	/* only this file's tables know a legacy view; others are the caller's */
	if (p->abi_minor >= 2 || !table || table->probe_weights != probe_weights)
		return table;
	h = table->ctx;
	if (p->kind == RF_KIND_PROJECTION || p->kind == RF_KIND_SHADE ||
	    p->kind == RF_KIND_OCCLUSION)
		for (i = 0; i < h->blend.nprobes; i++)
			if (probe_shaped(&h->blend.probes[i])) { /* [0] is probe */
				rf__format(err, errlen, "mode '%s' was built for plugin ABI %u.%u, "
				           "which knows axis-aligned probe boxes only, and probe "
				           "%u is %s: rebuild the mode against this reflect's "
				           "<reflect/plugin.h> (ABI %d.%d)", p->name,
				           p->abi_major, p->abi_minor, (unsigned)i + 1,
				           h->blend.probes[i].shape == RF_SHAPE_SPHERE
				               ? "a sphere"
				               : h->blend.probes[i].rotated
				                     ? "a rotated box"
				                     : "projected onto a proxy of its own",
				           RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR);
				return NULL;
			}
	return &h->legacy;
}

const struct rf_host *
rf_plugin_host_table(const rf_plugin_host *h)
{
	return &h->table;
}
