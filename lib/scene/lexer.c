/*
 * The scene format's words (reflect-scene(5)): statements of one line,
 * '#' comments, '\' at the end of a line to continue it, "double quotes"
 * around words with spaces (\" and \\ inside them).  The parser sees
 * a statement as a list of tokens, each with its line and column.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/lexer.h"

void
rf__lexer_init(struct rf__lexer *lx, const char *src, size_t len, const char *name,
               char *err, size_t errlen)
{
	memset(lx, 0, sizeof(*lx));
	lx->src = src;
	lx->len = len;
	lx->line = 1;
	lx->col = 1;
	lx->name = name;
	lx->err = err;
	lx->errlen = errlen;
}

int
rf__lexer_fail(const struct rf__lexer *lx, size_t line, size_t col, const char *fmt, ...)
{
	char msg[512];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(msg, sizeof(msg), fmt, ap);
	va_end(ap);
	rf__format(lx->err, lx->errlen, "%s:%zu:%zu: %s", lx->name, line, col, msg);
	return RF_EFORMAT;
}

static int
lx_peek(const struct rf__lexer *lx, size_t ahead)
{
	return lx->pos + ahead < lx->len ? (unsigned char)lx->src[lx->pos + ahead] : -1;
}

static void
lx_advance(struct rf__lexer *lx)
{
	if (lx->src[lx->pos] == '\n') {
		lx->line++;
		lx->col = 1;
	} else {
		lx->col++;
	}
	lx->pos++;
}

static void
free_tokens(struct rf__lexer *lx)
{
	size_t i;

	for (i = 0; i < lx->ntok; i++)
		free(lx->tok[i].owned);
	lx->ntok = 0;
}

static int
push_token(struct rf__lexer *lx, const struct rf__token *t)
{
	if (lx->ntok == lx->cap) {
		size_t cap = lx->cap ? 2 * lx->cap : 32;
		struct rf__token *tok = realloc(lx->tok, cap * sizeof(*tok));

		if (!tok)
			return RF_ENOMEM;
		lx->tok = tok;
		lx->cap = cap;
	}
	lx->tok[lx->ntok++] = *t;
	return 0;
}

/* A "quoted word": \" and \\ stand for themselves. */
static int
lex_quoted(struct rf__lexer *lx, struct rf__token *t)
{
	size_t n = 0, end;
	char *buf;
	int c;

	/* The word's own length, not the rest of the file: a scene of many
	 * short quoted words would otherwise allocate the file again for
	 * each.  Escapes only shorten it. */
	for (end = lx->pos + 1; end < lx->len && lx->src[end] != '"' && lx->src[end] != '\n';
	     end++)
		if (lx->src[end] == '\\' && end + 1 < lx->len &&
		    (lx->src[end + 1] == '"' || lx->src[end + 1] == '\\'))
			end++;
	if (!(buf = malloc(end - lx->pos + 1)))
		return RF_ENOMEM;
	lx_advance(lx);
	while ((c = lx_peek(lx, 0)) != '"') {
		if (c == -1 || c == '\n') {
			free(buf);
			return rf__lexer_fail(lx, lx->line, lx->col, "expected a closing '\"' for "
			               "the word opened at column %zu", t->col);
		}
		if (c == '\\' && (lx_peek(lx, 1) == '"' || lx_peek(lx, 1) == '\\')) {
			lx_advance(lx);
			c = lx_peek(lx, 0);
		}
		buf[n++] = (char)c;
		lx_advance(lx);
	}
	lx_advance(lx);
	t->owned = buf;
	t->text = buf;
	t->len = n;
	return 0;
}

int
rf__lexer_next(struct rf__lexer *lx)
{
	int c, rc;

	free_tokens(lx);
	for (;;) {
		struct rf__token t = { 0 };

		c = lx_peek(lx, 0);
		if (c == -1 || (c == '\n' && lx->ntok)) {
			if (c == '\n')
				lx_advance(lx);
			return lx->ntok ? 1 : 0;
		}
		if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
			lx_advance(lx);
			continue;
		}
		if (c == '#') {
			while ((c = lx_peek(lx, 0)) != -1 && c != '\n')
				lx_advance(lx);
			continue;
		}
		if (c == '\\') {
			size_t k = 1;

			while (lx_peek(lx, k) == ' ' || lx_peek(lx, k) == '\t' ||
			       lx_peek(lx, k) == '\r')
				k++;
			if (lx_peek(lx, k) == '\n' || lx_peek(lx, k) == -1) {
				while (k-- > 0)
					lx_advance(lx);
				if (lx_peek(lx, 0) == '\n')
					lx_advance(lx); /* the statement goes on */
				continue;
			}
		}
		if (c == 0)
			return rf__lexer_fail(lx, lx->line, lx->col, "expected text, found a NUL "
			               "byte");
		t.line = lx->line;
		t.col = lx->col;
		if (c == '"') {
			if ((rc = lex_quoted(lx, &t)) < 0)
				return rc;
		} else {
			t.text = lx->src + lx->pos;
			while ((c = lx_peek(lx, 0)) != -1 && c != ' ' && c != '\t' &&
			       c != '\r' && c != '\n' && c != '#' && c != 0 && c != '"')
				lx_advance(lx);
			t.len = (size_t)(lx->src + lx->pos - t.text);
		}
		if ((rc = push_token(lx, &t)) < 0) {
			free(t.owned);
			return rc;
		}
		lx->end_line = lx->line;
		lx->end_col = lx->col;
	}
}

void
rf__lexer_destroy(struct rf__lexer *lx)
{
	free_tokens(lx);
	free(lx->tok);
	lx->tok = NULL;
	lx->cap = 0;
}
