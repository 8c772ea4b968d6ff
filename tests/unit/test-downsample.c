/* The resolve of supersampled frames against a direct 2D filter, for
 * blocks of rows of every size. */
#include "reflect/reflect.h"
#include "tap.h"

enum { W = 37 * 4, H = 23 * 4, NCH = 3 };

static float frame[W * H * NCH];

/* Values with no structure a wrong index could match by chance. */
static void
fill(void)
{
	size_t i;
	unsigned s = 12345;

	for (i = 0; i < sizeof(frame) / sizeof(frame[0]); i++) {
		s = s * 1103515245u + 12345u;
		frame[i] = (float)((s >> 8) & 0xffff) / 65536.0f;
	}
	/* Channel 2 is an identifier: whole numbers. */
	for (i = 0; i < (size_t)W * H; i++)
		frame[i * NCH + 2] = (float)(i % 7);
}

/* Output pixel (x, y), channel c, from the definition: every sample's
 * weight is the product of its two axes' weights, normalised over the
 * samples in the frame. */
static double
direct(size_t w, size_t h, size_t factor, enum rf_resolve_filter filter, double sigma,
       size_t x, size_t y, size_t c)
{
	double sum = 0, wsum = 0, r = filter == RF_RESOLVE_BOX ? 0 : 3 * sigma;
	size_t sx, sy;

	for (sy = 0; sy < h; sy++)
		for (sx = 0; sx < w; sx++) {
			double dx = ((double)sx + 0.5) / (double)factor - ((double)x + 0.5);
			double dy = ((double)sy + 0.5) / (double)factor - ((double)y + 0.5);
			double wt;

			if (filter == RF_RESOLVE_BOX)
				wt = sx / factor == x && sy / factor == y;
			else if (fabs(dx) > r || fabs(dy) > r)
				wt = 0;
			else
				wt = exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
			sum += wt * frame[(sy * w + sx) * NCH + c];
			wsum += wt;
		}
	return sum / wsum;
}

/* Resolves the frame pushed in blocks of block rows; the output's rows. */
static int
resolve(float *out, size_t w, size_t h, size_t factor, enum rf_resolve_filter filter,
        double sigma, size_t block)
{
	static const unsigned char nearest[NCH] = { 0, 0, 1 };
	rf_downsampler *d;
	float *rows;
	size_t y, n, got = 0;
	int rc;

	if ((rc = rf_downsampler_create(&d, w, h, NCH, factor, filter, sigma, nearest)) < 0)
		return rc;
	rows = malloc(rf_downsampler_max_rows(d, block) * (w / factor) * NCH * sizeof(float));
	for (y = 0; y < h; y += block) {
		size_t k = block < h - y ? block : h - y;

		if ((rc = rf_downsampler_push(d, frame + y * w * NCH, k, rows, &n)) < 0)
			break;
		if (n > rf_downsampler_max_rows(d, block)) {
			rc = RF_EINVAL;
			break;
		}
		memcpy(out + got * (w / factor) * NCH, rows, n * (w / factor) * NCH * sizeof(float));
		got += n;
	}
	free(rows);
	rf_downsampler_destroy(d);
	if (rc < 0)
		return rc;
	return (int)got;
}

static void
check(size_t factor, enum rf_resolve_filter filter, double sigma)
{
	static float out[W * H * NCH], first[W * H * NCH];
	static const size_t blocks[] = { 1, 2, 3, 7, 64, H };
	size_t w = W / 4 * factor, h = H / 4 * factor;
	size_t ow = w / factor, oh = h / factor, b, x, y, c;

	fill();
	for (b = 0; b < sizeof(blocks) / sizeof(blocks[0]); b++) {
		int got = resolve(out, w, h, factor, filter, sigma, blocks[b]);

		if (got != (int)oh) {
			printf("# factor %zu block %zu: %d rows of %zu\n", factor, blocks[b], got, oh);
			tap_current_failed = 1;
			return;
		}
		if (b == 0)
			memcpy(first, out, ow * oh * NCH * sizeof(float));
		else if (memcmp(first, out, ow * oh * NCH * sizeof(float))) {
			printf("# factor %zu: blocks of %zu rows give other bytes\n", factor,
			       blocks[b]);
			tap_current_failed = 1;
			return;
		}
	}
	for (y = 0; y < oh; y++)
		for (x = 0; x < ow; x++)
			for (c = 0; c < 2; c++) {
				double want = direct(w, h, factor, filter, sigma, x, y, c);
				double got = out[(y * ow + x) * NCH + c];

				if (fabs(got - want) > 2e-6) {
					printf("# factor %zu filter %d: (%zu, %zu, %zu) %.9g != %.9g\n",
					       factor, (int)filter, x, y, c, got, want);
					tap_current_failed = 1;
					return;
				}
			}
	/* The identifier is the centre sample's. */
	for (y = 0; y < oh; y++)
		for (x = 0; x < ow; x++) {
			size_t sx = x * factor + factor / 2, sy = y * factor + factor / 2;

			if (out[(y * ow + x) * NCH + 2] != frame[(sy * w + sx) * NCH + 2]) {
				printf("# factor %zu: objid of (%zu, %zu) is not the centre's\n",
				       factor, x, y);
				tap_current_failed = 1;
				return;
			}
		}
}

TEST(box_matches_the_definition)
{
	check(1, RF_RESOLVE_BOX, 0);
	if (!tap_current_failed)
		check(3, RF_RESOLVE_BOX, 0);
	if (!tap_current_failed)
		check(4, RF_RESOLVE_BOX, 0);
}

TEST(gaussian_matches_the_definition)
{
	check(2, RF_RESOLVE_GAUSSIAN, RF_RESOLVE_SIGMA_DEFAULT);
	if (!tap_current_failed)
		check(3, RF_RESOLVE_GAUSSIAN, 1.7);
	if (!tap_current_failed)
		check(4, RF_RESOLVE_GAUSSIAN, 0.1);
}

/* The widest Gaussian reaches further than the frame: every output row
 * completes with the last input row, in one push of one row. */
TEST(widest_gaussian_on_a_small_frame)
{
	check(2, RF_RESOLVE_GAUSSIAN, RF_RESOLVE_SIGMA_MAX);
}

TEST(refusals)
{
	rf_downsampler *d = (rf_downsampler *)1;
	float row[8];
	size_t n;

	ASSERT_EQ(rf_downsampler_create(&d, 10, 9, 1, 3, RF_RESOLVE_BOX, 0, NULL), RF_EINVAL);
	ASSERT(d == NULL);
	ASSERT_EQ(rf_downsampler_create(&d, 9, 9, 1, 0, RF_RESOLVE_BOX, 0, NULL), RF_EINVAL);
	ASSERT_EQ(rf_downsampler_create(&d, 9, 9, 0, 3, RF_RESOLVE_BOX, 0, NULL), RF_EINVAL);
	ASSERT_EQ(rf_downsampler_create(&d, 9, 9, 1, 3, RF_RESOLVE_GAUSSIAN, 0.05, NULL),
	          RF_EINVAL);
	ASSERT_EQ(rf_downsampler_create(&d, 9, 9, 1, 3, RF_RESOLVE_GAUSSIAN, NAN, NULL),
	          RF_EINVAL);
	ASSERT_EQ(rf_downsampler_create(&d, 9, 9, 1, 3, (enum rf_resolve_filter)7, 1, NULL),
	          RF_EINVAL);
	ASSERT_EQ(rf_downsampler_create(&d, 4, 2, 1, 2, RF_RESOLVE_BOX, 0, NULL), 0);
	ASSERT_EQ(rf_downsampler_width(d), 2);
	ASSERT_EQ(rf_downsampler_height(d), 1);
	memset(row, 0, sizeof(row));
	ASSERT_EQ(rf_downsampler_push(d, row, 2, row + 4, &n), 0);
	ASSERT_EQ(n, 1);
	/* Past the frame's last row. */
	ASSERT_EQ(rf_downsampler_push(d, row, 1, row + 4, &n), RF_EINVAL);
	rf_downsampler_destroy(d);
	rf_downsampler_destroy(NULL);
}

int
main(void)
{
	RUN(box_matches_the_definition);
	RUN(gaussian_matches_the_definition);
	RUN(widest_gaussian_on_a_small_frame);
	RUN(refusals);
	TAP_DONE();
}
