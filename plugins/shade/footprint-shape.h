/* The shape of the footprint mode's lobe tables, for their generator
 * and the mode: views at angles 0 .. pi/2 from the normal, evenly, by
 * perceptual roughnesses 0 .. 1, evenly; an entry of the first holds the
 * bend of the lobe's centre from the mirror direction, its in-plane
 * widths toward the normal and toward the horizon, and its width across,
 * one of the second the lobe's shares (below) (radians; footprint-gen.c
 * says how they are measured). */
#ifndef REFLECT_PLUGINS_FOOTPRINT_SHAPE_H
#define REFLECT_PLUGINS_FOOTPRINT_SHAPE_H

#define FOOTPRINT_VIEWS 33
#define FOOTPRINT_ROUGHNESSES 33

static inline double
footprint_view_angle(unsigned i)
{
	return (double)i / (FOOTPRINT_VIEWS - 1) * 1.57079632679489661923;
}

#define FOOTPRINT_TAPS_MAX 4

/* The box path's second table: for each taps= n, the lobe cut into n
 * shares, one row each; n's first row. */
#define FOOTPRINT_SHARES 10 /* 1 + 2 + 3 + 4 */

static inline unsigned
footprint_first_share(unsigned n)
{
	return n * (n - 1) / 2;
}

#endif
