/* Messages, allocation and output checks for the tools (sbase style). */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

const char *argv0 = "reflect";

/* The command line as given: getopt permutes argv while it parses. */
static char **command_argv;
static int command_argc;
/* Whether standard output was a terminal when the tool started (before
 * anything could move it). */
static int stdout_terminal;

/* Removes the files being written, then dies of the signal as it would
 * have: the status says which, and a shell stops its loop on SIGINT. */
static void
remove_outputs(int sig)
{
	int e = errno;

	rf_output_remove_all();
	signal(sig, SIG_DFL);
	raise(sig);
	errno = e;
}

/* A signal the parent left ignored (nohup, a background job's SIGINT)
 * stays ignored. */
static void
on_signal(int sig)
{
	struct sigaction sa, old;

	if (sigaction(sig, NULL, &old) == 0 && old.sa_handler == SIG_IGN)
		return;
	memset(&sa, 0, sizeof(sa));
	sa.sa_handler = remove_outputs;
	sigemptyset(&sa.sa_mask);
	sigaction(sig, &sa, NULL);
}

void
cli_init(int argc, char **argv)
{
	const char *slash;

	if (argc > 0 && (command_argv = malloc((size_t)argc * sizeof(*argv)))) {
		memcpy(command_argv, argv, (size_t)argc * sizeof(*argv));
		command_argc = argc;
	}
	if (argc > 0 && argv[0]) {
		slash = strrchr(argv[0], '/');
		argv0 = slash ? slash + 1 : argv[0];
		if (!strncmp(argv0, "lt-", 3))
			argv0 += 3; /* libtool's uninstalled wrapper */
		/* getopt names the program by argv[0] in its messages. */
		argv[0] = (char *)argv0;
	}
	stdout_terminal = isatty(STDOUT_FILENO);
	/* Files being written are removed when a signal ends the tool
	 * (lib/util/output.c): a hidden temporary file would stay. */
	on_signal(SIGINT);
	on_signal(SIGTERM);
	on_signal(SIGHUP);
	/* A closed downstream pipe ends us quietly, even when a parent
	 * process left SIGPIPE ignored. */
	signal(SIGPIPE, SIG_DFL);
}

/*
 * Inputs read where they lie (mapped): a file truncated under the mapping
 * faults on the next read of a page it lost, and SIGBUS would end the
 * tool with no word of why.  The handler says which files it maps, in
 * the usual form, and exits as for any bad input.  The message is made
 * when a file is added, since a handler may not format.
 */
static char mapped_message[2048];
static size_t mapped_len, mapped_count;
/* Several threads may fault on the lost pages at once: the first tells
 * and exits, the others wait for it (an exit of theirs could cut the
 * message short). */
static atomic_flag mapped_told = ATOMIC_FLAG_INIT;

static void
on_sigbus(int sig)
{
	cli_plugin_crash(sig); /* a mode's own bus error: said so */
	if (atomic_flag_test_and_set(&mapped_told))
		for (;;)
			pause();
	if (write(STDERR_FILENO, mapped_message, mapped_len) < 0) {
		/* nothing left to tell it with */
	}
	_exit(EXIT_BAD_INPUT);
}

void
cli_guard_mapped(const char *name)
{
	static char names[1024];
	static size_t used;
	int n;

	if (mapped_count++ == 0)
		signal(SIGBUS, on_sigbus);
	n = snprintf(names + used, sizeof(names) - used, "%s'%s'", used ? " or " : "", name);
	if (n > 0 && (size_t)n < sizeof(names) - used)
		used += (size_t)n;
	n = snprintf(mapped_message, sizeof(mapped_message), "%s: %s: the file shrank "
	             "while it was read (bus error); let a file be while a tool reads it\n",
	             argv0, names);
	mapped_len = n < 0 ? 0 : (size_t)n < sizeof(mapped_message) ? (size_t)n
	                                                             : sizeof(mapped_message) - 1;
}

/* As gzip and zstd do: binary data would garble a terminal and be of no
 * use there.  Text (-fa) is written. */
void
cli_refuse_terminal(const char *what)
{
	if (stdout_terminal)
		die("%s is not written to a terminal: send standard output to a file "
		    "or a pipe%s", what, strcmp(what, "a binary stream") ? ""
		                                                          : " (-fa writes text)");
}

void
cli_record_command(rf_header *h)
{
	int rc = rf_header_add_command(h, command_argc, command_argv);

	if (rc < 0 && rc != RF_EINVAL)
		die_status(rc, NULL);
}

/* Writes s, each control byte (ESC, a tab, a newline...) as '?': a
 * message quotes names from files and command lines, and none of them
 * may move the terminal's cursor or change its colours. */
static void
put_clean(FILE *fp, const char *s)
{
	for (; *s; s++)
		fputc((unsigned char)*s < 0x20 || *s == 0x7f ? '?' : *s, fp);
}

void
cli_message_start(void)
{
	cli_progress_clear();
	put_clean(stderr, argv0);
	fputs(": ", stderr);
}

void
cli_put_quoted(FILE *fp, const char *s)
{
	fputc('\'', fp);
	put_clean(fp, s);
	fputc('\'', fp);
}

/* The message, strerror appended after a format ending in ':', into
 * buf; written to stderr after the tool's name. */
static void
vmessage(char *buf, size_t size, const char *fmt, va_list ap)
{
	size_t n = strlen(fmt), len;
	int e = errno;

	vsnprintf(buf, size, fmt, ap);
	len = strlen(buf);
	if (n && fmt[n - 1] == ':')
		snprintf(buf + len, size - len, " %s", strerror(e));
	cli_message_start();
	put_clean(stderr, buf);
	fputc('\n', stderr);
}

/* The stream the tool writes, ended as failed when it dies. */
static rf_writer *guarded_stream;

void
cli_guard_stream(rf_writer *w)
{
	guarded_stream = w;
}

/* A tool that dies after its stream began ends it with a trailer that
 * every reader refuses (rf_writer_fail): the stream may stop at the end
 * of a frame's rows, which a reader would take for a whole stream. */
static void
end_stream_failed(const char *msg)
{
	static atomic_flag ended = ATOMIC_FLAG_INIT;
	char line[RF_HEADER_LINE_MAX];

	if (!guarded_stream || atomic_flag_test_and_set(&ended))
		return;
	snprintf(line, sizeof(line), "%s: %s", argv0, msg);
	/* a stream that cannot take it is broken already, and said so */
	(void)rf_writer_fail(guarded_stream, line);
}

void
die(const char *fmt, ...)
{
	char buf[4096];
	va_list ap;

	va_start(ap, fmt);
	vmessage(buf, sizeof(buf), fmt, ap);
	va_end(ap);
	end_stream_failed(buf);
	exit(EXIT_BAD_INPUT);
}

void
die_sys(const char *fmt, ...)
{
	char buf[4096];
	va_list ap;

	va_start(ap, fmt);
	vmessage(buf, sizeof(buf), fmt, ap);
	va_end(ap);
	end_stream_failed(buf);
	exit(EXIT_SYSTEM);
}

void
die_status(int status, const char *msg)
{
	if (status == RF_EIO && errno == EPIPE)
		exit(EXIT_SYSTEM); /* downstream closed: no message */
	msg = msg && *msg ? msg : rf_strerror(status);
	cli_message_start();
	put_clean(stderr, msg);
	fputc('\n', stderr);
	end_stream_failed(msg);
	exit(status == RF_EIO || status == RF_ENOMEM ? EXIT_SYSTEM : EXIT_BAD_INPUT);
}

void
die_header_key(int rc)
{
	if (rc == RF_ENOMEM)
		die_status(rc, NULL);
	die("cannot write the output's header: a value is longer than a header line "
	    "(%d bytes)", RF_HEADER_LINE_MAX);
}

void
warn(const char *fmt, ...)
{
	char buf[4096];
	va_list ap;

	va_start(ap, fmt);
	vmessage(buf, sizeof(buf), fmt, ap);
	va_end(ap);
}

void *
emalloc(size_t n)
{
	void *p = malloc(n ? n : 1);

	if (!p)
		die_sys("out of memory (%zu bytes)", n);
	return p;
}

void *
ecalloc(size_t n, size_t size)
{
	void *p = calloc(n ? n : 1, size ? size : 1);

	if (!p)
		die_sys("out of memory (%zu x %zu bytes)", n, size);
	return p;
}

char *
estrdup(const char *s)
{
	char *p = strdup(s);

	if (!p)
		die_sys("out of memory");
	return p;
}

void
fshut(FILE *fp, const char *name)
{
	int err, e;

	errno = 0;
	err = fflush(fp) != 0 || ferror(fp);
	e = errno;
	if (fclose(fp) != 0 && !err) {
		err = 1;
		e = errno;
	}
	if (!err)
		return;
	if (e == EPIPE)
		exit(EXIT_SYSTEM); /* downstream closed: no message */
	errno = e ? e : EIO;
	die_sys("cannot write '%s':", name);
}

void
print_version(void)
{
	printf("%s (reflect) %s\nlibreflect %s\nplugin ABI %d.%d\n", argv0,
	       RF_VERSION_STRING, rf_version_string(), RF_PLUGIN_ABI_MAJOR,
	       RF_PLUGIN_ABI_MINOR);
	fshut(stdout, "<stdout>");
	exit(0);
}

void
cli_check_frame(const char *what, size_t w, size_t h)
{
	if (w > RF_FRAME_SIDE_MAX || h > RF_FRAME_SIDE_MAX)
		die("%s: a frame of %zu x %zu pixels is over the limit of %zu pixels a "
		    "side (reflect-stream(5))", what, w, h, RF_FRAME_SIDE_MAX);
	if (w * h > RF_FRAME_PIXELS_MAX)
		die("%s: a frame of %zu x %zu pixels is over the limit of %zu (2^28) "
		    "pixels (reflect-stream(5))", what, w, h, RF_FRAME_PIXELS_MAX);
}

size_t
parse_count(const char *arg, int opt, size_t min, size_t max)
{
	unsigned long long v;
	char *end;

	errno = 0;
	if (!arg || *arg < '0' || *arg > '9')
		die("option -%c: '%s' is not a non-negative integer", opt, arg ? arg : "");
	v = strtoull(arg, &end, 10);
	if (*end)
		die("option -%c: '%s' is not a non-negative integer", opt, arg);
	if (errno == ERANGE || v < min || v > max)
		die("option -%c: %s is out of range [%zu, %zu]", opt, arg, min, max);
	return (size_t)v;
}

double
parse_number(const char *name, const char *arg, double lo, double hi)
{
	char *end;
	double v;

	errno = 0;
	v = strtod(arg, &end);
	if (end == arg || *end || errno == ERANGE || !isfinite(v) || v < lo || v > hi)
		die("--%s: '%s' is not a number in [%g, %g]", name, arg, lo, hi);
	return v;
}

double
parse_whole(const char *name, const char *arg, double lo, double hi)
{
	double v = parse_number(name, arg, lo, hi);

	if (v != floor(v))
		die("--%s: '%s' is not a whole number in [%.0f, %.0f]", name, arg, lo, hi);
	return v;
}

enum rf_format
parse_format(const char *arg)
{
	if (!strcmp(arg, "a"))
		return RF_FORMAT_ASCII;
	if (strcmp(arg, "f"))
		die("option -f: '%s' is not a data format (a: ascii, f: float)", arg);
	return RF_FORMAT_FLOAT;
}

void
parse_floats(const char *arg, const char *what, float *out, int n)
{
	const char *p = arg;
	char *end;
	int i;

	for (i = 0; i < n; i++) {
		double v;

		errno = 0;
		v = strtod(p, &end);
		if (end == p || errno == ERANGE || !isfinite(v))
			die("%s: '%s' needs %d comma-separated numbers", what, arg, n);
		out[i] = (float)v;
		p = end;
		if (i + 1 < n) {
			if (*p != ',')
				die("%s: '%s' needs %d comma-separated numbers", what, arg, n);
			p++;
		}
	}
	if (*p)
		die("%s: '%s' needs %d comma-separated numbers", what, arg, n);
}

int
cli_threads(const char *arg)
{
	const char *env = getenv("REFLECT_THREADS");
	long n;

	if (arg)
		return (int)parse_count(arg, 'j', 1, 256);
	if (env && *env) {
		char *end;

		n = strtol(env, &end, 10);
		if (*end || n < 1 || n > 256)
			die("REFLECT_THREADS: '%s' is not a thread count in [1, 256]", env);
		return (int)n;
	}
	n = sysconf(_SC_NPROCESSORS_ONLN);
	return n < 1 ? 1 : n > 256 ? 256 : (int)n;
}

const char *
cli_input_or_default(const char *operand)
{
	struct stat st;

	if (operand)
		return operand;
	if (fstat(STDIN_FILENO, &st) < 0)
		return NULL;
	return S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode) || S_ISREG(st.st_mode) ? "-" : NULL;
}
