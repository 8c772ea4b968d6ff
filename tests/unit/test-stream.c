/* Unit tests of the stream reader and writer. */
#include <stdint.h>
#include <string.h>
#include <unistd.h>

#include "reflect/reflect.h"
#include "tap.h"

static rf_header *
make_header(size_t w, size_t h, const char *channels)
{
	rf_header *hd;

	if (rf_header_create(&hd) < 0 || rf_header_set_size(hd, w, h) < 0 ||
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
	rf_header_destroy(hd);
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

/* A file is mapped where it lies: three frames, rows mapped in pieces
 * and read in others, give the same values as reading; a pipe (not
 * mappable) gives NULL and consumes nothing. */
TEST(map_rows_from_a_file)
{
	FILE *fp = write_frames(5, 4, "P.X P.Y P.Z roughness", 3, RF_FORMAT_FLOAT);
	const rf_header *h;
	const float *rows;
	rf_reader *r;
	float buf[80];
	size_t i, f;

	ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
	for (f = 0; f < 3; f++) {
		ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
		ASSERT_EQ(rf_reader_map_rows(r, 1, &rows), 0);
		ASSERT(rows != NULL);
		for (i = 0; i < 20; i++)
			ASSERT(rows[i] == (float)i + 0.25f * (float)f);
		ASSERT_EQ(rf_reader_read_rows(r, buf, 1), 0);
		for (i = 0; i < 20; i++)
			ASSERT(buf[i] == (float)(20 + i) + 0.25f * (float)f);
		ASSERT_EQ(rf_reader_map_rows(r, 2, &rows), 0);
		ASSERT(rows != NULL);
		for (i = 0; i < 40; i++)
			ASSERT(rows[i] == (float)(40 + i) + 0.25f * (float)f);
	}
	ASSERT_EQ(rf_reader_next_frame(r, &h), 0);
	rf_reader_close(r);
	fclose(fp);

	/* Frames left unread or half mapped are skipped as before. */
	fp = write_frames(5, 4, "P.X P.Y P.Z roughness", 3, RF_FORMAT_FLOAT);
	ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_reader_map_rows(r, 3, &rows), 0);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_reader_map_rows(r, 4, &rows), 0);
	ASSERT(rows && rows[79] == 79.0f + 0.5f);
	ASSERT(rf_reader_map_rows(r, 1, &rows) < 0); /* past the last row */
	ASSERT(strstr(rf_reader_error(r), "past the last row"));
	rf_reader_close(r);
	fclose(fp);
}

/* Not a regular file: nothing mapped, nothing consumed. */
TEST(map_rows_from_a_pipe)
{
	FILE *src = write_frames(3, 2, "a b", 1, RF_FORMAT_FLOAT), *fp;
	const rf_header *h;
	const float *rows = (const float *)1;
	rf_reader *r;
	float buf[12];
	int fds[2], c;
	size_t i;

	ASSERT_EQ(pipe(fds), 0);
	while ((c = getc(src)) != EOF) {
		unsigned char ch = (unsigned char)c;

		ASSERT_EQ(write(fds[1], &ch, 1), 1);
	}
	close(fds[1]);
	fclose(src);
	fp = fdopen(fds[0], "rb");
	ASSERT_EQ(rf_reader_open(&r, fp, "pipe", NULL), 0);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_reader_map_rows(r, 2, &rows), 0);
	ASSERT(rows == NULL);
	ASSERT_EQ(rf_reader_read_rows(r, buf, 2), 0);
	for (i = 0; i < 12; i++)
		ASSERT(buf[i] == (float)i);
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
	ASSERT_EQ(rf_header_dup(&d, h), 0);
	ASSERT_STR_EQ(rf_header_get(d, "KEY"), "2");
	ASSERT_STR_EQ(rf_header_channel(d, 1), "b");
	ASSERT_EQ(rf_header_unset(d, "KEY"), 0);
	ASSERT(rf_header_get(d, "KEY") == NULL);
	rf_header_destroy(d);
	rf_header_destroy(h);
}

TEST(command_line_quoting)
{
	char *argv[] = { "/usr/bin/lt-reflect-shade", "-m", "approx:clamp=0",
	                 "it's here", "a\nb", NULL };
	rf_header *h = make_header(1, 1, "a");

	ASSERT_EQ(rf_header_add_command(h, 5, argv), 0);
	ASSERT_STR_EQ(rf_header_line(h, 0),
	              "reflect-shade -m approx:clamp=0 'it'\\''s here' a?b");
	rf_header_destroy(h);
}

TEST(size_overflow_refused)
{
	rf_header *h;

	ASSERT_EQ(rf_header_create(&h), 0);
	ASSERT(rf_header_set_size(h, SIZE_MAX / 2, 3) < 0);
	ASSERT(rf_header_set_size(h, 0, 3) < 0);
	ASSERT_EQ(rf_header_set_size(h, 3, 3), 0);
	rf_header_destroy(h);
}

TEST(block_rows)
{
	ASSERT_EQ(rf_block_rows(100, 10, 4000), 1);
	ASSERT_EQ(rf_block_rows(100, 10, 40000), 10);
	ASSERT_EQ(rf_block_rows(1, 1, 6), 1);
	ASSERT_EQ(rf_block_rows((size_t)1 << 30, 1, 4096), 1);
	/* A row whose size overflows is one row, not bytes / (wrapped size). */
	ASSERT_EQ(rf_block_rows(SIZE_MAX / 2 + 1, 2, 4096), 1);
	ASSERT_EQ(rf_block_rows(0, 3, 4096), 1);
}

/* A reader over a copy of n bytes of s. */
static FILE *
input(const char *s, size_t n)
{
	FILE *fp = tmpfile();

	fwrite(s, 1, n, fp);
	rewind(fp);
	return fp;
}

/* The status of the first rf_reader_next_frame on the string s. */
static int
first_frame(const char *s, size_t n, char *err, size_t errlen)
{
	FILE *fp = input(s, n);
	const rf_header *h;
	rf_reader *r;
	int rc;

	if (rf_reader_open(&r, fp, "in", NULL) < 0)
		return -1000;
	rc = rf_reader_next_frame(r, &h);
	if (err)
		snprintf(err, errlen, "%s", rf_reader_error(r));
	rf_reader_close(r);
	fclose(fp);
	return rc;
}

#define HEAD_REST "NCOLS=1\nNROWS=1\nNCOMP=1\nCHANNELS=a\nFORMAT=ascii\n\n1\n"

TEST(stream_identifier)
{
	char err[512];

	ASSERT_EQ(first_frame("#?REFLECT1\n" HEAD_REST, 11 + sizeof(HEAD_REST) - 1,
	                      err, sizeof(err)), 1);
	ASSERT_EQ(first_frame("#?REFLECT2\n" HEAD_REST, 11 + sizeof(HEAD_REST) - 1,
	                      err, sizeof(err)), RF_EVERSION);
	ASSERT_STR_EQ(err, "'in': stream version 2 is newer than this reader's (1); "
	                   "upgrade reflect");
	ASSERT_EQ(first_frame("#?REFLECT99999999999999999999\n" HEAD_REST,
	                      30 + sizeof(HEAD_REST) - 1, err, sizeof(err)),
	          RF_EVERSION);
	/* Leading zeros, signs and blanks are not a version. */
	ASSERT_EQ(first_frame("#?REFLECT01\n" HEAD_REST, 12 + sizeof(HEAD_REST) - 1,
	                      err, sizeof(err)), RF_EFORMAT);
	ASSERT_STR_EQ(err, "'in': bad stream identifier '#?REFLECT01'");
	ASSERT_EQ(first_frame("#?REFLECT 1\n" HEAD_REST, 12 + sizeof(HEAD_REST) - 1,
	                      NULL, 0), RF_EFORMAT);
	ASSERT_EQ(first_frame("#?REFLECT+1\n" HEAD_REST, 12 + sizeof(HEAD_REST) - 1,
	                      NULL, 0), RF_EFORMAT);
	ASSERT_EQ(first_frame("#?REFLECT1\r\n" HEAD_REST, 12 + sizeof(HEAD_REST) - 1,
	                      NULL, 0), 1);
}

/* The first bytes of an input tell a stream, of any version (the reader
 * judges that), from what is not one; the writer's and the ASCII
 * format's frames begin as the sniffing expects. */
TEST(stream_sniff)
{
	unsigned char head[16];
	FILE *fp;
	int format;

	ASSERT_EQ(rf_stream_sniff("#?REFLECT1\n", 11), 1);
	ASSERT_EQ(rf_stream_sniff("#?REFLECT2\n", 11), 1);
	ASSERT_EQ(rf_stream_sniff("#?REFLECT", 9), 1);
	ASSERT_EQ(rf_stream_sniff("#?REFLECT1", 8), 0);
	ASSERT_EQ(rf_stream_sniff("", 0), 0);
	ASSERT_EQ(rf_stream_sniff("#?reflect1\n", 11), 0);
	ASSERT_EQ(rf_stream_sniff("#?RADIANCE\n", 11), 0);
	ASSERT_EQ(rf_stream_sniff(" #?REFLECT1\n", 12), 0);
	ASSERT_EQ(rf_stream_sniff("\x76\x2f\x31\x01\x02\0\0\0\0", 9), 0);
	for (format = 0; format < 2; format++) {
		fp = write_frames(2, 2, "a b", 1, format ? RF_FORMAT_ASCII : RF_FORMAT_FLOAT);
		ASSERT_EQ(fread(head, 1, sizeof(head), fp), sizeof(head));
		ASSERT_EQ(rf_stream_sniff(head, sizeof(head)), 1);
		fclose(fp);
	}
}

/* A header line of RF_HEADER_LINE_MAX bytes is taken, with LF or CRLF;
 * one more byte is refused. */
TEST(header_line_limit)
{
	static char buf[4096 + 256];
	char err[512];
	size_t n, len;
	int crlf, extra;

	for (extra = 0; extra < 2; extra++)
		for (crlf = 0; crlf < 2; crlf++) {
			n = (size_t)sprintf(buf, "#?REFLECT1\nK=");
			len = RF_HEADER_LINE_MAX + (size_t)extra - 2;
			memset(buf + n, 'x', len);
			n += len;
			if (crlf)
				buf[n++] = '\r';
			buf[n++] = '\n';
			memcpy(buf + n, HEAD_REST, sizeof(HEAD_REST) - 1);
			n += sizeof(HEAD_REST) - 1;
			if (!extra) {
				ASSERT_EQ(first_frame(buf, n, err, sizeof(err)), 1);
			} else {
				ASSERT_EQ(first_frame(buf, n, err, sizeof(err)), RF_EFORMAT);
				ASSERT_STR_EQ(err, "'in': header line 2 is longer than 2048 "
				                   "bytes");
			}
		}
}

/* Headerless float frames: bytes that look like blanks are data. */
TEST(headerless_frames_of_blanks)
{
	static const char data[] = "\0\0\0\0    \n\n\n\n\r\t \n";
	struct rf_raw_input raw = { 1, 1, "v", RF_FORMAT_FLOAT };
	FILE *fp = input(data, sizeof(data) - 1);
	const rf_header *h;
	rf_reader *r;
	float v;
	uint32_t u;
	int frames = 0;

	ASSERT_EQ(rf_reader_open(&r, fp, "raw", &raw), 0);
	while (rf_reader_next_frame(r, &h) == 1) {
		ASSERT_EQ(rf_reader_read_rows(r, &v, 1), 0);
		memcpy(&u, &v, 4);
		if (frames == 1)
			ASSERT_EQ(u, 0x20202020u);
		if (frames == 2)
			ASSERT_EQ(u, 0x0a0a0a0au);
		frames++;
	}
	ASSERT_STR_EQ(rf_reader_error(r), "");
	ASSERT_EQ(frames, 4);
	rf_reader_close(r);
	fclose(fp);
}

/* A frame declaring a huge row is skipped (not read) without holding a
 * row: the truncation is found, not an allocation failure. */
TEST(skip_huge_frame)
{
	static const char head[] = "#?REFLECT1\nNCOLS=200000000\nNROWS=3\nNCOMP=1\n"
	                           "CHANNELS=a\nBigEndian=0\nFORMAT=float\n\n"
	                           "\0\0\0\0\0\0";
	FILE *fp = input(head, sizeof(head) - 1);
	const rf_header *h;
	rf_reader *r;
	float v;

	ASSERT_EQ(rf_reader_open(&r, fp, "big", NULL), 0);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_header_ncols(h), 200000000);
	ASSERT_EQ(rf_reader_next_frame(r, &h), RF_ETRUNCATED);
	ASSERT_STR_EQ(rf_reader_error(r), "'big': data ends inside a float in row 1 "
	                                  "of 3 (pixel 2 of 200000000, channel 'a')");
	/* After an error every call gives it again, touching nothing. */
	ASSERT_EQ(rf_reader_read_rows(r, &v, 1), RF_ETRUNCATED);
	ASSERT_EQ(rf_reader_next_frame(r, &h), RF_ETRUNCATED);
	ASSERT(h == NULL);
	ASSERT_STR_EQ(rf_reader_error(r), "'big': data ends inside a float in row 1 "
	                                  "of 3 (pixel 2 of 200000000, channel 'a')");
	rf_reader_close(r);
	fclose(fp);
}

TEST(ascii_errors_name_the_place)
{
	static const char s[] = "#?REFLECT1\nNCOLS=2\nNROWS=2\nNCOMP=2\n"
	                        "CHANNELS=a b\nFORMAT=ascii\n\n1 2 3 4\n5 6 7 z\n";
	FILE *fp = input(s, sizeof(s) - 1);
	const rf_header *h;
	rf_reader *r;
	float buf[8];

	ASSERT_EQ(rf_reader_open(&r, fp, "a", NULL), 0);
	ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
	ASSERT_EQ(rf_reader_read_rows(r, buf, 1), 0);
	ASSERT(buf[3] == 4.0f);
	ASSERT_EQ(rf_reader_read_rows(r, buf, 1), RF_EFORMAT);
	ASSERT_STR_EQ(rf_reader_error(r), "'a': ascii data: 'z' is not a number "
	                                  "(row 2 of 2, pixel 2 of 2, channel 'b')");
	ASSERT_EQ(rf_reader_read_rows(r, buf, 1), RF_EFORMAT);
	rf_reader_close(r);
	fclose(fp);
}

/* The writer never writes a header line a reader refuses. */
TEST(writer_refuses_long_channels_line)
{
	struct rf_writer_options opt = { RF_FORMAT_FLOAT, 0 };
	rf_header *h;
	FILE *fp = tmpfile();
	rf_writer *w;
	char name[32];
	int i;

	ASSERT_EQ(rf_header_create(&h), 0);
	ASSERT_EQ(rf_header_set_size(h, 1, 1), 0);
	for (i = 0; i < 200; i++) {
		snprintf(name, sizeof(name), "channel_%03d", i);
		ASSERT_EQ(rf_header_add_channel(h, name), i);
	}
	ASSERT_EQ(rf_writer_open(&w, fp, "out", &opt), 0);
	ASSERT_EQ(rf_writer_begin_frame(w, h), RF_ETOOBIG);
	ASSERT_STR_EQ(rf_writer_error(w), "'out': the CHANNELS line of 200 channels "
	                                  "would be 2408 bytes, more than the 2048 a "
	                                  "header line may hold");
	ASSERT_EQ(ftell(fp), 0);
	rf_writer_close(w);
	/* Without a header there is no such line. */
	opt.no_header = 1;
	ASSERT_EQ(rf_writer_open(&w, fp, "out", &opt), 0);
	ASSERT_EQ(rf_writer_begin_frame(w, h), 0);
	rf_writer_close(w);
	rf_header_destroy(h);
	fclose(fp);
}

/* Every frame's data is aligned, whatever the length of each header. */
TEST(every_frame_aligned)
{
	struct rf_writer_options opt = { RF_FORMAT_FLOAT, 0 };
	static const char *const keys[] = { "x", "xx", "xxx", "xxxx", "xxxxx" };
	rf_header *h = make_header(1, 1, "a");
	FILE *fp = tmpfile();
	const rf_header *rh;
	rf_writer *w;
	rf_reader *r;
	float v = 1.0f;
	size_t i;
	long end;
	char line[4096];

	ASSERT_EQ(rf_writer_open(&w, fp, "out", &opt), 0);
	for (i = 0; i < 5; i++) {
		ASSERT_EQ(rf_header_set(h, "K", keys[i]), 0);
		ASSERT_EQ(rf_writer_begin_frame(w, h), 0);
		ASSERT_EQ(rf_writer_write_rows(w, &v, 1), 0);
		ASSERT_EQ(rf_writer_end_frame(w), 0);
	}
	rf_writer_close(w);
	rewind(fp);
	/* Each frame: header lines up to the empty one, then 4 bytes. */
	for (i = 0; i < 5; i++) {
		while (fgets(line, sizeof(line), fp) && line[0] != '\n')
			;
		end = ftell(fp);
		ASSERT_EQ(end % 4, 0);
		fseek(fp, 4, SEEK_CUR);
	}
	rewind(fp);
	ASSERT_EQ(rf_reader_open(&r, fp, "out", NULL), 0);
	for (i = 0; i < 5; i++) {
		ASSERT_EQ(rf_reader_next_frame(r, &rh), 1);
		ASSERT_STR_EQ(rf_header_get(rh, "K"), keys[i]);
	}
	ASSERT_EQ(rf_reader_next_frame(r, &rh), 0);
	rf_reader_close(r);
	rf_header_destroy(h);
	fclose(fp);
}

TEST(set_channels_keeps_the_old_list_on_error)
{
	rf_header *h = make_header(1, 1, "a b");

	ASSERT(rf_header_set_channels(h, "x y x") < 0);
	ASSERT(rf_header_set_channels(h, "x bad=name") < 0);
	ASSERT(rf_header_set_channels(h, " , ") < 0);
	ASSERT_EQ(rf_header_nchannels(h), 2);
	ASSERT_STR_EQ(rf_header_channel(h, 1), "b");
	ASSERT_EQ(rf_header_set_channels(h, "x,y z"), 0);
	ASSERT_EQ(rf_header_nchannels(h), 3);
	ASSERT_STR_EQ(rf_header_channel(h, 2), "z");
	rf_header_destroy(h);
}

/* A command line too long for one header line ends in " ..." and no word
 * is cut; the tool's name stays. */
TEST(command_line_too_long)
{
	static char words[600][16], huge[3000];
	char *argv[602];
	rf_header *h = make_header(1, 1, "a");
	const char *line;
	size_t len, i;

	argv[0] = "/bin/reflect-tool";
	for (i = 0; i < 600; i++) {
		snprintf(words[i], sizeof(words[i]), "w%zu", i);
		argv[i + 1] = words[i];
	}
	ASSERT_EQ(rf_header_add_command(h, 601, argv), 0);
	line = rf_header_line(h, 0);
	len = strlen(line);
	ASSERT(len <= RF_HEADER_LINE_MAX);
	ASSERT(len > RF_HEADER_LINE_MAX - 10);
	ASSERT_STR_EQ(line + len - 4, " ...");
	ASSERT(!strncmp(line, "reflect-tool w0 w1 ", 19));
	/* The word before " ..." is whole: it is "w<n>" with the next one
	 * missing. */
	{
		const char *last = line + len - 5;
		char expect[16];
		size_t n;

		while (last > line && last[-1] != ' ')
			last--;
		n = (size_t)strtoul(last + 1, NULL, 10);
		snprintf(expect, sizeof(expect), "w%zu ...", n);
		ASSERT_STR_EQ(last, expect);
	}
	/* One-letter words: two must go to make room for " ...". */
	for (i = 1; i < 601; i++)
		argv[i] = "a";
	ASSERT_EQ(rf_header_add_command(h, 601, argv), 0);
	line = rf_header_line(h, 1);
	ASSERT_EQ(strlen(line), 12 + 2 * 600); /* 600 words fit */
	{
		static char *many[1200];

		many[0] = "reflect-tool";
		for (i = 1; i < 1200; i++)
			many[i] = "a";
		ASSERT_EQ(rf_header_add_command(h, 1200, many), 0);
		line = rf_header_line(h, 2);
		ASSERT_EQ(strlen(line), RF_HEADER_LINE_MAX);
		ASSERT_STR_EQ(line + RF_HEADER_LINE_MAX - 6, " a ...");
	}
	rf_header_destroy(h);
	h = make_header(1, 1, "a");
	/* One argument longer than a line: never cut, " ..." instead. */
	memset(huge, 'y', sizeof(huge) - 1);
	argv[1] = huge;
	argv[2] = "z";
	ASSERT_EQ(rf_header_add_command(h, 3, argv), 0);
	ASSERT_STR_EQ(rf_header_line(h, 0), "reflect-tool ...");
	rf_header_destroy(h);
}

/* A message never holds a control character, whatever the input held. */
TEST(messages_are_one_printable_line)
{
	static const char s[] = "#?REFLECT1\nNCOLS=2\tx\x7f\n\n";
	char err[512];
	size_t i;

	ASSERT_EQ(first_frame(s, sizeof(s) - 1, err, sizeof(err)), RF_EFORMAT);
	ASSERT_STR_EQ(err, "'in': header line 2: NCOLS is not a number ('2?x?')");
	for (i = 0; err[i]; i++)
		ASSERT((unsigned char)err[i] >= 0x20 && err[i] != 0x7f);
}

/* SAMPLES: 1 without the key, whole numbers 1 .. 2^32 - 1, nothing else
 * (no sign, space, exponent or fraction that strtoull would pass). */
TEST(samples_key)
{
	static const char *const bad[] = { "0", "-1", "+3", " 3", "3 ", "1e3", "1.5", "",
	                                   "0x10", "4294967296", "18446744073709551617" };
	rf_header *h;
	uint64_t n = 0;
	size_t i;

	ASSERT_EQ(rf_header_create(&h), 0);
	ASSERT_EQ(rf_header_samples(h, &n), 0);
	ASSERT_EQ(n, 1);
	ASSERT_EQ(rf_header_set(h, RF_KEY_SAMPLES, "12"), 0);
	ASSERT_EQ(rf_header_samples(h, &n), 0);
	ASSERT_EQ(n, 12);
	ASSERT_EQ(rf_header_set(h, RF_KEY_SAMPLES, "4294967295"), 0);
	ASSERT_EQ(rf_header_samples(h, &n), 0);
	ASSERT_EQ(n, 4294967295ll);
	for (i = 0; i < sizeof(bad) / sizeof(*bad); i++) {
		ASSERT_EQ(rf_header_set(h, RF_KEY_SAMPLES, bad[i]), 0);
		n = 7;
		ASSERT_EQ(rf_header_samples(h, &n), RF_EFORMAT);
		ASSERT_EQ(n, 1);
	}
	rf_header_destroy(h);
}

/* REGION: the whole frame without the key; a tile's place read back as
 * written; a whole-frame region writes no key; a value that is not four
 * whole numbers, or a tile that does not fit its full frame, refused. */
TEST(region_key)
{
	static const char *const bad[] = { "1 2 3", "1 2 30 40 5", "-1 2 30 40", "1 2 30 4x",
	                                   "1  2 30 40", " 1 2 30 40", "1 2 0 40", "26 2 30 40",
	                                   "1 37 30 40", "1 2 30 65537", "1 2 30 40 " };
	struct rf_region g, t = { 3, 4, 30, 40 };
	rf_header *h = make_header(5, 6, "R G B");
	size_t i;

	ASSERT(h != NULL);
	ASSERT_EQ(rf_header_region(h, &g), 0);
	ASSERT(g.x0 == 0 && g.y0 == 0 && g.width == 5 && g.height == 6);
	ASSERT_EQ(rf_header_set_region(h, &t), 0);
	ASSERT_STR_EQ(rf_header_get(h, RF_KEY_REGION), "3 4 30 40");
	ASSERT_EQ(rf_header_region(h, &g), 0);
	ASSERT(g.x0 == 3 && g.y0 == 4 && g.width == 30 && g.height == 40);
	/* the tile's last column and row are the full frame's: it fits */
	t.x0 = 25;
	t.y0 = 34;
	ASSERT_EQ(rf_header_set_region(h, &t), 0);
	ASSERT_EQ(rf_header_region(h, &g), 0);
	ASSERT(g.x0 == 25 && g.y0 == 34);
	t.x0 = 26;
	ASSERT_EQ(rf_header_set_region(h, &t), RF_EINVAL);
	t.x0 = 0;
	t.y0 = 0;
	t.width = 5;
	t.height = 6;
	ASSERT_EQ(rf_header_set_region(h, &t), 0);
	ASSERT(rf_header_get(h, RF_KEY_REGION) == NULL);
	for (i = 0; i < sizeof(bad) / sizeof(*bad); i++) {
		ASSERT_EQ(rf_header_set(h, RF_KEY_REGION, bad[i]), 0);
		g.x0 = 9;
		ASSERT_EQ(rf_header_region(h, &g), RF_EFORMAT);
		ASSERT(g.x0 == 0 && g.y0 == 0 && g.width == 5 && g.height == 6);
	}
	rf_header_destroy(h);
}

/* A crop: the rectangle's values and nothing else, in float and ascii,
 * the header the tile's with REGION; the next frame whole again; a
 * crop of a tile in the full frame's coordinates; refusals. */
TEST(reader_crop)
{
	enum rf_format formats[2] = { RF_FORMAT_FLOAT, RF_FORMAT_ASCII };
	const rf_header *h;
	struct rf_region g;
	rf_reader *r;
	float buf[60];
	size_t x, y, c, k;

	for (k = 0; k < 2; k++) {
		FILE *fp = write_frames(5, 4, "a b c", 2, formats[k]);

		ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
		ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
		ASSERT_EQ(rf_reader_crop(r, 1, 2, 4, 4, &h), 0);
		ASSERT_EQ(rf_header_ncols(h), 3);
		ASSERT_EQ(rf_header_nrows(h), 2);
		ASSERT_STR_EQ(rf_header_get(h, RF_KEY_REGION), "1 2 5 4");
		ASSERT_STR_EQ(rf_header_get(h, "PROBE_CENTER"), "0 1.5 0");
		ASSERT_EQ(rf_reader_rows_left(r), 2);
		ASSERT_EQ(rf_reader_read_rows(r, buf, 1), 0);
		ASSERT_EQ(rf_reader_read_rows(r, buf + 9, 1), 0);
		ASSERT_EQ(rf_reader_rows_left(r), 0);
		for (y = 0; y < 2; y++)
			for (x = 0; x < 3; x++)
				for (c = 0; c < 3; c++)
					ASSERT(buf[(y * 3 + x) * 3 + c] ==
					       (float)(((y + 2) * 5 + x + 1) * 3 + c));
		ASSERT(rf_reader_read_rows(r, buf, 1) < 0);
		rf_reader_close(r);
		fclose(fp);
		fp = write_frames(5, 4, "a b c", 2, formats[k]);
		ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
		ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
		ASSERT_EQ(rf_reader_crop(r, 0, 0, 5, 1, &h), 0);
		/* the rows left unread are skipped: frame 1 whole */
		ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
		ASSERT_EQ(rf_header_nrows(h), 4);
		ASSERT(rf_header_get(h, RF_KEY_REGION) == NULL);
		ASSERT_EQ(rf_reader_read_rows(r, buf, 4), 0);
		ASSERT(buf[59] == 59.25f);
		rf_reader_close(r);
		fclose(fp);
	}
	/* refusals: empty, past the frame, twice, after a row */
	{
		FILE *fp = write_frames(5, 4, "a b c", 1, RF_FORMAT_FLOAT);

		ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
		ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
		ASSERT_EQ(rf_reader_crop(r, 2, 0, 2, 4, &h), RF_EINVAL);
		ASSERT(strstr(rf_reader_error(r), "holds no pixel") != NULL);
		rf_reader_close(r);
		fclose(fp);
		fp = write_frames(5, 4, "a b c", 1, RF_FORMAT_FLOAT);
		ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
		ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
		ASSERT_EQ(rf_reader_crop(r, 0, 0, 6, 4, &h), RF_EINVAL);
		ASSERT(strstr(rf_reader_error(r), "not all of the region 0,0,6,4") != NULL);
		rf_reader_close(r);
		fclose(fp);
	}
	/* a tile of a tile: coordinates of the full frame */
	{
		struct rf_writer_options opt = { RF_FORMAT_FLOAT, 0 };
		struct rf_region t = { 10, 20, 100, 50 };
		rf_header *hd = make_header(4, 3, "v");
		rf_writer *wr;
		FILE *fp = tmpfile();

		for (x = 0; x < 12; x++)
			buf[x] = (float)x;
		ASSERT_EQ(rf_header_set_region(hd, &t), 0);
		ASSERT_EQ(rf_writer_open(&wr, fp, "tmp", &opt), 0);
		ASSERT_EQ(rf_writer_begin_frame(wr, hd), 0);
		ASSERT_EQ(rf_writer_write_rows(wr, buf, 3), 0);
		ASSERT_EQ(rf_writer_end_frame(wr), 0);
		rf_writer_close(wr);
		rf_header_destroy(hd);
		rewind(fp);
		ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
		ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
		ASSERT_EQ(rf_reader_crop(r, 0, 0, 4, 3, &h), RF_EINVAL);
		rf_reader_close(r);
		rewind(fp);
		ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
		ASSERT_EQ(rf_reader_next_frame(r, &h), 1);
		ASSERT_EQ(rf_reader_crop(r, 12, 21, 14, 23, &h), 0);
		ASSERT_EQ(rf_header_region(h, &g), 0);
		ASSERT(g.x0 == 12 && g.y0 == 21 && g.width == 100 && g.height == 50);
		ASSERT_EQ(rf_reader_crop(r, 12, 21, 14, 23, &h), RF_EINVAL);
		rf_reader_close(r);
		fclose(fp);
	}
}

int
main(void)
{
	RUN(roundtrip_float);
	RUN(map_rows_from_a_file);
	RUN(map_rows_from_a_pipe);
	RUN(data_is_aligned);
	RUN(roundtrip_ascii);
	RUN(byte_swap);
	RUN(skip_unread_rows);
	RUN(header_keys);
	RUN(command_line_quoting);
	RUN(size_overflow_refused);
	RUN(block_rows);
	RUN(stream_identifier);
	RUN(stream_sniff);
	RUN(header_line_limit);
	RUN(headerless_frames_of_blanks);
	RUN(skip_huge_frame);
	RUN(ascii_errors_name_the_place);
	RUN(writer_refuses_long_channels_line);
	RUN(every_frame_aligned);
	RUN(set_channels_keeps_the_old_list_on_error);
	RUN(command_line_too_long);
	RUN(messages_are_one_printable_line);
	RUN(samples_key);
	RUN(region_key);
	RUN(reader_crop);
	TAP_DONE();
}
