/* Rendering the G-buffer a block of rows at a time, rows spread over
 * threads; every pixel depends on its own ray only, so the bytes do not
 * depend on the thread count. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "util/pool.h"
#include "scene/accel.h"

enum {
	CH_PX, CH_PY, CH_PZ, CH_NX, CH_NY, CH_NZ, CH_NGX, CH_NGY, CH_NGZ,
	CH_VX, CH_VY, CH_VZ, CH_ROUGHNESS, CH_METALLIC, CH_ALBEDO_R, CH_ALBEDO_G,
	CH_ALBEDO_B, CH_MASK, CH_OBJID, CH_DEPTH,
	/* what the surface emits: by default when the scene has emission */
	CH_ER, CH_EG, CH_EB,
	/* on request only (-c T): three more floats a pixel on every stream
	 * for the few models that have a direction on the surface */
	CH_TX, CH_TY, CH_TZ, CH_COUNT
};

/* The channels written when none are asked for: all but the tangent and
 * the emission (added for scenes that emit). */
#define CH_DEFAULT (CH_DEPTH + 1)

static const char *const channel_names[CH_COUNT] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "Ng.X", "Ng.Y", "Ng.Z",
	"V.X", "V.Y", "V.Z", "roughness", "metallic", "albedo.R", "albedo.G",
	"albedo.B", "mask", "objid", "depth", "emission.R", "emission.G", "emission.B",
	"T.X", "T.Y", "T.Z"
};

/* Layer names that stand for three channels. */
static const struct {
	const char *name;
	int first;
} layers[] = {
	{ "P", CH_PX }, { "N", CH_NX }, { "Ng", CH_NGX }, { "V", CH_VX },
	{ "albedo", CH_ALBEDO_R }, { "T", CH_TX }, { "emission", CH_ER },
};


/* Pixels (inclusive) outside of which a ray cannot meet an object or a
 * mesh: the rest see the room alone, without a search. */
struct bounds {
	long x0, x1, y0, y1;
};

struct rf_gbuffer {
	const rf_scene *s;
	size_t width, height;
	size_t col0, ncols; /* the columns rendered (rf_gbuffer_set_columns) */
	int nthreads;
	size_t nch;
	int map[CH_COUNT]; /* output channel -> value index */
	int identity;      /* map[c] == c for the first nch channels */
	int emission;      /* an emission channel is written */
	struct rf_camera cam;
	struct camera_basis cb;
	double *k; /* per-object constants for rays from the camera */
	struct bounds *bounds; /* per object then mesh, where it can be on the image */
	size_t nbounds;
	uint32_t *scratch;     /* per thread: the boxes of a row */
	double *rays;          /* per thread: a row of directions, reciprocals */
	/* Kept from block to block, so that a frame of many blocks starts its
	 * threads once; NULL for one thread or if none could be had: the
	 * caller renders alone. */
	struct rf__pool *pool;
};

/* A block being rendered. */
struct block {
	const rf_gbuffer *g;
	float *out;
	size_t y;
};

static int
add_channel(rf_gbuffer *g, int c, char *err, size_t errlen)
{
	size_t i;

	for (i = 0; i < g->nch; i++)
		if (g->map[i] == c) {
			rf__format(err, errlen, "G-buffer channel '%s' is asked for twice",
			           channel_names[c]);
			return RF_ECHANNEL;
		}
	g->map[g->nch++] = c;
	return 0;
}

static int
select_channels(rf_gbuffer *g, const char *list, char *err, size_t errlen)
{
	const char *p = list;
	size_t n, i;
	int c, rc;

	if (!list) {
		int count = CH_DEFAULT + (g->s->has_emission ? 3 : 0);

		for (c = 0; c < count; c++)
			g->map[c] = c;
		g->nch = (size_t)count;
		return 0;
	}
	while (*p) {
		while (*p == ' ' || *p == ',' || *p == '\t')
			p++;
		if (!*p)
			break;
		n = strcspn(p, " ,\t");
		for (c = 0; c < CH_COUNT; c++)
			if (strlen(channel_names[c]) == n && !memcmp(channel_names[c], p, n))
				break;
		if (c < CH_COUNT) {
			if ((rc = add_channel(g, c, err, errlen)) < 0)
				return rc;
		} else {
			for (i = 0; i < sizeof(layers) / sizeof(layers[0]); i++)
				if (strlen(layers[i].name) == n && !memcmp(layers[i].name, p, n))
					break;
			if (i == sizeof(layers) / sizeof(layers[0])) {
				rf__format(err, errlen, "unknown G-buffer channel '%.*s' "
				           "(expected P, N, Ng, T, V, roughness, metallic, "
				           "albedo, mask, objid, depth, emission or a component "
				           "such as P.X)",
				           (int)(n > 64 ? 64 : n), p);
				return RF_ECHANNEL;
			}
			for (c = layers[i].first; c < layers[i].first + 3; c++)
				if ((rc = add_channel(g, c, err, errlen)) < 0)
					return rc;
		}
		p += n;
	}
	if (!g->nch) {
		rf__format(err, errlen, "no G-buffer channel asked for");
		return RF_ECHANNEL;
	}
	return 0;
}

int
rf_gbuffer_create(rf_gbuffer **gp, const rf_scene *s, size_t width, size_t height,
                  const char *channels, int nthreads, char *err, size_t errlen)
{
	rf_gbuffer *g;
	size_t bytes, i;
	int rc;

	*gp = NULL;
	if (!width || !height || rf__mul3(width, CH_COUNT, sizeof(float), &bytes) ||
	    bytes > RF_ROW_BYTES_MAX) {
		rf__format(err, errlen, "image size %zux%zu is out of range", width, height);
		return RF_ETOOBIG;
	}
	if (!(g = calloc(1, sizeof(*g))))
		return RF_ENOMEM;
	g->s = s;
	g->width = width;
	g->ncols = width;
	g->height = height;
	g->nthreads = nthreads < 1 ? 1 : nthreads > RF__THREADS_MAX ? RF__THREADS_MAX : nthreads;
	if ((rc = select_channels(g, channels, err, errlen)) < 0) {
		free(g);
		return rc;
	}
	g->identity = g->nch <= CH_ER + 3;
	for (i = 0; i < g->nch; i++) {
		g->identity &= g->map[i] == (int)i;
		g->emission |= g->map[i] >= CH_ER && g->map[i] <= CH_EB;
	}
	/* the identity writes every value straight out: all or none of the
	 * emission */
	g->identity &= g->nch == CH_DEFAULT || g->nch == CH_ER + 3;
	g->k = calloc(s->nobjects + 1, RF__ORIGIN_STRIDE * sizeof(double));
	g->nbounds = s->nobjects + s->nmeshes;
	g->bounds = calloc(g->nbounds + 1, sizeof(*g->bounds));
	g->scratch = calloc((size_t)g->nthreads * (g->nbounds + 1), sizeof(uint32_t));
	g->rays = malloc((size_t)g->nthreads * width * 6 * sizeof(double));
	if (!g->k || !g->bounds || !g->scratch || !g->rays) {
		rf_gbuffer_destroy(g);
		return RF_ENOMEM;
	}
	/* The scene's ray casting structure, now rather than in a row. */
	if ((s->nobjects || s->nmeshes) && !rf__accel_get(s, err, errlen)) {
		rf_gbuffer_destroy(g);
		return RF_ENOMEM;
	}
	if (g->nthreads > 1)
		rf__pool_create(&g->pool, g->nthreads);
	rf_gbuffer_set_camera(g, &s->camera, NULL, 0);
	*gp = g;
	return 0;
}

void
rf_gbuffer_destroy(rf_gbuffer *g)
{
	if (!g)
		return;
	rf__pool_destroy(g->pool);
	free(g->k);
	free(g->bounds);
	free(g->scratch);
	free(g->rays);
	free(g);
}

size_t
rf_gbuffer_nchannels(const rf_gbuffer *g)
{
	return g->nch;
}

const char *
rf_gbuffer_channel(const rf_gbuffer *g, size_t i)
{
	return i < g->nch ? channel_names[g->map[i]] : NULL;
}

static long
clamp_pixel(double v, size_t n)
{
	return v < -2.0 ? -2 : v > (double)n + 2.0 ? (long)n + 2 : (long)v;
}

/* The image rectangle that holds the projection of an object's bounding
 * box, a pixel wider on every side against rounding.  Rays through other
 * pixel centres cannot meet the object, since a ray's points all project
 * onto its pixel centre.  A mesh's box is its bounds, a float's rounding
 * wider. */
static void
box_bounds(const rf_gbuffer *g, const double bmin[3], const double bmax[3], struct bounds *b)
{
	const struct camera_basis *cb = &g->cb;
	double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
	int corner, behind = 0, i;

	for (corner = 0; corner < 8; corner++) {
		double rel[3], z, x, y;

		for (i = 0; i < 3; i++)
			rel[i] = ((corner >> i) & 1 ? bmax[i] : bmin[i]) - g->cam.position[i];
		z = rf__dot(rel, cb->f);
		if (!(z > 1e-9)) {
			behind++;
			continue;
		}
		x = rf__dot(rel, cb->r) / (z * cb->tx);
		y = rf__dot(rel, cb->u) / (z * cb->ty);
		xmin = x < xmin ? x : xmin;
		xmax = x > xmax ? x : xmax;
		ymin = y < ymin ? y : ymin;
		ymax = y > ymax ? y : ymax;
	}
	if (behind == 8) {
		/* Every ray leans forward: nothing behind the eye is seen. */
		b->x0 = b->y0 = 1;
		b->x1 = b->y1 = 0;
		return;
	}
	if (behind) {
		b->x0 = b->y0 = -2;
		b->x1 = (long)g->width + 2;
		b->y1 = (long)g->height + 2;
		return;
	}
	/* Pixel i's centre is at x = 2 (i + 0.5) / W - 1. */
	b->x0 = clamp_pixel(floor((xmin + 1.0) * 0.5 * (double)g->width - 0.5) - 1.0, g->width);
	b->x1 = clamp_pixel(ceil((xmax + 1.0) * 0.5 * (double)g->width - 0.5) + 1.0, g->width);
	b->y0 = clamp_pixel(floor((1.0 - ymax) * 0.5 * (double)g->height - 0.5) - 1.0,
	                    g->height);
	b->y1 = clamp_pixel(ceil((1.0 - ymin) * 0.5 * (double)g->height - 0.5) + 1.0,
	                    g->height);
}

int
rf_gbuffer_set_camera(rf_gbuffer *g, const struct rf_camera *cam, char *err,
                      size_t errlen)
{
	size_t i;
	int rc;

	if ((rc = rf_camera_check(cam, err, errlen)) < 0)
		return rc;
	g->cam = *cam;
	rf__camera_basis(cam, g->width, g->height, &g->cb);
	rf__trace_prepare(g->s, cam->position, g->k);
	for (i = 0; i < g->s->nobjects; i++)
		box_bounds(g, g->s->objects[i].min, g->s->objects[i].max, &g->bounds[i]);
	for (i = 0; i < g->s->nmeshes; i++) {
		const float *mb = g->s->meshes[i].bounds;
		double lo[3], hi[3];
		int j;

		for (j = 0; j < 3; j++) {
			const double pad = 1e-6 * (1.0 + fmax(fabs(mb[j]), fabs(mb[j + 3])));

			lo[j] = mb[j] - pad;
			hi[j] = mb[j + 3] + pad;
		}
		box_bounds(g, lo, hi, &g->bounds[g->s->nobjects + i]);
	}
	return 0;
}

/* One pixel's channels from its ray's hit. */
static void
write_pixel(const rf_gbuffer *g, const struct rf_hit *hit, const double d[3], float *out)
{
	float tmp[CH_COUNT], *v;
	size_t c;

	/* All channels in their order (the usual case) go straight out. */
	v = g->identity ? out : tmp;
	v[CH_PX] = (float)hit->P[0];
	v[CH_PY] = (float)hit->P[1];
	v[CH_PZ] = (float)hit->P[2];
	v[CH_NX] = (float)hit->N[0];
	v[CH_NY] = (float)hit->N[1];
	v[CH_NZ] = (float)hit->N[2];
	v[CH_NGX] = (float)hit->Ng[0];
	v[CH_NGY] = (float)hit->Ng[1];
	v[CH_NGZ] = (float)hit->Ng[2];
	/* P lies on the ray, so the way back to the eye is -d exactly. */
	v[CH_VX] = (float)-d[0];
	v[CH_VY] = (float)-d[1];
	v[CH_VZ] = (float)-d[2];
	v[CH_ROUGHNESS] = hit->roughness;
	v[CH_METALLIC] = hit->metallic;
	v[CH_ALBEDO_R] = hit->albedo[0];
	v[CH_ALBEDO_G] = hit->albedo[1];
	v[CH_ALBEDO_B] = hit->albedo[2];
	v[CH_MASK] = hit->mask;
	v[CH_OBJID] = (float)hit->objid;
	v[CH_DEPTH] = (float)hit->t;
	if (g->emission) {
		float e[3];

		rf__radiance(g->s, hit, e);
		v[CH_ER] = e[0];
		v[CH_EG] = e[1];
		v[CH_EB] = e[2];
	}
	if (!g->identity) {
		/* the identity's out has no room for them */
		v[CH_TX] = (float)hit->T[0];
		v[CH_TY] = (float)hit->T[1];
		v[CH_TZ] = (float)hit->T[2];
	}
	if (!g->identity)
		for (c = 0; c < g->nch; c++)
			out[c] = v[g->map[c]];
}

/* Row `task` of the block, with thread `thread`'s scratch. */
static void
render_row(void *arg, size_t task, int thread)
{
	const struct block *bk = arg;
	const rf_gbuffer *g = bk->g;
	size_t y = bk->y + task;
	float *out = bk->out + task * g->ncols * g->nch;
	double *rays = g->rays + (size_t)thread * g->width * 6;
	const double *o = g->cam.position;
	double sy = 1.0 - (2.0 * (double)y + 1.0) / (double)g->height;
	struct rf_hit hit[8];
	uint32_t *row_list = g->scratch + (size_t)thread * (g->nbounds + 1);
	size_t x, x0, i, nrow = 0;

	for (i = 0; i < g->nbounds; i++)
		if (g->bounds[i].y0 <= (long)y && (long)y <= g->bounds[i].y1)
			row_list[nrow++] = (uint32_t)i;
	/* The row's rays first: a loop of independent square roots and
	 * divisions runs at their throughput, not at their latency. */
	for (x = g->col0; x < g->col0 + g->ncols; x++) {
		double *ray = rays + 6 * x;

		rf__camera_dir(&g->cb, (2.0 * (double)x + 1.0) / (double)g->width - 1.0, sy,
		               ray);
		ray[3] = 1.0 / ray[0];
		ray[4] = 1.0 / ray[1];
		ray[5] = 1.0 / ray[2];
	}
	/* Eight pixels at a time: neighbours' rays go through the BVH as one
	 * packet (rf__trace8), with the same hits as one by one. */
	for (x0 = g->col0; x0 < g->col0 + g->ncols; x0 += 8) {
		const size_t end = g->col0 + g->ncols;
		const int n = end - x0 < 8 ? (int)(end - x0) : 8;
		const double *d[8], *inv[8];
		unsigned flags[8];
		int j;

		for (j = 0; j < n; j++) {
			x = x0 + (size_t)j;
			d[j] = rays + 6 * x;
			inv[j] = d[j] + 3;
			flags[j] = RF__TRACE_ROOM_ONLY;
			for (i = 0; i < nrow; i++) {
				const struct bounds *b = &g->bounds[row_list[i]];

				if (b->x0 <= (long)x && (long)x <= b->x1) {
					flags[j] = 0;
					break;
				}
			}
		}
		rf__trace8(g->s, o, g->k, n, d, inv, flags, hit);
		for (j = 0; j < n; j++)
			write_pixel(g, &hit[j], d[j], out + (x0 - g->col0 + (size_t)j) * g->nch);
	}
}

int
rf_gbuffer_set_columns(rf_gbuffer *g, size_t x0, size_t ncols)
{
	if (!ncols || x0 > g->width || ncols > g->width - x0)
		return RF_EINVAL;
	g->col0 = x0;
	g->ncols = ncols;
	return 0;
}

int
rf_gbuffer_render(rf_gbuffer *g, float *out, size_t y, size_t nrows)
{
	struct block bk;
	size_t r;

	if (y > g->height || nrows > g->height - y)
		return RF_EINVAL;
	if (!nrows)
		return 0;
	bk.g = g;
	bk.out = out;
	bk.y = y;
	/* A row is a task: threads that start late or run slow take fewer. */
	if (g->pool)
		rf__pool_run(g->pool, nrows, render_row, &bk);
	else
		for (r = 0; r < nrows; r++)
			render_row(&bk, r, 0);
	return 0;
}
