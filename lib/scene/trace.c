/*
 * The ground truth of a scene (reflect-trace(1)): each pixel-centre ray
 * of the camera, and on a reflective surface the one-bounce integral
 *
 *	I = integral of f(V, L) (N.L) Le(P, L) dL
 *
 * of a white (F = 1) GGX lobe against what the scene emits, by Monte
 * Carlo over the distribution of visible normals (Heitz 2018).  With L
 * drawn from that distribution the weight of a sample is G2/G1(V): G1(L)
 * for separable masking (Cycles 3.4's, the references'), (1 + Lambda(V))
 * / (1 + Lambda(V) + Lambda(L)) height-correlated.  A sample below the
 * surface or its geometric normal counts 0, as does a pixel seen from
 * behind.  Reflected rays pass through the reflective objects (what a
 * probe approximates, and the references' convention) unless they are
 * asked to be visible, and then see their emission.
 *
 * A pixel's samples are two Hammersley sets of half its count each, each
 * turned by a rotation hashed from the pixel's position, the seed and
 * the half: two independent estimates (--halves) whose mean is the
 * pixel, and bytes that never depend on threads.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "maths/ggx.h"
#include "util/pool.h"
#include "scene/accel.h"

struct rf_tracer {
	const rf_scene *s;
	struct rf_trace_options o;
	size_t width, height;
	size_t col0, ncols; /* the columns rendered (rf_tracer_set_columns) */
	struct camera_basis cb;
	struct rf_camera cam;
	double *kcam;       /* rf__trace_prepare for the camera */
	/* What reflected rays can meet besides the room (objects, meshes and
	 * the sky: 0 for the room alone), and rf__trace's flags for them. */
	size_t nseen;
	unsigned flags;
	double *k;          /* per thread: rf__trace_prepare for a pixel */
	/* cos and sin of 2 pi rf__ggx_radical_inverse(i) for a half's samples,
	 * i from turn0: a pixel's rotation turns them by angle addition
	 * instead of a sincos a sample (a tenth of the time) */
	float *turn;
	uint32_t turn0;
	/* Each half's points of the range: lo[j] .. lo[j] + n[j] - 1 of a set
	 * of all[j] (the whole run's half) */
	uint32_t lo[2], n[2], all[2];
	struct rf__pool *pool;
};

struct block {
	const struct rf_tracer *t;
	float *out;
	size_t y;
};

/* Samples a pass of integrate() takes at a time: the walls' chunk. */
#define TRACE_CHUNK RF__EMIT_CHUNK

void
rf_trace_options_init(struct rf_trace_options *o)
{
	memset(o, 0, sizeof(*o));
	o->samples = 1024;
	o->nthreads = 1;
}

int
rf_tracer_create(struct rf_tracer **tp, const rf_scene *s, size_t width, size_t height,
                 const struct rf_trace_options *o, char *err, size_t errlen)
{
	struct rf_tracer *t;
	size_t i;

	*tp = NULL;
	if (!width || !height || width > ((size_t)1 << 20) || height > ((size_t)1 << 20)) {
		rf__format(err, errlen, "image size %zux%zu is out of range", width, height);
		return RF_ETOOBIG;
	}
	if (o->samples < 1 || o->samples > (1u << 24) || (o->halves && o->samples < 2)) {
		rf__format(err, errlen, "%u samples: expected 1 to 16777216 (2 or more "
		           "for halves)", o->samples);
		return RF_EINVAL;
	}
	if (o->total > (1u << 24) ||
	    (uint64_t)o->first + o->samples > (o->total ? o->total : o->samples)) {
		rf__format(err, errlen, "samples %u .. %llu of %u: a range must lie in the "
		           "total, at most 16777216", o->first,
		           (unsigned long long)o->first + o->samples - 1,
		           o->total ? o->total : o->samples);
		return RF_EINVAL;
	}
	if (!(t = calloc(1, sizeof(*t))))
		return RF_ENOMEM;
	t->s = s;
	t->o = *o;
	if (t->o.nthreads < 1)
		t->o.nthreads = 1;
	if (t->o.nthreads > RF__THREADS_MAX)
		t->o.nthreads = RF__THREADS_MAX;
	t->width = width;
	t->ncols = width;
	t->height = height;
	t->kcam = calloc(s->nobjects + 1, RF__ORIGIN_STRIDE * sizeof(double));
	t->k = calloc((size_t)t->o.nthreads * (s->nobjects + 1), RF__ORIGIN_STRIDE *
	              sizeof(double));
	{
		/* sample s is point s / 2 of half s mod 2: the halves' shares of
		 * [first, first + samples), and of the whole run's [0, total) */
		uint32_t T = o->total ? o->total : o->samples, e = o->first + o->samples, j;

		for (j = 0; j < 2; j++) {
			t->lo[j] = (o->first + 1 - j) / 2;
			t->n[j] = (e + 1 - j) / 2 - t->lo[j];
			t->all[j] = (T + 1 - j) / 2;
		}
		t->turn0 = t->lo[1];
	}
	/* padded to whole chunks: integrate() reads a chunk whole */
	t->turn = calloc((size_t)(t->lo[0] + t->n[0] - t->turn0) + TRACE_CHUNK,
	                 2 * sizeof(float));
	if (!t->kcam || !t->k || !t->turn) {
		rf_tracer_destroy(t);
		return RF_ENOMEM;
	}
	for (i = 0; i < (size_t)(t->lo[0] + t->n[0] - t->turn0); i++) {
		double a = 2.0 * M_PI * rf__ggx_radical_inverse(t->turn0 + (uint32_t)i);

		t->turn[2 * i] = (float)cos(a);
		t->turn[2 * i + 1] = (float)sin(a);
	}
	for (i = 0; i < s->nobjects; i++)
		if (o->objects_visible || !(s->objects[i].mat.mask > 0.0f))
			t->nseen++;
	t->nseen += s->nmeshes;
	/* rays that leave the room alone see the sky: the general path */
	t->nseen += s->sky != NULL;
	t->flags = o->objects_visible ? 0 : RF__TRACE_SKIP_REFLECTIVE;
	if ((s->nobjects || s->nmeshes) && !rf__accel_get(s, err, errlen)) {
		rf_tracer_destroy(t);
		return RF_ENOMEM;
	}
	if (t->o.nthreads > 1)
		rf__pool_create(&t->pool, t->o.nthreads);
	rf_tracer_set_camera(t, &s->camera);
	*tp = t;
	return 0;
}

void
rf_tracer_destroy(struct rf_tracer *t)
{
	if (!t)
		return;
	rf__pool_destroy(t->pool);
	free(t->kcam);
	free(t->k);
	free(t->turn);
	free(t);
}

size_t
rf_tracer_nchannels(const struct rf_tracer *t)
{
	return t->o.halves ? 11 : 5;
}

const char *
rf_tracer_channel(const struct rf_tracer *t, size_t i)
{
	static const char *const names[] = {
		"R", "G", "B", "mask", "objid",
		"half1.R", "half1.G", "half1.B", "half2.R", "half2.G", "half2.B"
	};

	return i < rf_tracer_nchannels(t) ? names[i] : NULL;
}

int
rf_tracer_set_camera(struct rf_tracer *t, const struct rf_camera *cam)
{
	int rc;

	if ((rc = rf_camera_check(cam, NULL, 0)) < 0)
		return rc;
	t->cam = *cam;
	rf__camera_basis(cam, t->width, t->height, &t->cb);
	rf__trace_prepare(t->s, cam->position, t->kcam);
	return 0;
}

static uint32_t
hash(uint32_t x)
{
	/* lowbias32 (Wellons): every bit of the input moves every bit */
	x ^= x >> 16;
	x *= 0x7feb352du;
	x ^= x >> 15;
	x *= 0x846ca68bu;
	x ^= x >> 16;
	return x;
}

/* The lobe's integral at a hit seen along -v over points lo .. lo + K - 1
 * of a Hammersley set of n_all samples turned by rot: their sum (of
 * weight x radiance) into acc. */
#if defined(__GNUC__) && !defined(__clang__)
/* No floating-point traps are looked at: selects may be computed on
 * both sides, which lets the direction pass become vector code. */
__attribute__((optimize("no-trapping-math")))
#endif
static void
integrate(const struct rf_tracer *t, const struct rf_hit *h, const double v[3],
          const double *k, uint32_t rot, uint32_t lo, uint32_t K, uint32_t n_all,
          double acc[3])
{
	const double alpha = (double)h->roughness * h->roughness;
	const double a = alpha > 1e-4 ? alpha : 1e-4, alpha2 = a * a;
	const double *n = h->N, *ng = h->Ng;
	const double u0r = (double)(rot & 0xffff) / 65536.0, u1r = (double)(rot >> 16) / 65536.0;
	double x[3], y[3], vl[3], vh[3], t1[3], t2[3], len, lv;
	uint32_t i;
	int c;

	/* a frame about n: x, y, n */
	if (fabs(n[0]) > 0.9) {
		x[0] = -n[1]; x[1] = n[0]; x[2] = 0;
	} else {
		x[0] = 0; x[1] = -n[2]; x[2] = n[1];
	}
	len = sqrt(rf__dot(x, x));
	for (c = 0; c < 3; c++)
		x[c] /= len;
	rf__cross(n, x, y);
	vl[0] = rf__dot(v, x);
	vl[1] = rf__dot(v, y);
	vl[2] = rf__dot(v, n);
	lv = rf__ggx_lambda(alpha2, vl[2]); /* vl[2] > 0: trace_row asks */
	/* Heitz's view-stretched frame */
	vh[0] = a * vl[0];
	vh[1] = a * vl[1];
	vh[2] = vl[2];
	len = sqrt(rf__dot(vh, vh));
	for (c = 0; c < 3; c++)
		vh[c] /= len;
	len = vh[0] * vh[0] + vh[1] * vh[1];
	if (len > 0.0) {
		t1[0] = -vh[1] / sqrt(len);
		t1[1] = vh[0] / sqrt(len);
		t1[2] = 0.0;
	} else {
		t1[0] = 1.0;
		t1[1] = t1[2] = 0.0;
	}
	rf__cross(vh, t1, t2);
	{
		/* the loop in float scalars, every vector in registers: the
		 * sample's direction needs no more than float's precision */
		const float fa = (float)a, fa2 = fa * fa, s = 0.5f * (1.0f + (float)vh[2]);
		/* 2 (1 + Lambda(V)); Lambda(V) is finite, for the pixel faces
		 * the view */
		const float kv = 2.0f * (1.0f + (float)lv);
		const float t1x = (float)t1[0], t1y = (float)t1[1], t1z = (float)t1[2];
		const float t2x = (float)t2[0], t2y = (float)t2[1], t2z = (float)t2[2];
		const float vhx = (float)vh[0], vhy = (float)vh[1], vhz = (float)vh[2];
		const float vx = (float)vl[0], vy = (float)vl[1], vz = (float)vl[2];
		const float inv_k = 1.0f / (float)n_all;
		const float fx[3] = { (float)x[0], (float)x[1], (float)x[2] };
		const float fy[3] = { (float)y[0], (float)y[1], (float)y[2] };
		const float fn[3] = { (float)n[0], (float)n[1], (float)n[2] };
		const float fng[3] = { (float)ng[0], (float)ng[1], (float)ng[2] };
		const float rc = cosf(6.28318530718f * (float)u1r), rs = sinf(6.28318530718f * (float)u1r);
		/* Two passes over a chunk of samples: their directions and
		 * weights in a loop without branches, which the compiler makes
		 * vector code, then what each valid one sees. */
		float lxs[TRACE_CHUNK], lys[TRACE_CHUNK], lzs[TRACE_CHUNK];
		float wts[TRACE_CHUNK];
		int ok[TRACE_CHUNK];
		const int correlated = t->o.masking_correlated;
		uint32_t i0, j, m, next;

		for (i0 = 0; i0 < K; i0 += m) {
			/* the chunk's turns copied: the arrays below escape to
			 * the walls' pass, and loads through a pointer that might
			 * alias their stores would keep the loop scalar */
			float turn[2 * TRACE_CHUNK];

			memcpy(turn, t->turn + 2 * ((size_t)(lo - t->turn0) + i0), sizeof(turn));
			m = K - i0 < TRACE_CHUNK ? K - i0 : TRACE_CHUNK;
			/* whole chunks, the lanes past K not ok: a fixed trip
			 * count needs no scalar epilogue, and -O2 vectorizes it */
			for (j = 0; j < TRACE_CHUNK; j++) {
				i = lo + i0 + j;
				float u0 = ((float)i + 0.5f) * inv_k + (float)u0r;
				const float c0 = turn[2 * j], s0 = turn[2 * j + 1];
				/* cos and sin of 2 pi (rf__ggx_radical_inverse(i) + u1r) */
				const float cs = c0 * rc - s0 * rs, sn = s0 * rc + c0 * rs;
				float r, p1, p2, w, nhx, nhy, nhz, nex, ney, nez, len2, inv, vn;
				float lx, ly, lz, lzc, l0, l1, l2, wt;

				/* selects written as arithmetic: a conditional
				 * subtraction would be a branch the vectorizer
				 * refuses (it could trap) */
				u0 -= (float)(int)u0; /* u0 < 2: less 1 from 1 up */
				r = sqrtf(u0);
				p1 = r * cs;
				p2 = r * sn;
				p2 = (1.0f - s) * sqrtf(1.0f - p1 * p1) + s * p2;
				w = 1.0f - p1 * p1 - p2 * p2;
				w = sqrtf(w > 0.0f ? w : 0.0f);
				nhx = p1 * t1x + p2 * t2x + w * vhx;
				nhy = p1 * t1y + p2 * t2y + w * vhy;
				nhz = p1 * t1z + p2 * t2z + w * vhz;
				nex = fa * nhx;
				ney = fa * nhy;
				nez = nhz > 0.0f ? nhz : 0.0f;
				len2 = nex * nex + ney * ney + nez * nez;
				inv = 1.0f / sqrtf(len2 > 1e-30f ? len2 : 1e-30f);
				nex *= inv;
				ney *= inv;
				nez *= inv;
				vn = vx * nex + vy * ney + vz * nez;
				lx = 2.0f * vn * nex - vx;
				ly = 2.0f * vn * ney - vy;
				lz = 2.0f * vn * nez - vz;
				l0 = lx * fx[0] + ly * fy[0] + lz * fn[0];
				l1 = lx * fx[1] + ly * fy[1] + lz * fn[1];
				l2 = lx * fx[2] + ly * fy[2] + lz * fn[2];
				/* below the shading surface, or the geometric one (0, as
				 * in Cycles) */
				ok[j] = (j < m) & (len2 > 0.0f) & (lz > 0.0f) &
				        (l0 * fng[0] + l1 * fng[1] + l2 * fng[2] > 0.0f);
				lzc = lz > 0.0f ? lz : 1.0f;
				{
					/* With A = sqrt(mu^2 + a^2 (1 - mu^2)), Lambda(L) =
					 * (A / mu - 1) / 2, so with k = 2 (1 + Lambda(V))
					 * correlated: (1 + Lambda(V)) / (1 + Lambda(V) +
					 * Lambda(L)) = k mu / (k mu + A - mu); separable:
					 * 1 / (1 + Lambda(L)) = 2 mu / (mu + A).  One root,
					 * and one division of the numerator and denominator
					 * selected, so the loop has no branch */
					const float m2 = lzc * lzc;
					const float A = sqrtf(m2 + fa2 * (1.0f - m2));
					const float num = correlated ? kv * lzc : 2.0f * lzc;
					const float den = correlated ? kv * lzc + A - lzc : lzc + A;

					/* 0 for a ray that does not count: the sum below
					 * adds every lane */
					wt = ok[j] ? num / den : 0.0f;
				}
				lxs[j] = l0;
				lys[j] = l1;
				lzs[j] = l2;
				wts[j] = wt;
			}
			if (!t->nseen) {
				/* the room alone: the walls of the whole chunk at once */
				float rgb[TRACE_CHUNK][3];

				rf__room_emission_chunk(t->s, h->P, lxs, lys, lzs, ok, m, rgb);
				/* no branch: a ray that does not count weighs 0 */
				for (j = 0; j < m; j++)
					for (c = 0; c < 3; c++)
						acc[c] += wts[j] * rgb[j][c];
				continue;
			}
			/* the chunk's valid rays eight at a time (rf__trace8:
			 * the hits of one by one), summed in their order */
			for (j = 0; j < m; j = next) {
				double l[8][3];
				const double *dl[8];
				unsigned fl[8];
				uint32_t idx[8];
				struct rf_hit hl[8];
				int nl = 0, q;

				for (next = j; next < m && nl < 8; next++) {
					if (!ok[next])
						continue;
					l[nl][0] = lxs[next];
					l[nl][1] = lys[next];
					l[nl][2] = lzs[next];
					dl[nl] = l[nl];
					fl[nl] = t->flags;
					idx[nl++] = next;
				}
				if (!nl)
					break;
				rf__trace8(t->s, h->P, k, nl, dl, NULL, fl, hl);
				for (q = 0; q < nl; q++) {
					float rgb[3];

					rf__radiance(t->s, &hl[q], rgb);
					for (c = 0; c < 3; c++)
						acc[c] += wts[idx[q]] * rgb[c];
				}
			}
		}
	}
}

static void
trace_row(void *arg, size_t task, int thread)
{
	const struct block *bk = arg;
	const struct rf_tracer *t = bk->t;
	const size_t y = bk->y + task, nch = rf_tracer_nchannels(t);
	double *k = t->k + (size_t)thread * (t->s->nobjects + 1) * RF__ORIGIN_STRIDE;
	float *out = bk->out + task * t->ncols * nch;
	const double sy = 1.0 - (2.0 * (double)y + 1.0) / (double)t->height;
	size_t x;
	int c;

	for (x = t->col0; x < t->col0 + t->ncols; x++, out += nch) {
		double d[3], v[3], half[2][3] = { { 0 } };
		struct rf_hit h;
		float e[3];
		int j;

		rf__camera_dir(&t->cb, (2.0 * (double)x + 1.0) / (double)t->width - 1.0, sy, d);
		rf__trace(t->s, t->cam.position, t->kcam, d, NULL, 0, &h);
		for (c = 0; c < 3; c++)
			v[c] = -d[c];
		rf__radiance(t->s, &h, e);
		out[3] = h.mask;
		out[4] = (float)h.objid;
		if (h.mask > 0.0f && rf__dot(h.N, v) > 0.0) {
			if (t->nseen)
				rf__trace_prepare(t->s, h.P, k);
			for (j = 0; j < 2; j++) {
				uint32_t rot = hash((uint32_t)x * 0x9e3779b9u ^ hash((uint32_t)y +
				                    hash(t->o.seed * 2u + (uint32_t)j)));

				integrate(t, &h, v, k, rot, t->lo[j], t->n[j], t->all[j], half[j]);
			}
		}
		for (c = 0; c < 3; c++) {
			const uint32_t K = t->o.samples, n0 = t->n[0], n1 = t->n[1];
			/* reflection through the mask, the surface's own light over it */
			const double refl = (half[0][c] + half[1][c]) / K;

			out[c] = (float)(h.mask * refl + e[c]);
			if (t->o.halves) {
				out[5 + c] = (float)(h.mask * half[0][c] / n0 + e[c]);
				out[8 + c] = (float)(h.mask * half[1][c] / (n1 ? n1 : 1) + e[c]);
			}
		}
	}
}

int
rf_tracer_set_columns(struct rf_tracer *t, size_t x0, size_t ncols)
{
	if (!ncols || x0 > t->width || ncols > t->width - x0)
		return RF_EINVAL;
	t->col0 = x0;
	t->ncols = ncols;
	return 0;
}

int
rf_tracer_render(struct rf_tracer *t, float *out, size_t y, size_t nrows)
{
	struct block bk;
	size_t r;

	if (y > t->height || nrows > t->height - y)
		return RF_EINVAL;
	bk.t = t;
	bk.out = out;
	bk.y = y;
	if (t->pool)
		rf__pool_run(t->pool, nrows, trace_row, &bk);
	else
		for (r = 0; r < nrows; r++)
			trace_row(&bk, r, 0);
	return 0;
}
