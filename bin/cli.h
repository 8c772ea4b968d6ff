/* Helpers shared by the reflect-* tools (not part of libreflect). */
#ifndef REFLECT_CLI_H
#define REFLECT_CLI_H

#include <stdio.h>
#include <stdlib.h>

#include "reflect/reflect.h"
#include "reflect/plugin.h"
#include "reflect/scene.h"

#if defined(__GNUC__)
#define CLI_PRINTF(a, b) __attribute__((format(printf, a, b)))
#define CLI_NORETURN __attribute__((noreturn))
#else
#define CLI_PRINTF(a, b)
#define CLI_NORETURN
#endif

enum { EXIT_BAD_INPUT = 1, EXIT_SYSTEM = 2 };

extern const char *argv0;

void cli_init(int argc, char **argv);
/* Dies when standard output is a terminal: what ("a binary stream", "an
 * image") would be written to it. */
void cli_refuse_terminal(const char *what);
/* Appends the command line, in the order it was given, to a header. */
void cli_record_command(rf_header *h);
/* A file the tool may read through a mapping: should it shrink under
 * the mapping, the tool dies with a message naming it (not a bare bus
 * error). */
void cli_guard_mapped(const char *name);
/* A format ending in ':' gets ": strerror(errno)" appended (sbase rule). */
CLI_NORETURN void die(const char *fmt, ...) CLI_PRINTF(1, 2);
CLI_NORETURN void die_sys(const char *fmt, ...) CLI_PRINTF(1, 2);
/* Exit status for a libreflect error: 2 for system errors, else 1. */
CLI_NORETURN void die_status(int status, const char *msg);
/* Dies for a header key the library refused (rc): a value too long for
 * a header line, or out of memory. */
CLI_NORETURN void die_header_key(int rc);
/* The stream w (NULL: none) is ended as failed (rf_writer_fail, with
 * the message) when the tool dies after it began: cli_io_open guards
 * the stream it opens. */
void cli_guard_stream(rf_writer *w);
void warn(const char *fmt, ...) CLI_PRINTF(1, 2);
/* For a message written in pieces: "tool: ", and a name in quotes; both
 * write control bytes as '?', as every message does. */
void cli_message_start(void);
void cli_put_quoted(FILE *fp, const char *s);
void *emalloc(size_t n);
void *ecalloc(size_t n, size_t size);
char *estrdup(const char *s);
/* Flushes and closes fp; a write error ends the tool with status 2, a
 * closed downstream pipe ends it quietly. */
void fshut(FILE *fp, const char *name);
void print_version(void);
/* Dies unless a frame of w x h pixels is within RF_FRAME_SIDE_MAX and
 * RF_FRAME_PIXELS_MAX (reflect-stream(5)); what names the options that
 * made the size. */
void cli_check_frame(const char *what, size_t w, size_t h);
/* Parses a decimal count in [min, max] for option `opt`. */
size_t parse_count(const char *arg, int opt, size_t min, size_t max);
/* Parses a finite number in [lo, hi] for long option --name. */
double parse_number(const char *name, const char *arg, double lo, double hi);
/* A whole number in [lo, hi] for --name, or death saying so. */
double parse_whole(const char *name, const char *arg, double lo, double hi);
/* -f a|f: the stream's data format. */
enum rf_format parse_format(const char *arg);
/* Parses n comma-separated finite numbers for option `what`. */
void parse_floats(const char *arg, const char *what, float *out, int n);

/* A mode that crashes (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT): the
 * tool says which mode, file, call, frame and rows, and dies of the
 * signal.  cli_guard_plugins installs the handler (mode_load does);
 * cli_plugin_crash is its part for another handler of the signal to
 * call first: it returns only when no plugin code was running. */
void cli_guard_plugins(void);
void cli_plugin_crash(int sig);

/* Where the stream goes: stdout, or once a mode is loaded the descriptor
 * that standard output was (mode_load). */
FILE *cli_stdout(void);
/* From now on standard output (fd 1) leads to standard error, for
 * whatever plugin code prints, and cli_stdout() is what it was: before
 * plugin code runs, for a stream or a listing. */
void cli_keep_stdout(void);

/* The part of the full frame a run makes or keeps (cli_region.c):
 * --region=X0,Y0,X1,Y1, --tile=I/N (band I of N bands of whole rows),
 * --halo=P more pixels each way where the frame goes on. */
struct cli_region {
	int given;              /* CLI_OPT_REGION, CLI_OPT_TILE or 0 */
	const char *arg;        /* as given, for messages */
	size_t x0, y0, x1, y1;  /* --region */
	size_t index, count;    /* --tile */
	size_t halo;
};
#define CLI_REGION_OPTIONS \
	{ "region", required_argument, NULL, CLI_OPT_REGION }, \
	{ "tile", required_argument, NULL, CLI_OPT_TILE }, \
	{ "halo", required_argument, NULL, CLI_OPT_HALO }
#define CLI_REGION_USAGE "[--region=X0,Y0,X1,Y1|--tile=I/N] [--halo=P]"
#define CLI_REGION_HELP \
	"  --region=X0,Y0,X1,Y1  only pixels X0 <= x < X1, Y0 <= y < Y1 (a tile)\n" \
	"  --tile=I/N  only band I of N bands of rows   --halo=P  P pixels more\n"
/* Takes --region, --tile and --halo: 1 when opt was one of them. */
int cli_region_option(struct cli_region *r, int opt, const char *arg);
/* The pixels x0 <= x < x1, y0 <= y < y1 (rect) of a full frame of width
 * x height the options ask for, each pixel of the options scale x scale
 * of the frame's (--supersample), the halo added; the whole frame when
 * none was given.  Dies when they do not fit the frame. */
void cli_region_rect(const struct cli_region *r, size_t width, size_t height, size_t scale,
                     size_t rect[4]);
/* REGION in h, whose size is already the tile's. */
void cli_region_key(rf_header *h, const size_t rect[4], size_t width, size_t height);

/* Stream options every stream tool takes: -f a|f, -h, -H -x -y -c. */
struct cli_io {
	enum rf_format format;
	int no_header;
	int headerless;
	size_t x, y;
	const char *channels;
	const char *input_name; /* for messages */
	FILE *input;
	char *image_buf; /* an image file read as a stream: the stream's bytes */
	rf_reader *reader;
	rf_writer *writer;
	size_t frames;          /* read so far: the current one's number */
	enum rf_invalid invalid; /* --invalid, for the stages that check input */
	/* A file the tool made of the last frame (NULL: none), removed
	 * when a failed stream's trailer follows that frame. */
	const char *made;
	/* --region, --tile, --halo: cli_io_next crops each frame to it,
	 * unless crop_output (a filter crops what it writes instead). */
	struct cli_region region;
	int crop_output;
};

/* An input's first bytes, read without taking them from it (cli_sniff.c). */
#define CLI_SNIFF_BYTES 16
struct cli_sniff {
	unsigned char head[CLI_SNIFF_BYTES];
	size_t len;  /* fewer than CLI_SNIFF_BYTES only when the input is shorter */
	int regular; /* a regular file (else a pipe, a FIFO, a device...) */
};
/* Reads fd's first bytes into s and sets *fp to read fd from where it
 * was, those bytes included: fd belongs to *fp then.  0, or -1 with
 * errno (fd still the caller's). */
int cli_sniff_open(int fd, struct cli_sniff *s, FILE **fp);
enum cli_kind { CLI_KIND_STREAM, CLI_KIND_EXR, CLI_KIND_PNG, CLI_KIND_OTHER };
/* What the first bytes say the input is. */
enum cli_kind cli_sniff_kind(const struct cli_sniff *s);

#define CLI_IO_OPTSTRING "f:hHx:y:c:"
#define CLI_IO_USAGE "[-f a|f] [-h] [-H -x W -y H -c CHANNELS]"
/* Makes a pipe's buffer 1 MB (see cli_io.c); anything else is left alone. */
void cli_widen_pipe(int fd);
/* Returns 1 when it took the option. */
int cli_io_option(struct cli_io *io, int opt, const char *arg);
/* Opens the input (NULL or "-" is stdin) and the output on stdout. */
void cli_io_open(struct cli_io *io, const char *path);
/* Next frame: 1 and *h set, 0 at the end of input; dies on errors. */
int cli_io_next(struct cli_io *io, const rf_header **h);
void cli_io_read(struct cli_io *io, float *buf, size_t nrows);
/* Dies with the reader's message for error rc. */
void cli_io_read_failed(struct cli_io *io, int rc);
/* --invalid=error|clamp|zero into io->invalid; dies on another word. */
void cli_io_invalid_option(struct cli_io *io, const char *arg);
#define CLI_INVALID_USAGE "[--invalid=error|clamp|zero]"
/* Dies: the input's pixel broke a rule (why: the library's message). */
CLI_NORETURN void cli_io_invalid_failed(struct cli_io *io, const char *why);
/* Dies: the mode gave up in run() (why: "mode 'name': its message"). */
CLI_NORETURN void cli_io_plugin_failed(struct cli_io *io, const char *why);
/* Says, once a frame, how many pixels were clamped or zeroed. */
void cli_io_invalid_note(struct cli_io *io, size_t count);
void cli_io_begin(struct cli_io *io, const rf_header *h);
void cli_io_write(struct cli_io *io, const float *buf, size_t nrows);
void cli_io_end_frame(struct cli_io *io);
void cli_io_close(struct cli_io *io);

/* Computes one block: n rows from row y, in to out (NULL without output);
 * 0, or an error (bad input: a message of the caller's own) that stops
 * the frame. */
typedef int cli_block_fn(void *arg, const float *in, float *out, size_t y, size_t n);
/* Runs fn over a frame's nrows in blocks of `block` rows (in_floats and
 * out_floats a row), reading ahead and writing behind on threads of their
 * own; in_floats 0: no input (fn gets NULL), out_floats 0: no output.
 * Begin the output frame first.  Dies if a write fails; returns 0, the
 * error fn returned (fn's arg tells which), or the error of a failed
 * read for cli_io_read_failed, once the threads are gone, so that the
 * caller can free what it holds first. */
int cli_blocks(struct cli_io *io, size_t nrows, size_t block, size_t in_floats,
                size_t out_floats, cli_block_fn *fn, void *arg);

/* Rows a tool holds at once: a block of about this many bytes. */
#define CLI_BLOCK_BYTES ((size_t)4 << 20)

/* A per-pixel stage over the frame in, in blocks: begins the output
 * frame out (the stage's output header, its keys set), runs the rows,
 * destroys the stage and ends the frame; a refused pixel, a mode that
 * failed in run() or a failed read ends the process with its message. */
void cli_stage_rows(struct cli_io *io, rf_stage *stage, const rf_header *in,
                    const rf_header *out);

/* The frames of a tool that makes them (cli_frames.c): -n N, the full
 * run; --orbit=DEGREES and --path=orbit:DEGREES|line:X,Y,Z, the camera
 * over it; --frames=A-B or --frame=K, the part of it made here.  The
 * tool renders frames first..last, each as the full run makes it. */
enum {
	CLI_OPT_ORBIT = 0x1000,
	CLI_OPT_PATH,
	CLI_OPT_FRAMES,
	CLI_OPT_FRAME,
	CLI_OPT_PROGRESS,
	CLI_OPT_REGION,
	CLI_OPT_TILE,
	CLI_OPT_HALO
};
#define CLI_FRAME_OPTIONS \
	{ "orbit", required_argument, NULL, CLI_OPT_ORBIT }, \
	{ "path", required_argument, NULL, CLI_OPT_PATH }, \
	{ "frames", required_argument, NULL, CLI_OPT_FRAMES }, \
	{ "frame", required_argument, NULL, CLI_OPT_FRAME }
#define CLI_FRAME_USAGE "[-n FRAMES] [--frames=A-B|--frame=K] [--orbit=DEGREES] " \
	"[--path=orbit:DEGREES|line:X,Y,Z]"
#define CLI_FRAME_HELP \
	"  -n N               N frames, FRAME=0..N-1\n" \
	"  --frames=A-B  --frame=K  only the full run's frames A..B (or K)\n" \
	"  --orbit=DEGREES    turn the camera about its target over the frames\n" \
	"  --path=line:X,Y,Z  move the camera (and its target) to X,Y,Z\n"
struct cli_frames {
	size_t count;        /* -n: the full run's frames */
	size_t first, last;  /* made here: first..last */
	int ranged;          /* --frames or --frame given */
	const char *option, *range; /* which, and its text, for messages */
	struct rf_camera_path path;
};
void cli_frames_init(struct cli_frames *f);
/* A frame's header: its size, the command, the scene's keys for the
 * camera and FRAME; the tool adds its channels and keys. */
rf_header *cli_frame_header(const rf_scene *s, const struct rf_camera *cam, size_t frame,
                            size_t width, size_t height);
/* Takes -n and the options above: 1 when opt was one of them. */
int cli_frames_option(struct cli_frames *f, int opt, const char *arg);
/* Sets first..last, dying unless the range lies within the full run. */
void cli_frames_check(struct cli_frames *f);

/* How far a run is, on stderr (cli_progress.c): on a terminal a line
 * redrawn once the run lasts a second, --progress plain lines, -q
 * nothing.  cli_blocks reports a frame's rows; a tool that knows how
 * many frames it makes says so first. */
enum cli_progress_mode { CLI_PROGRESS_AUTO, CLI_PROGRESS_LINES, CLI_PROGRESS_QUIET };
#define CLI_PROGRESS_OPTION { "progress", no_argument, NULL, CLI_OPT_PROGRESS }
#define CLI_PROGRESS_USAGE "[-q|--progress]"
#define CLI_PROGRESS_HELP \
	"  -q  no progress   --progress  progress as plain lines (else on a terminal)\n"
/* Takes -q and --progress: 1 when opt was one of them. */
int cli_progress_option(int opt);
/* Blocks of at most a 32nd of a frame while progress shows, for a slow
 * tool whose rows do not depend on how they are blocked (trace). */
size_t cli_progress_block(size_t block, size_t rows_a_frame);
void cli_progress_frames(size_t count);
/* -q: not even a note that a slow step begins. */
int cli_progress_quiet(void);
void cli_progress_frame(size_t rows_a_frame);
void cli_progress_rows(size_t done);
/* What the rows count, for a tool whose steps are no rows ("file",
 * "step"; default "row"). */
void cli_progress_unit(const char *name);
/* Nothing after this counts: the frames are made, and a pass that writes
 * what they made (reflect-accumulate's result) is no frame of its own. */
void cli_progress_hold(void);
/* Erases a progress line before a message; cli_progress_end at the end
 * of the run (cli_io_close) also writes --progress's last line. */
void cli_progress_clear(void);
void cli_progress_end(void);

/* Threads over row blocks: -j N, else REFLECT_THREADS, else every core. */
int cli_threads(const char *arg);

/* The input operand of a tool with an embedded default (a scene, an
 * environment): the operand when one is given; else "-" when standard
 * input is a pipe, a socket or a file, so that nothing piped in is
 * ignored; else (a terminal, /dev/null, closed) NULL, the default. */
const char *cli_input_or_default(const char *operand);

/* A scene file (reflect-scene(5)), "-" for standard input, NULL or
 * "default" for the embedded default; death with the parser's message. */
struct rf_scene;
struct rf_scene *cli_load_scene(const char *path);
/* The same, the error returned with its message in err (RF_ENOTFOUND:
 * the file cannot be opened). */
int cli_read_scene(struct rf_scene **s, const char *path, char *err, size_t errlen);

/* --box, --center, --box-projection as given (NULL: not given), for
 * rf_probe_resolve. */
struct cli_probe {
	const char *box;
	const char *center;
	const char *projection;
};

/* Modes (plugins) of one kind: -l and -m name:key=value:... */
struct cli_mode {
	rf_module *module;
	const struct rf_plugin *plugin;
	double *values;
	int verbose;        /* -v */
	unsigned char *told; /* the optional inputs mode_note_absent named */
};
CLI_NORETURN void mode_list(unsigned kind);
/* -m MODE --help: the mode's summary, file and where it was found,
 * channels, parameters and man page, on standard output. */
CLI_NORETURN void mode_help(unsigned kind, const char *spec);
/* reflect-info --plugins: the search path's directories, each mode of
 * every kind with its file and where that lies, the shadowed files. */
CLI_NORETURN void mode_list_all(void);
/* --help's line for -m: the modes of the kind the search path holds,
 * and the default. */
void mode_help_line(unsigned kind, const char *def);
/* Loads a mode: its file found and checked, its parameters parsed (dies
 * with the reason).  Plugin code may print: from the first load on,
 * standard output (fd 1) leads to standard error, and the stream goes
 * out through a descriptor of its own, cli_stdout(). */
void mode_load(struct cli_mode *m, unsigned kind, const char *spec, int verbose);
void mode_unload(struct cli_mode *m);
/* With -v, names the optional inputs of the mode that frame in lacks
 * (they read as NaN), each the first time it is missing. */
void mode_note_absent(struct cli_mode *m, struct cli_io *io, const rf_header *in);
/* Says, once a frame, how many pixels' outputs of the mode were clamped
 * or zeroed (--invalid; rf_stage_invalid_output_count). */
void mode_invalid_note(struct cli_io *io, size_t count);

/* A tool that runs one mode over a stream, frame after frame
 * (cli_stage.c): its options, the mode it loaded and the host. */
struct rf_plugin_host;
struct cli_stage_run {
	struct cli_io io;
	struct cli_mode mode;
	const char *spec; /* -m as given, or the default */
	int nthreads;
	struct rf_plugin_host *host; /* its frame set to the current one */
};
/* The value of --help in a tool's long options. */
#define CLI_OPT_HELP ('?' + 256)
struct option;
struct cli_stage_tool {
	unsigned kind;    /* RF_KIND_* */
	const char *spec; /* the default mode */
	/* Short options besides -l -v -V -m -j and the stream's (NULL: none);
	 * long options, --help (CLI_OPT_HELP) among them. */
	const char *optstring;
	const struct option *long_options;
	/* --help: what the tool does (after "usage:"), then the tool's own
	 * options (after -m's line, before the common options). */
	const char *about;
	const char *help;
	void (*usage)(void);
	/* Takes one of the tool's own options: 1, or 0 for a usage error. */
	int (*option)(struct cli_stage_run *r, int opt, const char *arg);
	/* Once the mode and host are there, before the input is opened;
	 * after the last frame (both may be NULL). */
	void (*start)(struct cli_stage_run *r);
	void (*finish)(struct cli_stage_run *r);
	/* Reads frame in and writes what it makes of it. */
	void (*frame)(struct cli_stage_run *r, const rf_header *in);
};
/* Parses the options, loads the mode and runs the tool over its input:
 * a tool's whole main. */
int cli_stage_main(int argc, char **argv, const struct cli_stage_tool *t);
/* Records the command line in an output header, and the mode as key. */
void cli_stage_header(struct cli_stage_run *r, rf_header *out, const char *key);
/* Dies: the mode refused the input's frame (rc, its message err). */
CLI_NORETURN void cli_stage_refused(struct cli_stage_run *r, int rc, const char *err);
/* The frame's probe, with po's overrides (NULL: none): 1, or 0 when the
 * frame has none; death for a probe that cannot be. */
int cli_probe_resolve(struct rf_probe *probe, const rf_header *in,
                      const struct cli_probe *po);
/* The mode's per-pixel stage for frame in, the host's probe set to probe
 * (NULL: none); *out, begun, records the command line and the mode as
 * key.  For cli_stage_rows. */
rf_stage *cli_stage_begin(struct cli_stage_run *r, const rf_header *in,
                          const struct rf_probe *probe, const char *key, rf_header **out);

#endif
