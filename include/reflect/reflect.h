/*
 * libreflect: box-projected cubemap reflections, offline.
 *
 * Every function that can fail returns 0 (or a count) on success and a
 * negative rf_status on failure; nothing here prints or exits.
 *
 * Objects that hold state are opaque, made by rf_<name>_create (or a
 * constructor that says how it makes one: rf_header_dup, rf_image_read,
 * rf_scene_parse) and ended by rf_<name>_destroy.  Handles on a file or
 * a stream are opened and closed (rf_reader_open, rf_image_writer_close),
 * plugins loaded and unloaded (rf_module_load).
 *
 * Where there is more to say than the status, the message goes where
 * the caller gave room for it: the err buffer (char *err, size_t
 * errlen) of a call that sets something up, or, for the calls a tool
 * makes on an open handle block after block (rf_reader_read_rows,
 * rf_writer_write_rows, rf_stage_run, rf_image_writer_write_rows...),
 * the handle, whose rf_<name>_error() returns it.  Messages name the
 * file, line or channel and what was expected.
 */
#ifndef REFLECT_REFLECT_H
#define REFLECT_REFLECT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "reflect/version.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__) && !defined(RF_STATIC)
#define RF_EXTERN __attribute__((visibility("default")))
#else
#define RF_EXTERN
#endif

/* Errors: one list makes the enum and the messages. */
#define RF_STATUS_MAP(X)                                                  \
	X(NOMEM, "out of memory")                                         \
	X(IO, "input/output error")                                       \
	X(EOF, "end of stream")                                           \
	X(FORMAT, "malformed stream")                                     \
	X(VERSION, "unsupported stream version")                          \
	X(TRUNCATED, "truncated stream")                                  \
	X(TOOBIG, "size out of range")                                    \
	X(CHANNEL, "missing or bad channel")                              \
	X(INVAL, "invalid argument")                                      \
	X(PLUGIN, "plugin refused")                                       \
	X(NOTFOUND, "not found")                                          \
	X(IMAGE, "image error")                                           \
	X(FAILED, "the stream's writer failed")

enum rf_status {
	RF_OK = 0,
#define RF_STATUS_ENUM(name, msg) RF_E##name,
	RF__STATUS_FIRST = -100,
	RF_STATUS_MAP(RF_STATUS_ENUM)
#undef RF_STATUS_ENUM
	RF__STATUS_END
};

RF_EXTERN const char *rf_strerror(int status);
RF_EXTERN const char *rf_status_name(int status);

/*
 * Files written whole or not at all (lib/util/output.c): to a temporary
 * file beside the path, synced and renamed over it by rf_output_commit;
 * removed by rf_output_discard, at exit(3), and by rf_output_remove_all.
 * A path that is a device, a FIFO or a symbolic link is written in place.
 */
typedef struct rf_output rf_output;

/* The temporary file for path, made (empty): write rf_output_file(*o). */
RF_EXTERN int rf_output_begin(rf_output **o, const char *path, char *err, size_t errlen);
/* The same, opened for writing as *fp (rf_output_commit closes it). */
RF_EXTERN int rf_output_open(rf_output **o, const char *path, FILE **fp, char *err,
                             size_t errlen);
/* The file to write: the temporary file, or the path itself. */
RF_EXTERN const char *rf_output_file(const rf_output *o);
/* Flushes and syncs the file and renames it to its path; frees o.  On
 * an error (the reason in err) the file is removed, the old one kept. */
RF_EXTERN int rf_output_commit(rf_output *o, char *err, size_t errlen);
/* Removes the temporary file; frees o.  NULL is ignored. */
RF_EXTERN void rf_output_discard(rf_output *o);
/* Removes every temporary file still being written, with nothing but
 * unlink(2): for a signal handler, which the library never installs. */
RF_EXTERN void rf_output_remove_all(void);

RF_EXTERN unsigned rf_version(void);
RF_EXTERN const char *rf_version_string(void);

/*
 * The stream header.  It keeps every line it was given, in order: free
 * lines (each tool's command line) and KEY=value lines, unknown keys
 * included.  The size keys (NCOLS NROWS NCOMP CHANNELS BigEndian FORMAT)
 * are not stored as lines; the writer produces them from the fields.
 */
#define RF_HEADER_LINE_MAX 2048 /* bytes per header line, newline excluded */
#define RF_HEADER_LINES_MAX 4096
#define RF_CHANNELS_MAX 1024
#define RF_CHANNEL_NAME_MAX 63
#define RF_ROW_BYTES_MAX ((size_t)1 << 30)
/* The largest frame a tool makes from a size it is given (reflect-stream(5),
 * LIMITS): a side of at most 2^16 pixels and at most 2^28 pixels (16384 x
 * 16384), the limit on the values of an image the readers take. */
#define RF_FRAME_SIDE_MAX ((size_t)1 << 16)
#define RF_FRAME_PIXELS_MAX ((size_t)1 << 28)

enum rf_format {
	RF_FORMAT_FLOAT = 0,
	RF_FORMAT_ASCII = 1
};

typedef struct rf_header rf_header;

RF_EXTERN int rf_header_create(rf_header **h);
/* A copy of every field and line of h. */
RF_EXTERN int rf_header_dup(rf_header **copy, const rf_header *h);
RF_EXTERN void rf_header_destroy(rf_header *h);

RF_EXTERN size_t rf_header_ncols(const rf_header *h);
RF_EXTERN size_t rf_header_nrows(const rf_header *h);
RF_EXTERN int rf_header_set_size(rf_header *h, size_t ncols, size_t nrows);
/* 1 when the data (as read) was big-endian, 0 otherwise. */
RF_EXTERN int rf_header_big_endian(const rf_header *h);
RF_EXTERN enum rf_format rf_header_format(const rf_header *h);

RF_EXTERN size_t rf_header_nchannels(const rf_header *h);
RF_EXTERN const char *rf_header_channel(const rf_header *h, size_t i);
/* Index of the channel, or RF_ECHANNEL when there is none. */
RF_EXTERN int rf_header_find_channel(const rf_header *h, const char *name);
/* Appends a channel; returns its index.  A name already present is refused. */
RF_EXTERN int rf_header_add_channel(rf_header *h, const char *name);
/* Replaces the channel list; names separated by spaces or commas. */
RF_EXTERN int rf_header_set_channels(rf_header *h, const char *names);
/* A channel name is printable ASCII without spaces, commas or '='. */
RF_EXTERN int rf_channel_name_valid(const char *name);

/* KEY=value lines.  get returns NULL when the key is absent. */
RF_EXTERN const char *rf_header_get(const rf_header *h, const char *key);
RF_EXTERN int rf_header_set(rf_header *h, const char *key, const char *value);
RF_EXTERN int rf_header_unset(rf_header *h, const char *key);
/* A free line, e.g. a tool's command line (kept in order). */
RF_EXTERN int rf_header_add_line(rf_header *h, const char *line);
/* Appends "tool arg arg..." with arguments quoted where needed. */
RF_EXTERN int rf_header_add_command(rf_header *h, int argc, char *const *argv);
/* The stored lines in order, for printing; NULL past the end. */
RF_EXTERN const char *rf_header_line(const rf_header *h, size_t i);

/* How many samples across a pixel is (RF_KEY_SUPERSAMPLE): 1 without
 * the key; RF_EFORMAT when the value is not a whole number in [1,
 * RF_SUPERSAMPLE_MAX] or the frame's sides are not multiples of it. */
#define RF_SUPERSAMPLE_MAX 16
RF_EXTERN int rf_header_supersample(const rf_header *h, size_t *factor);

/* How many samples each value of the frame is the mean of
 * (RF_KEY_SAMPLES): 1 without the key, so that frames of one sample
 * each, as most tools make, merge as they always did; RF_EFORMAT when
 * the value is not a whole number in [1, RF_SAMPLES_MAX]. */
#define RF_SAMPLES_MAX 4294967295u
RF_EXTERN int rf_header_samples(const rf_header *h, uint64_t *samples);

/* Where a frame lies in a larger one, the full frame a tile of it was
 * cut from (RF_KEY_REGION): its first pixel's column x0 and row y0 in a
 * full frame of width x height pixels.  Without the key a frame is its
 * own full frame (x0 = y0 = 0, its own size), so that streams made
 * before tiles read as they always did. */
struct rf_region {
	size_t x0, y0;
	size_t width, height;
};
/* The frame's region; RF_EFORMAT (and *r the whole frame) when the value
 * is not four whole numbers or the frame does not lie within the full
 * frame, whose sides are at most RF_FRAME_SIDE_MAX. */
RF_EXTERN int rf_header_region(const rf_header *h, struct rf_region *r);
/* Sets the key for a frame whose size is already set; a region that is
 * the whole frame removes it.  RF_EINVAL when the frame does not lie
 * within r. */
RF_EXTERN int rf_header_set_region(rf_header *h, const struct rf_region *r);

/*
 * The header keys the tools share (reflect-stream(5) lists them).  Each
 * name is defined here once; the probe's keys are written and read only
 * by the functions below, so that a word means one thing in every tool.
 */
#define RF_KEY_SCENE "SCENE"           /* the scene's name */
#define RF_KEY_CAMERA "CAMERA"         /* position, target, up (3 each), fov */
#define RF_KEY_FRAME "FRAME"           /* the frame's number, from 0 */
#define RF_KEY_SUPERSAMPLE "SUPERSAMPLE" /* N: a pixel is N x N samples */
#define RF_KEY_SAMPLES "SAMPLES"       /* N: each value a mean of N samples */
#define RF_KEY_REGION "REGION"         /* X0 Y0 WIDTH HEIGHT: a tile's place in
                                          the full frame, and that frame's size */
#define RF_KEY_PROBE_BOX "PROBE_BOX"   /* XMIN YMIN ZMIN XMAX YMAX ZMAX */
#define RF_KEY_PROBE_CENTER "PROBE_CENTER" /* X Y Z, the capture point */
#define RF_KEY_PROBE_BOX_PROJECTION "PROBE_BOX_PROJECTION" /* 1 or 0 */
#define RF_KEY_PROBE_ENV "PROBE_ENV"   /* the probe's environment file */
#define RF_KEY_PROBE_BLEND "PROBE_BLEND" /* blend distance in metres */
#define RF_KEY_PROBE_IMPORTANCE "PROBE_IMPORTANCE" /* blending order, highest first */
#define RF_KEY_PROBE_BEVEL "PROBE_BEVEL" /* RADIUS [grown]: the rounded box */
#define RF_KEY_PROBE_SHAPE "PROBE_SHAPE" /* box or sphere (inscribed in PROBE_BOX) */
#define RF_KEY_PROBE_ROTATION "PROBE_ROTATION" /* 9 numbers, row-major, about
                                                  the box's centre */
#define RF_KEY_PROBE_PROXY "PROBE_PROXY" /* box, sphere or infinite: the shape
                                            lookups project onto */
#define RF_KEY_PROBE_PROXY_BOX "PROBE_PROXY_BOX" /* as PROBE_BOX, the proxy's */
#define RF_KEY_PROBE_PROXY_ROTATION "PROBE_PROXY_ROTATION" /* as PROBE_ROTATION */
#define RF_KEY_PROJECTION "PROJECTION" /* reflect-project's mode */
#define RF_KEY_SHADE "SHADE"           /* reflect-shade's mode */
#define RF_KEY_OCCLUSION "OCCLUSION"   /* reflect-occlude's mode */
#define RF_KEY_ENV_MAPPING "ENV_MAPPING" /* the roughness-to-lod mapping used */
#define RF_KEY_ENV_STEPS "ENV_STEPS"   /* the lod of its roughest level */
#define RF_KEY_ACCUMULATE "ACCUMULATE" /* reflect-accumulate's mode */
#define RF_KEY_ACCUMULATED "ACCUMULATED" /* frames in an accumulated result */
#define RF_KEY_FILTER "FILTER"         /* reflect-filter's mode */

/*
 * Reading.  A reader takes frames back to back until EOF.  Errors fill a
 * message (see rf_reader_error) that names the input, the header line or
 * the row, and what was expected.
 */
typedef struct rf_reader rf_reader;

struct rf_raw_input {
	/* For headerless input (-H): geometry and channel names. */
	size_t ncols, nrows;
	const char *channels; /* "a b c" or "a,b,c" */
	enum rf_format format;
};

RF_EXTERN int rf_reader_open(rf_reader **r, FILE *fp, const char *name,
                             const struct rf_raw_input *raw);
RF_EXTERN void rf_reader_close(rf_reader *r);
/* 1 and *h set when a frame starts, 0 at a clean end of input, < 0 error.
 * The header stays owned by the reader until the next call. */
RF_EXTERN int rf_reader_next_frame(rf_reader *r, const rf_header **h);
/* Reads nrows rows of the current frame into buf (ncols*ncomp floats a
 * row), converting to native floats. */
RF_EXTERN int rf_reader_read_rows(rf_reader *r, float *buf, size_t nrows);
/* The next nrows rows where they lie, without a copy: when the input is a
 * regular file of float data in this machine's byte order, *rows points
 * into a read-only mapping of it, valid until the next call on the reader.
 * Otherwise *rows is NULL and nothing is consumed: read them instead
 * (as for data that ends early, whose message rf_reader_read_rows gives). */
RF_EXTERN int rf_reader_map_rows(rf_reader *r, size_t nrows, const float **rows);
/* Rows of the current frame not yet read. */
RF_EXTERN size_t rf_reader_rows_left(const rf_reader *r);
/* Reads of the current frame only its pixels x0 .. x1 - 1 of rows y0 ..
 * y1 - 1, in the full frame's coordinates (its REGION), before any of
 * its rows is read: *h is then the frame's header with the tile's size
 * and REGION.  The rest of the frame is skipped, and map_rows maps
 * nothing.  RF_EINVAL (the message says why) for an empty rectangle or
 * one that the frame does not hold. */
RF_EXTERN int rf_reader_crop(rf_reader *r, size_t x0, size_t y0, size_t x1, size_t y1,
                             const rf_header **h);
/* Index (from 0) of the current frame. */
RF_EXTERN size_t rf_reader_frame_index(const rf_reader *r);
RF_EXTERN const char *rf_reader_error(const rf_reader *r);
/* rf_reader_next_frame returns RF_EFAILED for a trailer (see
 * rf_writer_fail): the tool that wrote the stream failed, and the frame
 * before the trailer is not to be trusted; the error message says so,
 * with the writer's own message. */
/* 1 when bytes, the first len of an input, begin as a stream does: with
 * its magic, whatever version follows (the reader judges that); else 0,
 * as for fewer bytes than the magic's.  For a tool that tells a stream
 * from an image before it reads either. */
RF_EXTERN int rf_stream_sniff(const void *bytes, size_t len);

/* Writing. */
typedef struct rf_writer rf_writer;

struct rf_writer_options {
	enum rf_format format;
	int no_header; /* -h: data only */
};

RF_EXTERN int rf_writer_open(rf_writer **w, FILE *fp, const char *name,
                             const struct rf_writer_options *opt);
RF_EXTERN void rf_writer_close(rf_writer *w);
RF_EXTERN int rf_writer_begin_frame(rf_writer *w, const rf_header *h);
RF_EXTERN int rf_writer_write_rows(rf_writer *w, const float *buf, size_t nrows);
/* Checks that every row of the frame was written. */
RF_EXTERN int rf_writer_end_frame(rf_writer *w);
RF_EXTERN const char *rf_writer_error(const rf_writer *w);
/* Ends the stream of a tool that cannot go on, so that no reader takes
 * it for whole (reflect-stream(5), FAILED STREAMS): the rows of a frame
 * begun and not finished are written as NaN, then a trailer, a header
 * with the one key FAILED=message (a line, cut to fit).  Nothing when
 * no frame was begun or the stream has no headers (-h).  0, or RF_EIO;
 * the writer takes no more frames after it. */
RF_EXTERN int rf_writer_fail(rf_writer *w, const char *message);

/* The number of rows that fit in about `bytes` for a row of ncols*ncomp
 * floats (at least 1): the block size tools stream with. */
RF_EXTERN size_t rf_block_rows(size_t ncols, size_t ncomp, size_t bytes);

/*
 * Plugins (see reflect/plugin.h for the ABI).  A loaded plugin is opaque;
 * its descriptor is checked before anything else in it is touched.
 */
struct rf_plugin;
typedef struct rf_module rf_module;

RF_EXTERN const char *rf_plugin_kind_name(unsigned kind);
/* 1 for a shade mode that writes spec.R G B itself (RF_PLUGIN_RADIANCE,
 * or an ABI 1.0 mode without roughness.eff), 0 for one the host
 * samples for. */
RF_EXTERN int rf_plugin_writes_radiance(const struct rf_plugin *p);
/* 1 for such a mode that traces into the environment as it is (level 0
 * and plain box-filtered levels, the host's sample_radiance), 0 for one
 * that reads the GGX chain (RF_PLUGIN_PREFILTERED) or is sampled for:
 * whether a raw environment is prefiltered for the mode, and whether
 * the host makes the plain levels. */
RF_EXTERN int rf_plugin_traces_raw(const struct rf_plugin *p);
/* Searches REFLECT_PLUGIN_PATH, then REFLECT_PLUGIN_SYSTEM_PATH (when set;
 * empty means none) else the installed directory, for KIND-NAME.so (the
 * kind as rf_plugin_kind_name spells it) then NAME.so in each, passing
 * over files that are no plugin.  A name containing '/' is a path.  A file is read
 * as data before dlopen: one cut short, of another machine, or without
 * the entry is refused unloaded.  On failure err holds the reason. */
RF_EXTERN int rf_module_load(rf_module **m, const char *name, unsigned kind,
                             char *err, size_t errlen);
RF_EXTERN int rf_module_load_file(rf_module **m, const char *path, unsigned kind,
                                  char *err, size_t errlen);
RF_EXTERN void rf_module_unload(rf_module *m);
RF_EXTERN const struct rf_plugin *rf_module_plugin(const rf_module *m);
RF_EXTERN const char *rf_module_path(const rf_module *m);

/* The directories searched, in order, as one ':'-separated string owned
 * by the library (valid until the next call): REFLECT_PLUGIN_PATH's,
 * REFLECT_PLUGIN_SYSTEM_PATH's (when set) or the installed directory,
 * then the user's own, $XDG_DATA_HOME/reflect/plugins (else
 * ~/.local/share/reflect/plugins) when it is a directory. */
RF_EXTERN const char *rf_plugin_search_path(void);
/* Directory i (from 0) of the search path, and where it comes from
 * ("REFLECT_PLUGIN_PATH", "REFLECT_PLUGIN_SYSTEM_PATH", "the installed
 * plugin directory", "the user plugin directory", the last one even
 * when it is not made yet): 1, or 0 past the last.  Both are the
 * library's, valid until the next call. */
RF_EXTERN int rf_plugin_search_dir(size_t i, const char **dir, const char **origin);
/* Where in the search path a plugin file lies: the origin of the first
 * directory that holds it, as rf_plugin_search_dir names it, or NULL
 * (a path given to -m). */
RF_EXTERN const char *rf_plugin_dir_origin(const char *path);
/* The man page of the mode p loaded from path: reflect-mode-KIND-NAME.7
 * or reflect-mode-NAME.7 beside the file, or for a mode of the installed
 * plugin directory in the installation's man7; its path into buf and 0,
 * else RF_ENOTFOUND. */
RF_EXTERN int rf_plugin_man_page(const char *path, const struct rf_plugin *p, char *buf,
                                 size_t len);

/* Checks the directories of REFLECT_PLUGIN_PATH and of
 * REFLECT_PLUGIN_SYSTEM_PATH (or the installed one): RF_EPLUGIN, with err
 * naming it and the fix, for one that every user may write to and that
 * is not sticky (rf_module_load and rf_plugin_scan refuse to search
 * such a path); else 0, with warning (when not NULL) saying which
 * directory is relative, or "". */
RF_EXTERN int rf_plugin_path_check(char *err, size_t errlen, char *warning,
                                   size_t warnlen);

/* Calls fn for every plugin file (*.so) in the search path, in the order
 * rf_module_load tries them; `shadowed` is 1 for a file it never reaches,
 * as one of the mode's names comes first (a NAME.so after a KIND-NAME.so
 * is loaded to learn whether it is of that kind).  A file that is no
 * plugin (not ELF, or exporting no rf_plugin_entry) is passed over
 * unloaded; one cut short is visited, for its refusal. */
typedef void (*rf_plugin_visit_fn)(void *arg, const char *path, int shadowed);
RF_EXTERN int rf_plugin_scan(rf_plugin_visit_fn fn, void *arg);

/* The plugin code the calling thread is running, for a crash handler
 * (a mode that faults takes the process with it): NULL when none, else
 * the mode (NULL while its file loads), its file (NULL when unknown),
 * which call ("load", "create", "run", "destroy"), and for run() the
 * frame (counted from 1) and the rows.  Async-signal-safe: it only reads
 * the thread's own record, which the library sets around every call. */
struct rf_plugin_call {
	const char *mode;
	const char *file;
	const char *what;
	size_t frame;
	size_t row_first, nrows; /* the first row from 0, and how many */
};
RF_EXTERN const struct rf_plugin_call *rf_plugin_current_call(void);

/* Parses "key=value:key=value" against the plugin's parameter table into
 * values[nparams] (defaults first).  err names the key and the range. */
struct rf_param;
RF_EXTERN int rf_plugin_parse_params(const struct rf_plugin *p, const char *spec,
                                     double *values, char *err, size_t errlen);
/* The string an RF_PARAM_STRING parameter's value stands for (its value
 * from rf_plugin_parse_params, the given string's or the default's); a
 * value it did not make gives q's default (q->choices, or "" for q NULL
 * or without one).  The library keeps the strings for the process's
 * life. */
RF_EXTERN const char *rf_plugin_param_string(const struct rf_param *q, double value);

RF_EXTERN float rf_srgb_encode(float linear);
RF_EXTERN float rf_srgb_decode(float encoded);

/*
 * A stage runs one plugin over the frames of a stream: it maps the
 * plugin's inputs to stream channels by name, keeps every other channel,
 * appends the plugin's outputs (or overwrites channels of the same name)
 * and spreads rows over threads, one plugin instance per thread.
 */
struct rf_host;
typedef struct rf_stage rf_stage;

RF_EXTERN int rf_stage_create(rf_stage **s, const struct rf_plugin *p,
                              const double *values, const struct rf_host *host,
                              int nthreads, char *err, size_t errlen);
RF_EXTERN void rf_stage_destroy(rf_stage *s);
/* Prepares a frame with this input header; the output header is valid
 * until the next call.  err names a missing channel. */
RF_EXTERN int rf_stage_begin_frame(rf_stage *s, const rf_header *in,
                                   rf_header **out, char *err, size_t errlen);
/* Appends a channel the stage leaves alone (it neither copies nor
 * writes it) to the current frame's output header, for a later pass over
 * the same rows to fill in place; returns its index, or the existing
 * channel's of that name.  After rf_stage_begin_frame. */
RF_EXTERN int rf_stage_reserve_channel(rf_stage *s, const char *name);
/* Gives the plugin value for its input channel name at every pixel, in
 * place of the stream's (reflect-shade --box-projection=off gives
 * hit.dist and probe.dist +inf, so that every mode is the classic
 * lookup); NULL name drops every such value.  RF_ENOTFOUND when the
 * plugin reads no such channel (nothing is changed). */
RF_EXTERN int rf_stage_set_input_value(rf_stage *s, const char *name, float value);
/* Processes nrows rows starting at row y of the current frame.  Under
 * RF_INVALID_ERROR (the default) a pixel whose input is invalid (see
 * below) makes it return RF_EINVAL, with the first such pixel of the
 * rows in rf_stage_error. */
RF_EXTERN int rf_stage_run(rf_stage *s, const float *in, float *out, size_t y,
                           size_t nrows);

/*
 * Invalid input: of the channels a stage's plugin reads, P.*, R.* and D.*
 * must be finite; hit.dist and probe.dist must not be NaN (negative is
 * behind the point, +inf nothing hit);
 * N, Ng and V (all three components read) directions, finite and neither
 * so long nor so short that their squared length leaves float's range,
 * but where the stream's mask is 0 (a wall reflects nothing); roughness,
 * metallic and mask must lie in [0, 1]; emission.R G B must be a radiance,
 * finite and not negative.  What to do with a pixel that
 * breaks a rule: stop with a message naming the frame, row, pixel and
 * channel (ERROR); clamp a scalar to its range (NaN to its low end, a
 * distance's NaN to +inf, a radiance's +inf to FLT_MAX), an infinite
 * coordinate to +-FLT_MAX, and normalise a vector, in double
 * (CLAMP); or write the plugin's outputs of that pixel as 0 (ZERO, and
 * CLAMP for a vector without any direction, such as zero).  Clamped and
 * zeroed pixels are counted.
 */
enum rf_invalid { RF_INVALID_ERROR = 0, RF_INVALID_CLAMP = 1, RF_INVALID_ZERO = 2 };
/* "error", "clamp" or "zero"; RF_EINVAL for anything else. */
RF_EXTERN int rf_invalid_parse(const char *name, enum rf_invalid *policy);
RF_EXTERN void rf_stage_set_invalid(rf_stage *s, enum rf_invalid policy);
/* The message of the last RF_EINVAL from rf_stage_run in this frame
 * ("row 3, pixel 5: channel 'N.X' is nan", counted from 1), "" when there
 * was none. */
RF_EXTERN const char *rf_stage_error(const rf_stage *s);
/* Pixels of the current frame clamped or zeroed so far. */
RF_EXTERN size_t rf_stage_invalid_count(const rf_stage *s);
/* What the plugin writes is checked too: of its outputs, those that are
 * channels of the rules above keep them (a projection's R.*, D.* finite,
 * hit.dist and probe.dist not NaN), roughness.eff and occlusion lie in
 * [0, 1], spec.* are radiances (finite, not negative), and no other
 * output is NaN; but where the stream's mask is 0.  A pixel that breaks
 * one is handled under the same policy, its message "row R, pixel X:
 * mode 'm' broke its output contract: channel 'c' is ..."; these are
 * the pixels of the frame whose outputs were clamped or zeroed so far. */
RF_EXTERN size_t rf_stage_invalid_output_count(const rf_stage *s);

/*
 * An accumulator runs an accumulate mode (plugin.h) over the frames of a
 * stream: it keeps the mode's state for every value of every pixel
 * between frames, and writes a frame's running result in place of each
 * accumulated channel (with stats, its standard error as NAME.se, added
 * or overwritten).  Frames must have frame 0's size and channel list.
 */
typedef struct rf_accumulator rf_accumulator;

struct rf_accumulate_options {
	const char *channels; /* "a,b" ("a b"), or NULL: every spec.* and R G B */
	const char *reset;    /* header keys ("CAMERA,SCENE") whose change from
	                         one frame to the next restarts, or NULL */
	int stats;            /* write NAME.se channels */
	int keep;             /* keep the last frame for rf_accumulator_result */
};

RF_EXTERN int rf_accumulator_create(rf_accumulator **a, const struct rf_plugin *p,
                                    const double *values, const struct rf_host *host,
                                    int nthreads, const struct rf_accumulate_options *o,
                                    char *err, size_t errlen);
RF_EXTERN void rf_accumulator_destroy(rf_accumulator *a);
/* Takes the next frame's header; the output header (the input's, with
 * the .se channels and ACCUMULATED) is valid until the next call.  err
 * names the frame and how it differs from frame 0, or the channel that
 * is missing. */
RF_EXTERN int rf_accumulator_begin_frame(rf_accumulator *a, const rf_header *in,
                                         rf_header **out, char *err, size_t errlen);
/* Adds nrows rows of the frame from row y; with out (output layout) not
 * NULL, writes them with the running result.  A value that is not
 * finite stops it with RF_EINVAL and the first such pixel of the rows in
 * rf_accumulator_error. */
RF_EXTERN int rf_accumulator_run(rf_accumulator *a, const float *in, float *out,
                                 size_t y, size_t nrows);
/* The result so far, rows y.. of the last frame (options.keep). */
RF_EXTERN int rf_accumulator_result(rf_accumulator *a, float *out, size_t y,
                                    size_t nrows);
/* Frames in the state: since the start, or the last reset. */
RF_EXTERN size_t rf_accumulator_count(const rf_accumulator *a);
RF_EXTERN const char *rf_accumulator_error(const rf_accumulator *a);

/*
 * A filter runs a filter mode (plugin.h) over a frame in passes, holding
 * a band of rows per pass, not the frame: it reads the frame's rows
 * through a callback as its bands have room, and writes each row as soon
 * as it is filtered, the filtered channels (those named, or by default
 * every spec.* channel and R G B) in place, every other channel as read,
 * but for the standard errors of those filtered (NAME.se, not filtered
 * themselves), which the filter made stale: the output has them not.
 */
typedef struct rf_filter rf_filter;

struct rf_filter_options {
	const char *channels; /* "a,b" ("a b"), or NULL: every spec.* and R G B */
};

/* nrows rows into rows (the frame's layout), in order; 0 or an error. */
typedef int rf_filter_read_fn(void *arg, float *rows, size_t nrows);
typedef int rf_filter_write_fn(void *arg, const float *rows, size_t nrows);

/* host is an rf_plugin_host's table (rf_plugin_host_table), to which
 * the mode declares its passes; RF_EINVAL for a table of the caller's. */
RF_EXTERN int rf_filter_create(rf_filter **f, const struct rf_plugin *p,
                               const double *values, const struct rf_host *host,
                               int nthreads, const struct rf_filter_options *o,
                               char *err, size_t errlen);
RF_EXTERN void rf_filter_destroy(rf_filter *f);
/* Takes the next frame's header; the output header (the input's, less
 * the stale standard errors) is valid until the next call.  err names a
 * missing guide channel. */
RF_EXTERN int rf_filter_begin_frame(rf_filter *f, const rf_header *in, rf_header **out,
                                    char *err, size_t errlen);
/* Filters the frame: every row read once, written once, in order.  A
 * filtered value that is not finite stops it with RF_EINVAL and the
 * pixel in rf_filter_error; a callback's error is returned as it is. */
RF_EXTERN int rf_filter_frame(rf_filter *f, rf_filter_read_fn *read_rows,
                              rf_filter_write_fn *write_rows, void *arg);
/* The passes the mode declared. */
RF_EXTERN uint32_t rf_filter_passes(const rf_filter *f);
/* How far a filtered pixel reaches, rows (and columns) each way: the
 * sum of the passes' radii.  A tile filtered with that many more pixels
 * around it (its halo, where the frame goes on) is the filtered full
 * frame's tile. */
RF_EXTERN size_t rf_filter_reach(const rf_filter *f);
RF_EXTERN const char *rf_filter_error(const rf_filter *f);

#ifdef __cplusplus
}
#endif

/* Images, their comparison and reports of modes against the truth have
 * headers of their own; they are part of this one. */
#include "reflect/image.h"
#include "reflect/compare.h"
#include "reflect/report.h"

#endif
