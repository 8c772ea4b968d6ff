/*
 * The scene's acceleration structure: one Embree 3 scene per rf_scene,
 * its meshes as triangle geometry on their own buffers, its analytic
 * objects as one user geometry whose intersection runs raycast.c's
 * double-precision arithmetic.
 *
 * Embree sees the ray in single precision; the objects are decided in
 * double.  The ray's double origin and direction, and the nearest object
 * so far, travel in the intersect context (struct ctx), so a callback
 * compares exact distances, ties to the lower index as a loop over the
 * objects would.  Embree's own float tfar only culls, and is kept a
 * little beyond the exact distance, with the objects' boxes grown by a
 * margin that covers the float ray's deviation, so that nothing nearer is
 * culled.  The room (probe 0's box seen from inside) stays outside: every
 * ray starts in it, so its box culls nothing, and rf__trace tries it last
 * as before.
 *
 * Rays that leave together go down the BVH eight at a time
 * (rtcIntersect8): the callback serves any number of lanes, each finding
 * its double ray by the ray's id, and the winner's refinement is the
 * single ray's, so a packet's hits are the single rays' to the bit.
 *
 * One device per scene: the library keeps no process-wide state, and a
 * device with the BVH of a few objects costs under half a millisecond
 * (bench/mesh-bench).  The BVH is built on one thread ("threads=1"): the
 * tools thread over rows themselves, the build stays the same at any -j
 * (so does which of two triangles sharing an edge a ray meets), and
 * Embree's task scheduler keeps one thread of its own, idle while the
 * tools render.
 */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include <embree3/rtcore.h>

#include "scene/accel.h"

/* Geometry masks: a triangle of a reflective material (mask > 0), or
 * anything else; rays that pass reflective surfaces see only the latter
 * among the triangles (objects are sorted in the callback). */
#define GMASK_OTHER 1u
#define GMASK_REFLECTIVE 2u

/* How far the float ray may stray from the double one, relative to the
 * scene's size: some hundred times float's epsilon. */
#define MARGIN_REL 1e-5

/* A triangle geometry: which mesh, and its triangles' indices in the mesh
 * when it holds a part of them (NULL: all, in order). */
struct tri_geom {
	int mesh;
	uint32_t *map;
	uint32_t *indices; /* the part's own index buffer, or NULL */
};

struct rf__accel {
	RTCDevice dev;
	RTCScene scene;
	unsigned user_id; /* the objects' geometry, or RTC_INVALID_GEOMETRY_ID */
	struct tri_geom *geoms; /* by geometry id (the user one's unused) */
	size_t ngeoms;
	const rf_scene *s;
	float margin;
};

/* What a ray carries to the callbacks: Embree's context first, so that a
 * callback's context pointer is this.  A packet's lanes are found by the
 * ray's id, which is the lane's index. */
struct ctx {
	struct RTCIntersectContext rtc;
	const rf_scene *s;
	const struct rf__lane *lane;
	struct rf__candidate *best; /* by lane */
	const double *o, *d, *inv; /* an occlusion query's ray */
	double tmax; /* an occlusion query's end */
};

/* Fields of a packet of N rays (RTCRayHitN), one float or unsigned per
 * lane, in the order of struct RTCRayHit; a single ray is N = 1. */
#define RAYN_TFAR 8
#define RAYN_ID 10
#define HITN_U 15
#define HITN_V 16
#define HITN_PRIM 17
#define HITN_GEOM 18

static float
round_down(double v)
{
	float f = (float)v;

	return (double)f > v ? nextafterf(f, -INFINITY) : f;
}

static float
round_up(double v)
{
	float f = (float)v;

	return (double)f < v ? nextafterf(f, INFINITY) : f;
}

static void
object_bounds(const struct RTCBoundsFunctionArguments *args)
{
	const struct rf__accel *a = args->geometryUserPtr;
	const struct object *ob = &a->s->objects[args->primID];
	struct RTCBounds *b = args->bounds_o;

	b->lower_x = round_down(ob->min[0] - a->margin);
	b->lower_y = round_down(ob->min[1] - a->margin);
	b->lower_z = round_down(ob->min[2] - a->margin);
	b->upper_x = round_up(ob->max[0] + a->margin);
	b->upper_y = round_up(ob->max[1] + a->margin);
	b->upper_z = round_up(ob->max[2] + a->margin);
}

/* Any number of rays: rtcIntersect1 calls with one, rtcIntersect8 with
 * up to eight, the lanes not asked for invalid. */
static void
object_intersect(const struct RTCIntersectFunctionNArguments *args)
{
	const struct ctx *c = (const struct ctx *)args->context;
	const rf_scene *s = c->s;
	const size_t i = args->primID;
	const struct object *ob = &s->objects[i];
	const unsigned N = args->N;
	float *fr = (float *)args->rayhit;
	unsigned *ur = (unsigned *)args->rayhit;
	const float margin = ((const struct rf__accel *)args->geometryUserPtr)->margin;
	unsigned j;

	for (j = 0; j < N; j++) {
		const struct rf__lane *l;
		struct rf__candidate cand, *best;
		float far;

		if (!args->valid[j])
			continue;
		l = &c->lane[ur[RAYN_ID * N + j]];
		best = &c->best[ur[RAYN_ID * N + j]];
		if ((l->flags & RF__TRACE_SKIP_REFLECTIVE) && ob->mat.mask > 0.0f)
			continue;
		if (!rf__object_hit(ob, l->k ? l->k + i * RF__ORIGIN_STRIDE : NULL, l->o, l->d,
		                    l->inv, &cand))
			continue;
		if (!(cand.t < best->t || (cand.t == best->t && (int)i < best->index)))
			continue;
		cand.index = (int)i;
		*best = cand;
		/* Culling only, and never short of the exact distance. */
		far = round_up(cand.t * (1.0 + MARGIN_REL) + (double)margin);
		if (far < fr[RAYN_TFAR * N + j]) {
			fr[RAYN_TFAR * N + j] = far;
			ur[HITN_GEOM * N + j] = args->geomID;
			ur[HITN_PRIM * N + j] = args->primID;
		}
	}
}

/* A shadow ray: any object before its end stops it. */
static void
object_occluded(const struct RTCOccludedFunctionNArguments *args)
{
	const struct ctx *c = (const struct ctx *)args->context;
	const struct object *ob = &c->s->objects[args->primID];
	struct RTCRay *ray = (struct RTCRay *)args->ray;
	struct rf__candidate cand;

	/* rtcOccluded1 only: one ray, valid */
	if (!args->valid[0])
		return;
	if (rf__object_hit(ob, NULL, c->o, c->d, c->inv, &cand) && cand.t < c->tmax)
		ray->tfar = -INFINITY; /* Embree's mark of an occluded ray */
}

void
rf__accel_destroy(struct rf__accel *a)
{
	size_t i;

	if (!a)
		return;
	if (a->scene)
		rtcReleaseScene(a->scene);
	if (a->dev)
		rtcReleaseDevice(a->dev);
	for (i = 0; i < a->ngeoms; i++) {
		free(a->geoms[i].map);
		free(a->geoms[i].indices);
	}
	free(a->geoms);
	free(a);
}

static int
remember(struct rf__accel *a, unsigned id, int mesh, uint32_t *map, uint32_t *indices)
{
	struct tri_geom *g;
	size_t i;

	if (id >= a->ngeoms) {
		if (!(g = realloc(a->geoms, (id + 1) * sizeof(*g)))) {
			free(map);
			free(indices);
			return RF_ENOMEM;
		}
		for (i = a->ngeoms; i <= id; i++)
			g[i].mesh = -1, g[i].map = NULL, g[i].indices = NULL;
		a->geoms = g;
		a->ngeoms = id + 1;
	}
	a->geoms[id].mesh = mesh;
	a->geoms[id].map = map;
	a->geoms[id].indices = indices;
	return 0;
}

/* One triangle geometry over a mesh's shared vertices: all its triangles
 * (map NULL, the mesh's own indices) or those listed in map. */
static int
add_triangles(struct rf__accel *a, const struct rf__mesh *m, int mesh, uint32_t *map,
              size_t n, unsigned gmask)
{
	RTCGeometry g = rtcNewGeometry(a->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
	uint32_t *indices = NULL;
	unsigned id;
	size_t i;

	if (!g) {
		free(map);
		return RF_ENOMEM;
	}
	if (map) {
		if (!(indices = malloc(3 * n * sizeof(*indices)))) {
			rtcReleaseGeometry(g);
			free(map);
			return RF_ENOMEM;
		}
		for (i = 0; i < n; i++)
			memcpy(indices + 3 * i, m->indices + 3 * (size_t)map[i], 3 * sizeof(*indices));
	}
	/* rf__scene_add_mesh pads positions by a float: Embree reads the last
	 * vertex with a 16-byte load */
	rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m->positions,
	                           0, 3 * sizeof(float), m->nvertices);
	rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
	                           indices ? indices : m->indices, 0, 3 * sizeof(uint32_t), n);
	rtcSetGeometryMask(g, gmask);
	rtcCommitGeometry(g);
	id = rtcAttachGeometry(a->scene, g);
	rtcReleaseGeometry(g);
	return remember(a, id, mesh, map, indices);
}

static int
reflective(const struct rf__mesh *m, size_t tri)
{
	return rf__mesh_material_of(m, (uint32_t)tri)->mask > 0.0f;
}

static int
add_mesh(struct rf__accel *a, const struct rf__mesh *m, int mesh)
{
	size_t i, nrefl = 0, j0 = 0, j1 = 0;
	uint32_t *refl, *other;
	int rc;

	for (i = 0; i < m->ntriangles; i++)
		nrefl += (size_t)reflective(m, i);
	if (nrefl == 0 || nrefl == m->ntriangles)
		return add_triangles(a, m, mesh, NULL, m->ntriangles,
		                     nrefl ? GMASK_REFLECTIVE : GMASK_OTHER);
	/* Both kinds: two geometries on the same vertices. */
	refl = malloc(nrefl * sizeof(*refl));
	other = malloc((m->ntriangles - nrefl) * sizeof(*other));
	if (!refl || !other) {
		free(refl);
		free(other);
		return RF_ENOMEM;
	}
	for (i = 0; i < m->ntriangles; i++) {
		if (reflective(m, i))
			refl[j0++] = (uint32_t)i;
		else
			other[j1++] = (uint32_t)i;
	}
	if ((rc = add_triangles(a, m, mesh, refl, nrefl, GMASK_REFLECTIVE)) < 0) {
		free(other);
		return rc;
	}
	return add_triangles(a, m, mesh, other, m->ntriangles - nrefl, GMASK_OTHER);
}

static double
scene_size(const rf_scene *s)
{
	double L = fmax(fabs(s->camera.position[0]),
	                fmax(fabs(s->camera.position[1]), fabs(s->camera.position[2])));
	size_t i;
	int j;

	for (i = 0; i < s->nobjects; i++)
		for (j = 0; j < 3; j++)
			L = fmax(L, fmax(fabs(s->objects[i].min[j]), fabs(s->objects[i].max[j])));
	for (i = 0; i < s->nmeshes; i++)
		for (j = 0; j < 6; j++)
			L = fmax(L, fabs((double)s->meshes[i].bounds[j]));
	for (i = 0; i < s->nprobes; i++) {
		const struct rf_scene_probe *p = &s->probes[i];
		double half = 0.0;

		/* a turned box reaches no further from its centre than its
		 * half diagonal */
		for (j = 0; j < 3; j++)
			half += 0.25 * (p->box_max[j] - p->box_min[j]) * (p->box_max[j] - p->box_min[j]);
		half = sqrt(half);
		for (j = 0; j < 3; j++)
			L = fmax(L, p->rotated ? fabs(0.5 * (p->box_min[j] + p->box_max[j])) + half
			                       : fmax(fabs(p->box_min[j]), fabs(p->box_max[j])));
	}
	return L;
}

static int
build(const rf_scene *s, struct rf__accel **ap, char *err, size_t errlen)
{
	struct rf__accel *a = calloc(1, sizeof(*a));
	enum RTCError e;
	size_t i;
	int rc = 0;

	*ap = NULL;
	if (!a)
		return RF_ENOMEM;
	a->s = s;
	a->user_id = RTC_INVALID_GEOMETRY_ID;
	a->margin = (float)(MARGIN_REL * (1.0 + scene_size(s)));
	if (!(a->dev = rtcNewDevice("threads=1,set_affinity=0"))) {
		rf__format(err, errlen, "cannot start Embree: %s",
		           rtcGetDeviceError(NULL) == RTC_ERROR_UNSUPPORTED_CPU
		                   ? "this CPU is not supported" : "out of memory");
		free(a);
		return RF_ENOMEM;
	}
	if (!(a->scene = rtcNewScene(a->dev))) {
		rc = RF_ENOMEM;
		goto fail;
	}
	rtcSetSceneBuildQuality(a->scene, RTC_BUILD_QUALITY_MEDIUM);
	for (i = 0; i < s->nmeshes && rc == 0; i++) {
		((struct rf__mesh *)&s->meshes[i])->objid = (int)(s->nobjects + 1 + i);
		rc = add_mesh(a, &s->meshes[i], (int)i);
	}
	if (rc == 0 && s->nobjects) {
		RTCGeometry g = rtcNewGeometry(a->dev, RTC_GEOMETRY_TYPE_USER);

		if (!g) {
			rc = RF_ENOMEM;
			goto fail;
		}
		rtcSetGeometryUserPrimitiveCount(g, (unsigned)s->nobjects);
		rtcSetGeometryUserData(g, a);
		rtcSetGeometryBoundsFunction(g, object_bounds, NULL);
		rtcSetGeometryIntersectFunction(g, object_intersect);
		rtcSetGeometryOccludedFunction(g, object_occluded);
		rtcSetGeometryMask(g, GMASK_OTHER | GMASK_REFLECTIVE);
		rtcCommitGeometry(g);
		a->user_id = rtcAttachGeometry(a->scene, g);
		rtcReleaseGeometry(g);
	}
	if (rc < 0)
		goto fail;
	rtcCommitScene(a->scene);
	if ((e = rtcGetDeviceError(a->dev)) != RTC_ERROR_NONE) {
		rc = e == RTC_ERROR_OUT_OF_MEMORY ? RF_ENOMEM : RF_EINVAL;
		rf__format(err, errlen, "cannot build the scene's ray casting structure "
		           "(Embree error %d)", (int)e);
		goto fail;
	}
	*ap = a;
	return 0;
fail:
	if (rc == RF_ENOMEM)
		rf__format(err, errlen, "%s", rf_strerror(rc));
	rf__accel_destroy(a);
	return rc;
}

const struct rf__accel *
rf__accel_get(const rf_scene *cs, char *err, size_t errlen)
{
	rf_scene *s = (rf_scene *)cs; /* the structure is a cache of the scene */
	struct rf__accel *a = atomic_load_explicit(&s->accel, memory_order_acquire);

	if (a)
		return a;
	pthread_mutex_lock(&s->accel_lock);
	if (!(a = atomic_load_explicit(&s->accel, memory_order_relaxed)) &&
	    build(s, &a, err, errlen) == 0)
		atomic_store_explicit(&s->accel, a, memory_order_release);
	pthread_mutex_unlock(&s->accel_lock);
	return a;
}

/* The winner of lane l again in double: its triangle (geometry g,
 * primitive prim, Embree's float t, u and v) into *mh, unless an object
 * lies as near.  One helper for rf__accel_intersect and its packets, so
 * that both give the same bits. */
static void
refine(const struct rf__accel *a, const rf_scene *s, const struct rf__lane *l,
       unsigned geom, unsigned primid, float tfar, float u, float v,
       const struct rf__candidate *best, struct rf__mesh_hit *mh)
{
	const struct tri_geom *g;
	const struct rf__mesh *m;
	const double *o = l->o, *d = l->d;
	uint32_t prim;
	const uint32_t *ix;
	double v0[3], e1[3], e2[3], pv[3], tv[3], qv[3], det;
	int j;

	mh->mesh = -1;
	if (geom == RTC_INVALID_GEOMETRY_ID || geom == a->user_id)
		return;
	g = &a->geoms[geom];
	m = &s->meshes[g->mesh];
	prim = g->map ? g->map[primid] : primid;
	ix = m->indices + 3 * (size_t)prim;
	for (j = 0; j < 3; j++) {
		v0[j] = m->positions[3 * (size_t)ix[0] + j];
		e1[j] = (double)m->positions[3 * (size_t)ix[1] + j] - v0[j];
		e2[j] = (double)m->positions[3 * (size_t)ix[2] + j] - v0[j];
		tv[j] = o[j] - v0[j];
	}
	/* Moeller-Trumbore: P = o + t d on the ray, and on the triangle's
	 * plane to double's precision, where Embree's float t would leave it
	 * off by some 1e-7 t. */
	rf__cross(d, e2, pv);
	det = rf__dot(e1, pv);
	mh->mesh = g->mesh;
	mh->prim = prim;
	if (fabs(det) > 1e-300) {
		const double id = 1.0 / det;

		rf__cross(tv, e1, qv);
		mh->b1 = rf__dot(tv, pv) * id;
		mh->b2 = rf__dot(d, qv) * id;
		mh->t = rf__dot(e2, qv) * id;
	}
	if (!(fabs(det) > 1e-300) || !(mh->t > 0.0) || !isfinite(mh->t)) {
		/* edge-on: Embree's own values */
		mh->t = tfar;
		mh->b1 = u;
		mh->b2 = v;
	}
	/* An object at the same distance wins, as it would have first. */
	if (best->t <= mh->t)
		mh->mesh = -1;
}

/* Triangles are single precision: a ray leaving a mesh's surface would
 * meet its own triangle a float's error away.  Objects ignore it (their
 * callback starts at raycast.c's own bound). */
static float
ray_tnear(const double o[3])
{
	return (float)(MARGIN_REL * (1.0 + fmax(fabs(o[0]), fmax(fabs(o[1]), fabs(o[2])))));
}

static unsigned
ray_mask(unsigned flags)
{
	return flags & RF__TRACE_SKIP_REFLECTIVE ? GMASK_OTHER : GMASK_OTHER | GMASK_REFLECTIVE;
}

void
rf__accel_intersect(const struct rf__accel *a, const rf_scene *s, const double o[3],
                    const double *k, const double d[3], const double inv[3], unsigned flags,
                    struct rf__candidate *best, struct rf__mesh_hit *mh)
{
	const struct rf__lane l = { o, k, d, inv, flags };
	struct ctx c;
	struct RTCRayHit rh;

	rtcInitIntersectContext(&c.rtc);
	c.s = s;
	c.lane = &l;
	c.best = best;
	rh.ray.org_x = (float)o[0];
	rh.ray.org_y = (float)o[1];
	rh.ray.org_z = (float)o[2];
	rh.ray.dir_x = (float)d[0];
	rh.ray.dir_y = (float)d[1];
	rh.ray.dir_z = (float)d[2];
	rh.ray.tnear = ray_tnear(o);
	rh.ray.tfar = INFINITY;
	rh.ray.time = 0.0f;
	rh.ray.mask = ray_mask(flags);
	rh.ray.id = 0;
	rh.ray.flags = 0;
	rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
	rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
	rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
	rtcIntersect1(a->scene, &c.rtc, &rh);
	refine(a, s, &l, rh.hit.geomID, rh.hit.primID, rh.ray.tfar, rh.hit.u, rh.hit.v, best,
	       mh);
}

void
rf__accel_intersect8(const struct rf__accel *a, const rf_scene *s, int n,
                     const struct rf__lane *l, const int *valid, struct rf__candidate *best,
                     struct rf__mesh_hit *mh)
{
	struct ctx c;
	RTC_ALIGN(32) struct RTCRayHit8 rh;
	RTC_ALIGN(32) int v[8];
	int j, any = 0;

	if (n <= 0)
		return;
	rtcInitIntersectContext(&c.rtc);
	c.s = s;
	c.lane = l;
	c.best = best;
	for (j = 0; j < 8; j++) {
		/* Embree reads every lane; the ones past n repeat the first */
		const struct rf__lane *lj = &l[j < n ? j : 0];

		v[j] = j < n && valid[j] ? -1 : 0;
		any |= v[j];
		rh.ray.org_x[j] = (float)lj->o[0];
		rh.ray.org_y[j] = (float)lj->o[1];
		rh.ray.org_z[j] = (float)lj->o[2];
		rh.ray.dir_x[j] = (float)lj->d[0];
		rh.ray.dir_y[j] = (float)lj->d[1];
		rh.ray.dir_z[j] = (float)lj->d[2];
		rh.ray.tnear[j] = ray_tnear(lj->o);
		rh.ray.tfar[j] = INFINITY;
		rh.ray.time[j] = 0.0f;
		rh.ray.mask[j] = ray_mask(lj->flags);
		rh.ray.id[j] = (unsigned)(j < n ? j : 0);
		rh.ray.flags[j] = 0;
		rh.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
		rh.hit.primID[j] = RTC_INVALID_GEOMETRY_ID;
		rh.hit.instID[0][j] = RTC_INVALID_GEOMETRY_ID;
	}
	for (j = 0; j < n; j++)
		mh[j].mesh = -1;
	if (!any)
		return;
	rtcIntersect8(v, a->scene, &c.rtc, &rh);
	for (j = 0; j < n; j++)
		if (v[j])
			refine(a, s, &l[j], rh.hit.geomID[j], rh.hit.primID[j], rh.ray.tfar[j],
			       rh.hit.u[j], rh.hit.v[j], &best[j], &mh[j]);
}

int
rf__accel_occluded(const struct rf__accel *a, const rf_scene *s, const double o[3],
                   const double d[3], const double inv[3], double tmax)
{
	struct ctx c;
	struct RTCRay ray;

	rtcInitIntersectContext(&c.rtc);
	c.s = s;
	c.lane = NULL;
	c.best = NULL;
	c.o = o;
	c.d = d;
	c.inv = inv;
	c.tmax = tmax;
	ray.org_x = (float)o[0];
	ray.org_y = (float)o[1];
	ray.org_z = (float)o[2];
	ray.dir_x = (float)d[0];
	ray.dir_y = (float)d[1];
	ray.dir_z = (float)d[2];
	/* the margin of rf__accel_intersect's rays, off the surface left */
	ray.tnear = ray_tnear(o);
	/* triangles are decided in float: a rounding short of the end */
	ray.tfar = tmax < (double)FLT_MAX ? round_down(tmax) : INFINITY;
	ray.time = 0.0f;
	ray.mask = GMASK_OTHER | GMASK_REFLECTIVE;
	ray.id = 0;
	ray.flags = 0;
	if (!(ray.tfar > ray.tnear))
		return 0;
	rtcOccluded1(a->scene, &c.rtc, &ray);
	return ray.tfar == -INFINITY;
}
