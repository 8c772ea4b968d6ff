/*
 * A mode that crashes takes the tool with it: without a word the shell
 * says "Segmentation fault", and the user cannot tell the mode's bug
 * from the tool's.  The handler below says which mode, from which file,
 * in which call, on which frame and rows, and then dies of the same
 * signal, so the exit status is the one the crash would have had.
 *
 * It only formats strings the library prepared (rf_plugin_current_call:
 * the faulting thread's own record) and integers, with write(2); it runs
 * on an alternate stack, so that a mode that overflows its stack is
 * reported too.  A fault outside plugin code goes to whatever handled
 * it before (a sanitizer's, the mapped-file one), or kills as it would.
 */
#include <signal.h>
#include <stdatomic.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

static const int crash_signals[] = { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT };
#define NSIGNALS (sizeof(crash_signals) / sizeof(crash_signals[0]))
static struct sigaction previous[NSIGNALS];
/* Threads may crash at once: the first tells, the others wait for the
 * signal it dies of. */
static atomic_flag told = ATOMIC_FLAG_INIT;

struct line {
	char buf[2048];
	size_t n;
};

/* A string, control bytes as '?', as every message writes them. */
static void
put(struct line *l, const char *s)
{
	for (; s && *s && l->n < sizeof(l->buf) - 1; s++)
		l->buf[l->n++] = (unsigned char)*s < 0x20 || *s == 0x7f ? '?' : *s;
}

static void
put_number(struct line *l, size_t v)
{
	char digits[24];
	int k = 0;

	do
		digits[k++] = (char)('0' + v % 10);
	while ((v /= 10) && k < (int)sizeof(digits));
	while (k && l->n < sizeof(l->buf) - 1)
		l->buf[l->n++] = digits[--k];
}

static const char *
signal_text(int sig)
{
	switch (sig) {
	case SIGSEGV:
		return "segmentation fault (SIGSEGV)";
	case SIGBUS:
		return "bus error (SIGBUS)";
	case SIGFPE:
		return "arithmetic exception (SIGFPE)";
	case SIGILL:
		return "illegal instruction (SIGILL)";
	case SIGABRT:
		return "abort (SIGABRT)";
	}
	return "a fatal signal";
}

/* Dies of sig now, as without a handler: a raised signal stays pending
 * while the handler blocks it, so it is unblocked here. */
static void
die_of(int sig)
{
	struct sigaction dfl;
	sigset_t set;

	memset(&dfl, 0, sizeof(dfl));
	dfl.sa_handler = SIG_DFL;
	sigemptyset(&dfl.sa_mask);
	sigaction(sig, &dfl, NULL);
	raise(sig);
	sigemptyset(&set);
	sigaddset(&set, sig);
	sigprocmask(SIG_UNBLOCK, &set, NULL);
	_exit(128 + sig);
}

void
cli_plugin_crash(int sig)
{
	const struct rf_plugin_call *c = rf_plugin_current_call();
	struct line l;

	if (!c)
		return;
	if (atomic_flag_test_and_set(&told))
		for (;;)
			pause();
	l.n = 0;
	put(&l, argv0);
	if (c->mode) {
		put(&l, ": mode '");
		put(&l, c->mode);
		put(&l, "'");
		if (c->file) {
			put(&l, " ('");
			put(&l, c->file);
			put(&l, "')");
		}
		put(&l, " crashed in ");
		put(&l, c->what);
		put(&l, "()");
		if (c->frame) {
			put(&l, " on frame ");
			put_number(&l, c->frame);
			put(&l, c->nrows > 1 ? ", rows " : ", row ");
			put_number(&l, c->row_first + 1);
			if (c->nrows > 1) {
				put(&l, "-");
				put_number(&l, c->row_first + c->nrows);
			}
		}
	} else {
		put(&l, ": plugin '");
		put(&l, c->file);
		put(&l, "' crashed while it was loaded (its constructors or rf_plugin_entry())");
	}
	put(&l, ": ");
	put(&l, signal_text(sig));
	put(&l, "; the mode has a bug: report it to its author with the input that "
	        "makes it crash");
	l.buf[l.n++] = '\n';
	if (write(STDERR_FILENO, l.buf, l.n) < 0) {
		/* nothing left to tell it with */
	}
	die_of(sig);
}

static void
on_crash(int sig, siginfo_t *info, void *context)
{
	size_t i;

	(void)context;
	cli_plugin_crash(sig);
	for (i = 0; i < NSIGNALS && crash_signals[i] != sig; i++)
		;
	if (i == NSIGNALS || ((previous[i].sa_flags & SA_SIGINFO)
	                          ? !previous[i].sa_sigaction
	                          : previous[i].sa_handler == SIG_DFL ||
	                                    previous[i].sa_handler == SIG_IGN))
		die_of(sig);
	/* Whoever handled it before: a fault recurs when this returns, and
	 * reaches it with its own details; a sent signal is sent again. */
	sigaction(sig, &previous[i], NULL);
	if (info->si_code <= 0)
		raise(sig);
}

void
cli_guard_plugins(void)
{
	static int done;
	static char altstack[1 << 16];
	struct sigaction sa;
	stack_t ss;
	size_t i;

	if (done++)
		return;
	memset(&ss, 0, sizeof(ss));
	ss.ss_sp = altstack;
	ss.ss_size = sizeof(altstack);
	/* without it a stack overflow dies unreported, as before */
	(void)sigaltstack(&ss, NULL);
	memset(&sa, 0, sizeof(sa));
	sa.sa_sigaction = on_crash;
	sa.sa_flags = SA_SIGINFO | SA_ONSTACK;
	sigemptyset(&sa.sa_mask);
	for (i = 0; i < NSIGNALS; i++)
		sigaction(crash_signals[i], &sa, &previous[i]);
}
