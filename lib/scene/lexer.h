/* Internal to the scene area: the scene format's tokens. */
#ifndef REFLECT_SCENE_LEXER_H
#define REFLECT_SCENE_LEXER_H

#include <stddef.h>

#include "util/util.h"

struct rf__token {
	const char *text; /* not terminated; owned by `owned` when quoted */
	size_t len;
	size_t line, col;
	char *owned;
};

struct rf__lexer {
	const char *src;
	size_t len, pos, line, col;
	const char *name; /* for messages */
	char *err;
	size_t errlen;
	/* the statement read last */
	struct rf__token *tok;
	size_t ntok, cap;
	size_t end_line, end_col; /* just past its last token */
};

void rf__lexer_init(struct rf__lexer *lx, const char *src, size_t len, const char *name,
                    char *err, size_t errlen);
/* Reads the next statement's tokens: 1, 0 at the end of the text, or an
 * error with "name:line:col: message" in err. */
int rf__lexer_next(struct rf__lexer *lx);
/* RF_EFORMAT, with "name:line:col: message" in err. */
int rf__lexer_fail(const struct rf__lexer *lx, size_t line, size_t col, const char *fmt,
                   ...) RF__PRINTF(4, 5);
void rf__lexer_destroy(struct rf__lexer *lx);

#endif
