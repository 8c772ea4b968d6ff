/* The stream options and the read/write loop shared by the stream tools. */
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "reflect/import.h"

int
cli_io_option(struct cli_io *io, int opt, const char *arg)
{
	switch (opt) {
	case 'f':
		io->format = parse_format(arg);
		return 1;
	case 'h':
		io->no_header = 1;
		return 1;
	case 'H':
		io->headerless = 1;
		return 1;
	case 'x':
		io->x = parse_count(arg, 'x', 1, RF_FRAME_SIDE_MAX);
		return 1;
	case 'y':
		io->y = parse_count(arg, 'y', 1, RF_FRAME_SIDE_MAX);
		return 1;
	case 'c':
		io->channels = arg;
		return 1;
	}
	return cli_region_option(&io->region, opt, arg);
}

/* "-c 3" names the channels c0 c1 c2; otherwise -c lists the names. */
static char *
raw_channel_names(const char *arg)
{
	size_t n, i, len = 0;
	char *names, *end;

	if (*arg < '0' || *arg > '9')
		return estrdup(arg);
	n = strtoul(arg, &end, 10);
	if (*end || n < 1 || n > RF_CHANNELS_MAX)
		die("option -c: '%s' is neither a channel count in [1, %d] nor a "
		    "list of names", arg, RF_CHANNELS_MAX);
	names = emalloc(n * 8);
	for (i = 0; i < n; i++)
		len += (size_t)sprintf(names + len, "%sc%zu", i ? " " : "", i);
	return names;
}

/*
 * A pipe of 1 MB instead of Linux's 64 KB: a block of rows is megabytes,
 * and through a small pipe every block is dozens of wake-ups of the stages
 * on both sides, which then never overlap their work; piped export ran at
 * 0.43 s against 0.16 s from a file.  1 MB is the limit for unprivileged
 * processes.  Not a pipe, or no such fcntl: nothing happens.
 */
void
cli_widen_pipe(int fd)
{
#ifdef F_SETPIPE_SZ
	(void)fcntl(fd, F_SETPIPE_SZ, 1 << 20);
#else
	(void)fd;
#endif
}

/* An image file where a stream was asked for: read as reflect-import
 * reads it (its channels under their own names), into a stream in
 * memory that the reader then takes like any other.  OpenEXR and PNG
 * cost no image module. */
static FILE *
image_as_stream(const char *path, char **bufp)
{
	struct rf_writer_options wopt = { RF_FORMAT_FLOAT, 0 };
	struct rf_import_options o;
	const rf_image *images[1];
	char err[1024], *buf = NULL;
	size_t len = 0, y, w, rows;
	rf_image *img;
	rf_import *im;
	rf_writer *wr;
	FILE *mem;
	float *px;
	int rc;

	if ((rc = rf_image_read(&img, path, err, sizeof(err))) < 0)
		die_status(rc, err);
	memset(&o, 0, sizeof(o));
	images[0] = img;
	if ((rc = rf_import_create(&im, images, &path, 1, &o, err, sizeof(err))) < 0)
		die_status(rc, err);
	if (!(mem = open_memstream(&buf, &len)))
		die_sys("out of memory");
	if ((rc = rf_writer_open(&wr, mem, path, &wopt)) < 0 ||
	    (rc = rf_writer_begin_frame(wr, rf_import_header(im))) < 0)
		die_status(rc, NULL);
	w = rf_header_ncols(rf_import_header(im)) * rf_header_nchannels(rf_import_header(im));
	px = emalloc(w * sizeof(float));
	rows = rf_header_nrows(rf_import_header(im));
	for (y = 0; y < rows; y++) {
		rf_import_rows(im, y, 1, px);
		if ((rc = rf_writer_write_rows(wr, px, 1)) < 0)
			die_status(rc, NULL);
	}
	free(px);
	rf_writer_close(wr);
	rf_import_destroy(im);
	rf_image_destroy(img);
	if (fclose(mem) != 0)
		die_sys("out of memory");
	if (!(mem = fmemopen(buf, len, "rb")))
		die_sys("out of memory");
	/* the reader reads from buf until cli_io_close */
	*bufp = buf;
	return mem;
}

/* A file that does not start like a stream, and that the image layer
 * knows by its first bytes or its name. */
static int
is_image_file(const struct cli_sniff *s, const char *path)
{
	const char *dot = strrchr(path, '.');

	switch (cli_sniff_kind(s)) {
	case CLI_KIND_STREAM: return 0;
	case CLI_KIND_EXR:
	case CLI_KIND_PNG: return 1;
	default: break;
	}
	return dot && rf_image_type_for_path(path) >= 0 && strcmp(dot, ".rfl") &&
	       strcmp(dot, ".stream");
}

/* The input at path, its first bytes looked at and kept (cli_sniff.c). */
static FILE *
open_input(const char *path, struct cli_sniff *s)
{
	FILE *fp;
	int fd;

	if ((fd = open(path, O_RDONLY | O_CLOEXEC)) < 0)
		die("cannot open '%s':", path);
	if (cli_sniff_open(fd, s, &fp) < 0)
		die_sys("cannot read '%s':", path);
	return fp;
}

void
cli_io_open(struct cli_io *io, const char *path)
{
	struct rf_raw_input raw;
	struct rf_writer_options wopt = { io->format, io->no_header };
	int rc;

	cli_widen_pipe(fileno(cli_stdout()));
	if (!path || !strcmp(path, "-")) {
		io->input = stdin;
		io->input_name = "<stdin>";
		cli_widen_pipe(STDIN_FILENO);
	} else {
		struct cli_sniff sniff;

		io->input = open_input(path, &sniff);
		io->input_name = path;
		if (!io->headerless && is_image_file(&sniff, path)) {
			fclose(io->input);
			io->input = image_as_stream(path, &io->image_buf);
		}
	}
	cli_guard_mapped(io->input_name);
	if (io->headerless) {
		if (!io->x || !io->y || !io->channels)
			die("headerless input (-H) needs -x WIDTH, -y HEIGHT and -c CHANNELS");
		cli_check_frame("-H -x -y", io->x, io->y);
		raw.ncols = io->x;
		raw.nrows = io->y;
		raw.channels = raw_channel_names(io->channels);
		raw.format = RF_FORMAT_FLOAT;
		rc = rf_reader_open(&io->reader, io->input, io->input_name, &raw);
		free((char *)raw.channels);
	} else {
		rc = rf_reader_open(&io->reader, io->input, io->input_name, NULL);
	}
	if (rc < 0)
		die_status(rc, NULL);
	if ((rc = rf_writer_open(&io->writer, cli_stdout(), "<stdout>", &wopt)) < 0)
		die_status(rc, NULL);
	cli_guard_stream(io->writer);
}

int
cli_io_next(struct cli_io *io, const rf_header **h)
{
	int rc = rf_reader_next_frame(io->reader, h);

	/* the frame before a failed stream's trailer is not whole: a file
	 * made of it goes, as a file of a tool that fails does */
	if (rc == RF_EFAILED && io->made && *io->made && unlink(io->made) == 0)
		die("%s; '%s', made of that frame, is removed", rf_reader_error(io->reader),
		    io->made);
	if (rc < 0)
		die_status(rc, rf_reader_error(io->reader));
	io->frames += rc == 1;
	if (rc == 1 && io->region.given && !io->crop_output) {
		struct rf_region g;
		size_t rect[4];

		if (rf_header_region(*h, &g) < 0)
			die("'%s': frame %zu: " RF_KEY_REGION "='%s' is not X0 Y0 WIDTH HEIGHT of "
			    "a full frame that holds this one", io->input_name, io->frames,
			    rf_header_get(*h, RF_KEY_REGION));
		cli_region_rect(&io->region, g.width, g.height, 1, rect);
		if (rf_reader_crop(io->reader, rect[0], rect[1], rect[2], rect[3], h) < 0)
			die_status(RF_EINVAL, rf_reader_error(io->reader));
	}
	return rc;
}

void
cli_io_invalid_option(struct cli_io *io, const char *arg)
{
	if (rf_invalid_parse(arg, &io->invalid) < 0)
		die("--invalid: '%s' is not error, clamp or zero", arg);
}

void
cli_io_invalid_failed(struct cli_io *io, const char *why)
{
	die("'%s': frame %zu, %s (--invalid=clamp or --invalid=zero goes on)", io->input_name,
	    io->frames, why);
}

void
cli_io_plugin_failed(struct cli_io *io, const char *why)
{
	die("'%s': frame %zu, %s", io->input_name, io->frames, why);
}

void
cli_io_invalid_note(struct cli_io *io, size_t count)
{
	if (count)
		warn("'%s': frame %zu: %zu pixel%s with invalid input %s", io->input_name,
		     io->frames, count, count == 1 ? "" : "s",
		     io->invalid == RF_INVALID_CLAMP ? "clamped (or zeroed)" : "zeroed");
}

void
cli_io_read(struct cli_io *io, float *buf, size_t nrows)
{
	int rc = rf_reader_read_rows(io->reader, buf, nrows);

	if (rc < 0)
		die_status(rc, rf_reader_error(io->reader));
}

void
cli_io_read_failed(struct cli_io *io, int rc)
{
	die_status(rc, rf_reader_error(io->reader));
}

void
cli_io_begin(struct cli_io *io, const rf_header *h)
{
	int rc;

	if (io->format == RF_FORMAT_FLOAT)
		cli_refuse_terminal("a binary stream");
	if ((rc = rf_writer_begin_frame(io->writer, h)) < 0)
		die_status(rc, rf_writer_error(io->writer));
}

void
cli_io_write(struct cli_io *io, const float *buf, size_t nrows)
{
	int rc = rf_writer_write_rows(io->writer, buf, nrows);

	if (rc < 0)
		die_status(rc, rf_writer_error(io->writer));
}

void
cli_io_end_frame(struct cli_io *io)
{
	int rc = rf_writer_end_frame(io->writer);

	if (rc < 0)
		die_status(rc, rf_writer_error(io->writer));
}

void
cli_io_close(struct cli_io *io)
{
	cli_progress_end();
	rf_reader_close(io->reader);
	cli_guard_stream(NULL);
	rf_writer_close(io->writer);
	if (io->input && io->input != stdin)
		fclose(io->input);
	free(io->image_buf);
	fshut(cli_stdout(), "<stdout>");
}
