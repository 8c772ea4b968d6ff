/* Unit tests of the stream reader and writer. */
#include <stdint.h>

#include "reflect/reflect.h"
#include "tap.h"

static rf_header *
make_header(size_t w, size_t h, const char *channels)
{
	rf_header *hd = rf_header_new();

	if (!hd || rf_header_set_size(hd, w, h) < 0 ||
	    rf_header_set_channels(hd, channels) < 0)
		return NULL;
	return hd;
}

/* Writes frames of a w x h x nc ramp (value = index + 0.25 * frame). */
static FILE *
write_frames(size_t w, size_t h, const char *channels, size_t nframes,
             enum rf_format format)
{
	struct rf_writer_options opt = { format, 0 };
	rf_header *hd = make_header(w, h, channels);
	rf_writer *wr;
	FILE *fp = tmpfile();
	size_t nc = rf_header_nchannels(hd), f, i;
	float *buf = malloc(w * h * nc * sizeof(float));

	rf_header_add_line(hd, "unit-test -x 1");
	rf_header_set(hd, "PROBE_CENTER", "0 1.5 0");
	rf_writer_open(&wr, fp, "tmp", &opt);
	for (f = 0; f < nframes; f++) {
		for (i = 0; i < w * h * nc; i++)
			buf[i] = (float)i + 0.25f * (float)f;
		rf_writer_begin_frame(wr, hd);
		rf_writer_write_rows(wr, buf, 1);
		rf_writer_write_rows(wr, buf + w * nc, h - 1);
		rf_writer_end_frame(wr);
	}
	rf_writer_close(wr);
	rf_header_free(hd);
	free(buf);
	rewind(fp);
	return fp;
}

TEST(roundtrip_float)
{
	FILE *fp = write_frames(5, 3, "P.X P.Y P.Z roughness", 2, RF_FORMAT_FLOAT);
	const rf_header *h;
	rf_reader *r;
	float buf[60];
	size_t i, f;

	ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
	for (f = 0; f < 2; f++) {
		ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
		ASSERT_EQ(rf_header_ncols(h), 5);
		ASSERT_EQ(rf_header_nrows(h), 3);
		ASSERT_EQ(rf_header_nchannels(h), 4);
		ASSERT_STR_EQ(rf_header_channel(h, 3), "roughness");
		ASSERT_EQ(rf_header_find_channel(h, "P.Y"), 1);
		ASSERT(rf_header_find_channel(h, "P.W") < 0);
		ASSERT_STR_EQ(rf_header_get(h, "PROBE_CENTER"), "0 1.5 0");
		ASSERT_STR_EQ(rf_header_line(h, 0), "unit-test -x 1");
		ASSERT_EQ(rf_reader_read_rows(r, buf, 3), 0);
		for (i = 0; i < 60; i++)
			ASSERT(buf[i] == (float)i + 0.25f * (float)f);
	}
	ASSERT_EQ(rf_reader_next_frame(r, &h), 0);
	rf_reader_close(r);
	fclose(fp);
}

TEST(data_is_aligned)
{
	FILE *fp = write_frames(2, 2, "a", 1, RF_FORMAT_FLOAT);
	char line[4096];
	long end = 0;

	while (fgets(line, sizeof(line), fp))
		if (line[0] == '\n') {
			end = ftell(fp);
			break;
		}
	ASSERT(end > 0);
	ASSERT_EQ(end % 4, 0);
	fseek(fp, 0, SEEK_END);
	ASSERT_EQ(ftell(fp) - end, 2 * 2 * 4);
	fclose(fp);
}

TEST(roundtrip_ascii)
{
	FILE *fp = write_frames(3, 2, "a b", 2, RF_FORMAT_ASCII);
	const rf_header *h;
	rf_reader *r;
	float buf[12];
	size_t i;

	ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_header_format(h), RF_FORMAT_ASCII);
	ASSERT_EQ(rf_reader_read_rows(r, buf, 2), 0);
	for (i = 0; i < 12; i++)
		ASSERT(buf[i] == (float)i);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_reader_read_rows(r, buf, 2), 0);
	ASSERT(buf[11] == 11.25f);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 0);
	rf_reader_close(r);
	fclose(fp);
}

/* A big-endian file made by hand reads back as native floats. */
TEST(byte_swap)
{
	static const char head[] = "#?REFLECT1\nNCOLS=2\nNROWS=1\nNCOMP=1\n"
	                           "CHANNELS=v\nBigEndian=1\nFORMAT=float\n\n";
	unsigned char be[8];
	float v[2] = { 1.5f, -2.0f }, got[2];
	const rf_header *h;
	rf_reader *r;
	FILE *fp = tmpfile();
	int i, k;

	for (i = 0; i < 2; i++) {
		uint32_t u;

		memcpy(&u, &v[i], 4);
		for (k = 0; k < 4; k++)
			be[i * 4 + k] = (unsigned char)(u >> (24 - 8 * k));
	}
	fwrite(head, 1, sizeof(head) - 1, fp);
	fwrite(be, 1, 8, fp);
	rewind(fp);
	ASSERT_EQ(rf_reader_open(&r, fp, "be", NULL), 0);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_header_big_endian(h), 1);
	ASSERT_EQ(rf_reader_read_rows(r, got, 1), 0);
	ASSERT(got[0] == 1.5f && got[1] == -2.0f);
	rf_reader_close(r);
	fclose(fp);
}

/* Unread rows are skipped when the next frame is asked for. */
TEST(skip_unread_rows)
{
	FILE *fp = write_frames(4, 4, "a b c", 3, RF_FORMAT_FLOAT);
	const rf_header *h;
	rf_reader *r;
	float buf[12];

	ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_reader_frame_index(r), 1);
	ASSERT_EQ(rf_reader_read_rows(r, buf, 1), 0);
	ASSERT(buf[0] == 0.25f);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_reader_read_rows(r, buf, 1), 0);
	ASSERT(buf[0] == 0.5f);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 0);
	rf_reader_close(r);
	fclose(fp);
}

TEST(header_keys)
{
	rf_header *h = make_header(1, 1, "a");
	rf_header *d;

	ASSERT(h);
	ASSERT_EQ(rf_header_set(h, "KEY", "1"), 0);
	ASSERT_EQ(rf_header_set(h, "KEY", "2"), 0);
	ASSERT_STR_EQ(rf_header_get(h, "KEY"), "2");
	ASSERT(rf_header_line(h, 1) == NULL);
	ASSERT(rf_header_set(h, "NCOLS", "3") < 0);
	ASSERT(rf_header_set(h, "FORMAT", "ascii") < 0);
	ASSERT(rf_header_set(h, "BAD KEY", "1") < 0);
	ASSERT(rf_header_set(h, "K", "line\nbreak") < 0);
	ASSERT(rf_header_add_channel(h, "a") < 0);
	ASSERT(rf_header_add_channel(h, "has space") < 0);
	ASSERT(rf_header_add_channel(h, "x=y") < 0);
	ASSERT_EQ(rf_header_add_channel(h, "b"), 1);
	d = rf_header_dup(h);
	ASSERT(d);
	ASSERT_STR_EQ(rf_header_get(d, "KEY"), "2");
	ASSERT_STR_EQ(rf_header_channel(d, 1), "b");
	ASSERT_EQ(rf_header_unset(d, "KEY"), 0);
	ASSERT(rf_header_get(d, "KEY") == NULL);
	rf_header_free(d);
	rf_header_free(h);
}

TEST(command_line_quoting)
{
	char *argv[] = { "/usr/bin/lt-reflect-shade", "-m", "approx:clamp=0",
	                 "it's here", "a\nb", NULL };
	rf_header *h = make_header(1, 1, "a");

	ASSERT_EQ(rf_header_add_command(h, 5, argv), 0);
	ASSERT_STR_EQ(rf_header_line(h, 0),
	              "reflect-shade -m approx:clamp=0 'it'\\''s here' a?b");
	rf_header_free(h);
}

TEST(size_overflow_refused)
{
	rf_header *h = rf_header_new();

	ASSERT(rf_header_set_size(h, SIZE_MAX / 2, 3) < 0);
	ASSERT(rf_header_set_size(h, 0, 3) < 0);
	ASSERT_EQ(rf_header_set_size(h, 3, 3), 0);
	rf_header_free(h);
}

TEST(block_rows)
{
	ASSERT_EQ(rf_block_rows(100, 10, 4000), 1);
	ASSERT_EQ(rf_block_rows(100, 10, 40000), 10);
	ASSERT_EQ(rf_block_rows(1, 1, 6), 1);
	ASSERT_EQ(rf_block_rows((size_t)1 << 30, 1, 4096), 1);
}

int
main(void)
{
	RUN(roundtrip_float);
	RUN(data_is_aligned);
	RUN(roundtrip_ascii);
	RUN(byte_swap);
	RUN(skip_unread_rows);
	RUN(header_keys);
	RUN(command_line_quoting);
	RUN(size_overflow_refused);
	RUN(block_rows);
	TAP_DONE();
}
