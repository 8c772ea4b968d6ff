/* reflect-info: print each frame's header, and with -s channel statistics. */
#include <getopt.h>
#include <math.h>
#include <string.h>

#include "cli.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-sV] [-H -x W -y H -c CHANNELS] [file]\n"
	        "       %s --plugins\n", argv0, argv0);
	exit(EXIT_BAD_INPUT);
}

struct stats {
	double min, max, sum, comp; /* comp: Neumaier's compensation */
	size_t finite, nan, inf;
};

/* Adds v to the sum without losing small values next to large ones
 * (1e30 + 0.25 - 1e30 is 0.25, not 0). */
static void
add(struct stats *s, double v)
{
	double t = s->sum + v;

	if (fabs(s->sum) >= fabs(v))
		s->comp += (s->sum - t) + v;
	else
		s->comp += (v - t) + s->sum;
	s->sum = t;
}

static void
print_header(const rf_header *h, size_t frame)
{
	const char *line;
	size_t i;

	printf("frame %zu:\n", frame + 1);
	for (i = 0; (line = rf_header_line(h, i)); i++)
		printf("\t%s\n", line);
	printf("\tNCOLS=%zu\n\tNROWS=%zu\n\tNCOMP=%zu\n\tCHANNELS=",
	       rf_header_ncols(h), rf_header_nrows(h), rf_header_nchannels(h));
	for (i = 0; i < rf_header_nchannels(h); i++)
		printf("%s%s", i ? " " : "", rf_header_channel(h, i));
	printf("\n");
	if (rf_header_format(h) == RF_FORMAT_FLOAT)
		printf("\tBigEndian=%d\n", rf_header_big_endian(h));
	printf("\tFORMAT=%s\n", rf_header_format(h) == RF_FORMAT_FLOAT ? "float" : "ascii");
}

static void
frame_stats(struct cli_io *io, const rf_header *h)
{
	size_t ncomp = rf_header_nchannels(h), ncols = rf_header_ncols(h);
	size_t rows = rf_block_rows(ncols, ncomp, CLI_BLOCK_BYTES), y, n, i, c;
	struct stats *st = ecalloc(ncomp, sizeof(*st));
	float *buf;

	if (rows > rf_header_nrows(h))
		rows = rf_header_nrows(h);
	buf = emalloc(rows * ncols * ncomp * sizeof(float));
	for (c = 0; c < ncomp; c++) {
		st[c].min = INFINITY;
		st[c].max = -INFINITY;
	}
	for (y = 0; y < rf_header_nrows(h); y += n) {
		n = rf_header_nrows(h) - y < rows ? rf_header_nrows(h) - y : rows;
		cli_io_read(io, buf, n);
		for (i = 0; i < n * ncols; i++)
			for (c = 0; c < ncomp; c++) {
				double v = buf[i * ncomp + c];

				if (isnan(v)) {
					st[c].nan++;
				} else if (isinf(v)) {
					st[c].inf++;
				} else {
					st[c].finite++;
					add(&st[c], v);
					if (v < st[c].min)
						st[c].min = v;
					if (v > st[c].max)
						st[c].max = v;
				}
			}
	}
	printf("\t%-16s %14s %14s %14s %10s %10s\n", "channel", "min", "max", "mean",
	       "nan", "inf");
	for (c = 0; c < ncomp; c++) {
		if (st[c].finite)
			printf("\t%-16s %14.7g %14.7g %14.7g %10zu %10zu\n",
			       rf_header_channel(h, c), st[c].min, st[c].max,
			       (st[c].sum + st[c].comp) / (double)st[c].finite,
			       st[c].nan, st[c].inf);
		else
			printf("\t%-16s %14s %14s %14s %10zu %10zu\n",
			       rf_header_channel(h, c), "-", "-", "-", st[c].nan, st[c].inf);
	}
	free(buf);
	free(st);
}

int
main(int argc, char **argv)
{
	static const struct option long_options[] = {
		{ "help", no_argument, NULL, 'Q' },
		{ "plugins", no_argument, NULL, 'P' },
		{ NULL, 0, NULL, 0 },
	};
	struct cli_io io = { 0 };
	const rf_header *h;
	int c, stats = 0, plugins = 0;

	cli_init(argc, argv);
	while ((c = getopt_long(argc, argv, "sVHx:y:c:", long_options, NULL)) != -1) {
		if (c != 'h' && cli_io_option(&io, c, optarg))
			continue;
		switch (c) {
		case 's': stats = 1; break;
		case 'P': plugins = 1; break;
		case 'V': print_version(); break;
		case 'Q':
			printf("usage: %s [-sV] [-H -x W -y H -c CHANNELS] [file]\n"
			       "       %s --plugins\n"
			       "Prints the header of every frame of a stream (stdin when no file\n"
			       "or '-'). See reflect-info(1).\n"
			       "  -s  per-channel min, max and mean of the finite values, and\n"
			       "      the counts of NaN and Inf\n"
			       "  -H -x W -y H -c CHANNELS  headerless float input of W x H\n"
			       "      pixels; CHANNELS is a list of names or a count\n"
			       "  -V  versions of the tool, the library and the plugin ABI\n"
			       "  --plugins  the plugin search path, and every mode in it: its\n"
			       "      kind, name, file and where that was found\n",
			       argv0, argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default: usage();
		}
	}
	if (argc - optind > 1 || (plugins && argc > optind))
		usage();
	if (plugins)
		mode_list_all();
	cli_io_open(&io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&io, &h)) {
		print_header(h, rf_reader_frame_index(io.reader));
		if (stats)
			frame_stats(&io, h);
	}
	cli_io_close(&io);
	return 0;
}
