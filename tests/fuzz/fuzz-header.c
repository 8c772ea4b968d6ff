/*
 * libFuzzer harness for the stream reader (header parser and data) and,
 * through a round trip, the writer.
 *
 * The input is a stream: it is read frame by frame with rf_reader through
 * fmemopen, every row of every frame is read (frames whose row is larger
 * than 1 MiB are skipped, so that no allocation is large), and the header
 * of each frame that parsed is written again with rf_writer and read back:
 * a header the reader took must come back the same, or the harness aborts.
 *
 * make fuzz builds and runs it; make check replays its corpus (see
 * tests/fuzz/README).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/reflect.h"

#define HARNESS "fuzz-header"
#include "harness.h"

#define ROW_BYTES_CAP ((size_t)1 << 20)

/* Writes the header (no data) and reads it back: it must be the same. */
static void
round_trip(const rf_header *h)
{
	struct rf_writer_options opt = { rf_header_format(h), 0 };
	const rf_header *back;
	rf_writer *w;
	rf_reader *r;
	char *mem = NULL;
	size_t len = 0, i;
	FILE *fp;
	int rc;

	if (!(fp = open_memstream(&mem, &len)))
		return;
	check(rf_writer_open(&w, fp, "mem", &opt) == 0, "writer_open");
	rc = rf_writer_begin_frame(w, h);
	check(rc == 0, "a header the reader took is refused by the writer");
	check(rf_writer_error(w) != NULL, "writer_error");
	rf_writer_close(w);
	fclose(fp);
	if (!(fp = fmemopen(mem, len, "r"))) {
		free(mem);
		return;
	}
	check(rf_reader_open(&r, fp, "back", NULL) == 0, "reader_open");
	rc = rf_reader_next_frame(r, &back);
	if (rc != 1)
		fprintf(stderr, "fuzz-header: %s\n", rf_reader_error(r));
	check(rc == 1, "a written header does not read back");
	check(rf_header_ncols(back) == rf_header_ncols(h), "NCOLS differs");
	check(rf_header_nrows(back) == rf_header_nrows(h), "NROWS differs");
	check(rf_header_format(back) == rf_header_format(h), "FORMAT differs");
	check(rf_header_nchannels(back) == rf_header_nchannels(h), "NCOMP differs");
	for (i = 0; i < rf_header_nchannels(h); i++)
		check(!strcmp(rf_header_channel(back, i), rf_header_channel(h, i)),
		      "a channel name differs");
	for (i = 0; rf_header_line(h, i); i++)
		check(rf_header_line(back, i) &&
		      !strcmp(rf_header_line(back, i), rf_header_line(h, i)),
		      "a header line differs");
	check(rf_header_line(back, i) == NULL, "more header lines came back");
	rf_reader_close(r);
	fclose(fp);
	free(mem);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const rf_header *h;
	rf_reader *r;
	float *row;
	size_t bytes, i;
	FILE *fp;
	int rc;

	if (!size || !(fp = fmemopen((void *)data, size, "r")))
		return 0;
	if (rf_reader_open(&r, fp, "fuzz", NULL) < 0) {
		fclose(fp);
		return 0;
	}
	while ((rc = rf_reader_next_frame(r, &h)) == 1) {
		rf_header *d;

		check(rf_header_dup(&d, h) == 0, "header_dup");
		/* The lookups must agree with the list. */
		for (i = 0; i < rf_header_nchannels(h); i++)
			check(rf_header_find_channel(h, rf_header_channel(h, i)) == (int)i,
			      "find_channel");
		(void)rf_header_get(h, "PROBE_CENTER");
		round_trip(d);
		rf_header_destroy(d);
		bytes = rf_header_ncols(h) * rf_header_nchannels(h) * sizeof(float);
		if (bytes > ROW_BYTES_CAP)
			continue; /* the next frame skips it without a row buffer */
		check((row = malloc(bytes)) != NULL, "malloc");
		while (rf_reader_rows_left(r))
			if ((rc = rf_reader_read_rows(r, row, 1)) < 0)
				break;
		free(row);
		if (rc < 0)
			break;
	}
	if (rc < 0) {
		const char *msg = rf_reader_error(r);

		check(msg[0] != '\0', "an error without a message");
		/* One line of printable text, whatever the input held. */
		for (i = 0; msg[i]; i++)
			check((unsigned char)msg[i] >= 0x20 && msg[i] != 0x7f,
			      "a control character in a message");
	}
	rf_reader_close(r);
	fclose(fp);
	return 0;
}
