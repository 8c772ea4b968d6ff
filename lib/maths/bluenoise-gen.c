/*
 * bluenoise-gen: writes the blue-noise masks of the raytraced mode as a C
 * header, by the void-and-cluster method (Ulichney 1993), so that reflect
 * ships no downloaded data: the masks come from this file and a seed.
 *
 *	bluenoise-gen >bluenoise.h
 *
 * A mask is SIZE x SIZE ranks on a torus.  The energy of a cell is the
 * sum over the pattern's ones of a Gaussian of their toroidal distance
 * (sigma 1.9, cut at 6 cells, as the STBN SDK).  From a random pattern of
 * about a tenth ones, the tightest cluster (the one of most energy) and
 * the largest void (the zero of least) are swapped until they are the
 * same cell; then the ones are ranked by removing tightest clusters, and
 * the zeros by filling largest voids, so every prefix of the ranks is
 * itself evenly spread.  Two masks, of two seeds, give the two numbers
 * of a ray.  Linear scans: some 4096^2 steps a mask, well under a second.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SIZE 64
#define CELLS (SIZE * SIZE)
#define SIGMA 1.9
#define RADIUS 6

static double kernel[2 * RADIUS + 1][2 * RADIUS + 1];

static uint32_t
next_random(uint32_t *state)
{
	/* xorshift32: enough to scatter the first pattern */
	uint32_t x = *state;

	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	return *state = x;
}

/* Adds sign x the Gaussian about cell c to every cell's energy. */
static void
splat(double *energy, int c, double sign)
{
	int cx = c % SIZE, cy = c / SIZE, dx, dy;

	for (dy = -RADIUS; dy <= RADIUS; dy++)
		for (dx = -RADIUS; dx <= RADIUS; dx++) {
			int x = (cx + dx + SIZE) % SIZE, y = (cy + dy + SIZE) % SIZE;

			energy[y * SIZE + x] += sign * kernel[dy + RADIUS][dx + RADIUS];
		}
}

/* The one of most energy (value 1) or the zero of least (value 0). */
static int
extreme(const double *energy, const unsigned char *bits, int value)
{
	int c, best = -1;

	for (c = 0; c < CELLS; c++)
		if (bits[c] == value &&
		    (best < 0 || (value ? energy[c] > energy[best] : energy[c] < energy[best])))
			best = c;
	return best;
}

static void
make_mask(uint32_t seed, uint16_t *rank)
{
	static unsigned char bits[CELLS], start[CELLS];
	static double energy[CELLS], start_energy[CELLS];
	int c, ones = 0, n, cluster, hole;

	memset(bits, 0, sizeof(bits));
	memset(energy, 0, sizeof(energy));
	while (ones < CELLS / 10) {
		c = (int)(next_random(&seed) % CELLS);
		if (!bits[c]) {
			bits[c] = 1;
			splat(energy, c, 1);
			ones++;
		}
	}
	/* Swap the tightest cluster into the largest void until stable. */
	for (;;) {
		cluster = extreme(energy, bits, 1);
		bits[cluster] = 0;
		splat(energy, cluster, -1);
		hole = extreme(energy, bits, 0);
		bits[hole] = 1;
		splat(energy, hole, 1);
		if (hole == cluster)
			break;
	}
	memcpy(start, bits, sizeof(bits));
	memcpy(start_energy, energy, sizeof(energy));
	/* The initial ones, ranked down from ones - 1. */
	for (n = ones - 1; n >= 0; n--) {
		cluster = extreme(energy, bits, 1);
		bits[cluster] = 0;
		splat(energy, cluster, -1);
		rank[cluster] = (uint16_t)n;
	}
	/* Then every zero, ranked up, each in the largest void left. */
	memcpy(bits, start, sizeof(bits));
	memcpy(energy, start_energy, sizeof(energy));
	for (n = ones; n < CELLS; n++) {
		hole = extreme(energy, bits, 0);
		bits[hole] = 1;
		splat(energy, hole, 1);
		rank[hole] = (uint16_t)n;
	}
}

int
main(void)
{
	static uint16_t masks[2][CELLS];
	int m, c, dx, dy;

	for (dy = -RADIUS; dy <= RADIUS; dy++)
		for (dx = -RADIUS; dx <= RADIUS; dx++)
			kernel[dy + RADIUS][dx + RADIUS] =
				exp(-(dx * dx + dy * dy) / (2.0 * SIGMA * SIGMA));
	make_mask(0x2545F491u, masks[0]);
	make_mask(0x9E3779B9u, masks[1]);
	printf("/* Made by bluenoise-gen (void and cluster, %dx%d, sigma %.1f): do "
	       "not edit. */\n", SIZE, SIZE, SIGMA);
	printf("#define RF__BLUENOISE_SIZE %d\n", SIZE);
	printf("static const unsigned short rf__bluenoise_rank[2][%d] = {\n", CELLS);
	for (m = 0; m < 2; m++) {
		printf("{");
		for (c = 0; c < CELLS; c++)
			printf("%s%u,", c % 16 ? "" : "\n", masks[m][c]);
		printf("\n},\n");
	}
	printf("};\n");
	return ferror(stdout) ? 1 : 0;
}
