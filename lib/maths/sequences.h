/*
 * The sample sequences of reflect: white noise, blue noise and the
 * low-discrepancy (Hammersley) set, keyed by pixel, frame and seed, as
 * the raytraced mode draws its rays and as the host hands them to any
 * mode (plugin.h's random_pairs).  Header-only, as projection.h is: the
 * plugin and the host include it, and so give the same numbers.
 */
#ifndef REFLECT_MATHS_SEQUENCES_H
#define REFLECT_MATHS_SEQUENCES_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "maths/lanes.h"

/* Two 64 x 64 blue-noise masks, made at build time by bluenoise-gen.c. */
#include "maths/bluenoise.h"

enum { SEQUENCE_WHITE, SEQUENCE_BLUE, SEQUENCE_LOW_DISCREPANCY };

/* Jarzynski and Olano's rf__pcg4d: four 32-bit keys, four well-mixed words. */
static inline void
rf__pcg4d(uint32_t v[4])
{
	int i;

	for (i = 0; i < 4; i++)
		v[i] = v[i] * 1664525u + 1013904223u;
	v[0] += v[1] * v[3];
	v[1] += v[2] * v[0];
	v[2] += v[0] * v[1];
	v[3] += v[1] * v[2];
	for (i = 0; i < 4; i++)
		v[i] ^= v[i] >> 16;
	v[0] += v[1] * v[3];
	v[1] += v[2] * v[0];
	v[2] += v[0] * v[1];
	v[3] += v[1] * v[2];
}

/* The top 24 bits: [0, 1), never 1. */
static inline float
rf__unit_float(uint32_t h)
{
	return (float)(h >> 8) * (1.0f / 16777216.0f);
}

static inline float
rf__radical_inverse(uint32_t i)
{
	i = (i << 16) | (i >> 16);
	i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
	i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
	i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
	i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
	return rf__unit_float(i);
}

static inline float
rf__fract(float x)
{
	float f = x - floorf(x);

	return f < 1.0f ? f : 0.0f;
}

/* rf__fract of an x in [0, 2), the sum of two numbers in [0, 1): the same
 * bits as rf__fract, without floorf (a call on x86-64's baseline, half of
 * the raytraced mode's time outside its rays): less 1 or less 0. */
static inline float
rf__fract_below2(float x)
{
	return x - (float)(x >= 1.0f);
}

/* out = rf__fract(in + b) for in and b in [0, 1), by rf__fract_below2.  Its
 * select becomes a branch in GCC's scalar code (at -O2 the loop is not
 * vectorized: n is unknown), and a branch on noise is mispredicted half
 * the time: 40 % of the raytraced mode's own loop at 64 blue rays.  Four
 * at a time in vector code, the same subtraction of 1 or 0. */
static inline void
rf__shift_below2(const float *restrict in, float b, uint32_t n, float *restrict out)
{
	uint32_t i = 0;

#if defined(__SSE2__)
	const rf__lanes_v4f one = { 1.0f, 1.0f, 1.0f, 1.0f }, vb = { b, b, b, b };

	for (; i + 4 <= n; i += 4) {
		rf__lanes_v4f x;

		memcpy(&x, in + i, sizeof(x));
		x += vb;
		x -= (rf__lanes_v4f)((rf__lanes_v4i)one & (x >= one));
		memcpy(out + i, &x, sizeof(x));
	}
#endif
	for (; i < n; i++)
		out[i] = rf__fract_below2(in[i] + b);
}

/* Point i of the Hammersley set of n: ((i + 1/2) / n, radical inverse). */
static inline void
rf__hammersley(uint32_t i, uint32_t n, float *a, float *b)
{
	*a = ((float)i + 0.5f) / (float)n;
	*b = rf__radical_inverse(i);
}

/* Pairs i0 .. i0 + n - 1 of a pixel's sequence.  White: a hash of pixel,
 * index, seed and frame.  The others: the points ham0, ham1 (n of them),
 * moved by r2_step steps of the R2 sequence (Roberts 2018: animated
 * frames reuse no other's numbers), and for blue by the pixel's values
 * of two blue-noise masks, offset by the seed (Cranley-Patterson
 * rotation, Georgiev and Fajardo's dithered sampling): every pixel
 * converges as Hammersley does, and what error is left is spread as blue
 * noise, fine grained, which the eye and any later blur forgive. */
static inline void
rf__sequence_pairs(int pattern, uint32_t seed, uint32_t frame, uint32_t r2_step, uint32_t px,
               uint32_t py, uint32_t i0, uint32_t n, const float *ham0, const float *ham1,
               float *u0, float *u1)
{
	float b0 = 0.0f, b1 = 0.0f, f0 = 0.0f, f1 = 0.0f;
	uint32_t i;

	if (pattern == SEQUENCE_WHITE) {
		for (i = 0; i < n; i++) {
			uint32_t v[4] = { px, py, i0 + i, seed ^ (frame * 0x9E3779B9u) };

			rf__pcg4d(v);
			u0[i] = rf__unit_float(v[0]);
			u1[i] = rf__unit_float(v[1]);
		}
		return;
	}
	if (pattern == SEQUENCE_BLUE) {
		uint32_t sx = (px + seed * 23u) % RF__BLUENOISE_SIZE;
		uint32_t sy = (py + seed * 41u) % RF__BLUENOISE_SIZE;
		uint32_t c = sy * RF__BLUENOISE_SIZE + sx;

		b0 = ((float)rf__bluenoise_rank[0][c] + 0.5f) / (float)(RF__BLUENOISE_SIZE * RF__BLUENOISE_SIZE);
		b1 = ((float)rf__bluenoise_rank[1][c] + 0.5f) / (float)(RF__BLUENOISE_SIZE * RF__BLUENOISE_SIZE);
	}
	if (r2_step) {
		f0 = (float)r2_step * 0.7548776662f;
		f1 = (float)r2_step * 0.5698402910f;
	}
	/* one pass a step, each without a test inside */
	if (pattern == SEQUENCE_BLUE) {
		rf__shift_below2(ham0, b0, n, u0);
		rf__shift_below2(ham1, b1, n, u1);
	} else {
		memcpy(u0, ham0, n * sizeof(*u0));
		memcpy(u1, ham1, n * sizeof(*u1));
	}
	if (r2_step)
		for (i = 0; i < n; i++) {
			u0[i] = rf__fract(u0[i] + f0);
			u1[i] = rf__fract(u1[i] + f1);
		}
}

#endif
