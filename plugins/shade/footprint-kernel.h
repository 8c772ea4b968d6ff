/* The prefilter's kernels as the footprint mode's lobe table measures
 * them, for the mode and for the bench's oracle, which size their taps
 * the same way.  Include after footprint-table.h. */
#ifndef REFLECT_PLUGINS_FOOTPRINT_KERNEL_H
#define REFLECT_PLUGINS_FOOTPRINT_KERNEL_H

#include "footprint-shape.h"

/* The perceptual roughness whose prefilter kernel is w wide: the row
 * theta_v = 0, piecewise linear in roughness, inverted.  The row grows
 * with roughness (footprint-gen refuses a table where it does not), so
 * the first entry as wide as w is found by halves. */
static inline double
footprint_kernel_roughness(double w)
{
	unsigned j, lo_j = 1, hi_j = FOOTPRINT_ROUGHNESSES;
	double lo, hi;

	if (!(w > 0.0))
		return 0.0;
	while (lo_j < hi_j) {
		unsigned mid = (lo_j + hi_j) / 2;

		if (w <= footprint_table[0][mid][3])
			hi_j = mid;
		else
			lo_j = mid + 1;
	}
	j = lo_j;
	if (j == FOOTPRINT_ROUGHNESSES)
		return 1.0;
	lo = footprint_table[0][j - 1][3];
	hi = footprint_table[0][j][3];
	return ((double)(j - 1) + (w - lo) / (hi - lo)) / (FOOTPRINT_ROUGHNESSES - 1);
}

#endif
