/*
 * dfg-gen: writes the DFG table of libreflect as a C header, integrated
 * when reflect is built (lib/surface/dfg-integrate.h: 1024 visible-normal
 * samples an entry), so that no process pays for it at run time.
 *
 *	dfg-gen >dfg-table.h
 *
 * Values are written as hexadecimal floats: the header holds the very
 * floats the integration gives.
 */
#include <stdio.h>

#include "surface/dfg-integrate.h"
#include "reflect/surface.h"

int
main(void)
{
	static double disc[3 * DFG_SAMPLES];
	unsigned i, j, k;

	for (k = 0; k < DFG_SAMPLES; k++)
		disc_point(k, DFG_SAMPLES, disc + 3 * k);
	printf("/* Made by dfg-gen (%d x %d entries, %d samples each): do not edit. */\n",
	       RF_DFG_SIZE, RF_DFG_SIZE, DFG_SAMPLES);
	printf("static const float table[%d] = {\n", RF_DFG_SIZE * RF_DFG_SIZE * 2);
	for (j = 0; j < RF_DFG_SIZE; j++)
		for (i = 0; i < RF_DFG_SIZE; i++) {
			double x = (double)i / (RF_DFG_SIZE - 1), a, b;

			integrate(x * x, (double)j / (RF_DFG_SIZE - 1), disc, DFG_SAMPLES, &a, &b);
			printf("%af, %af,%s", (double)(float)a, (double)(float)b,
			       i % 4 == 3 ? "\n" : " ");
		}
	printf("};\n");
	return ferror(stdout) ? 1 : 0;
}
