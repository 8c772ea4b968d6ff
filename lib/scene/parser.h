/* Internal to the scene area: the scene format's parser state and the
 * helpers that statements parsed outside parse.c share with it. */
#ifndef REFLECT_SCENE_PARSER_H
#define REFLECT_SCENE_PARSER_H

#include "scene/lexer.h"
#include "scene/scene-internal.h"

#define ATTRS_MAX 64

struct parser {
	struct rf__lexer lx; /* and the statement's tokens */
	const char *name; /* for messages */
	char *dir;        /* base of relative paths, or NULL */
	rf_scene *s;
	size_t pos; /* the statement's next token */
	/* attribute names seen in it, for duplicates */
	const struct rf__token *attrs[ATTRS_MAX];
	size_t nattrs;
	size_t camera_line, name_line, room_line, pattern_line;
	/* where the first probe says 'sphere': refused once the file says
	 * the room is drawn */
	size_t room_sphere_line, room_sphere_col;
	size_t wall_line[RF__FACES];
	/* the probes that name no env: see envless_probes() */
	struct envless {
		size_t probe, line, col;
	} *envless;
	size_t nenvless;
};

#define fail_at(p, ...) rf__lexer_fail(&(p)->lx, __VA_ARGS__)
#define FAIL_TOK(p, t, ...) fail_at((p), (t)->line, (t)->col, __VA_ARGS__)
#define FAIL_END(p, ...) fail_at((p), (p)->lx.end_line, (p)->lx.end_col, __VA_ARGS__)

/* The token shown in a message, cut to a sensible length. */
#define TOKFMT "'%.*s%s'"
#define TOKARG(t) (int)((t)->len > 40 ? 40 : (t)->len), (t)->text, (t)->len > 40 ? "..." : ""

/* parse.c's helpers: each reads the statement's next tokens, or fails
 * with "name:line:col: message" (RF_EFORMAT) naming what was expected. */
int rf__tok_is(const struct rf__token *t, const char *word);
int rf__parse_number(struct parser *p, const char *what, double *v);
int rf__parse_numbers(struct parser *p, const char *what, double *v, int n);
int rf__parse_word(struct parser *p, const char *what, const struct rf__token **t);
/* A copy of a path, relative ones taken from the scene file's directory. */
int rf__parse_path(struct parser *p, const struct rf__token *t, char **out);
/* The next attribute name (1), the end of the statement (0); one given
 * twice is an error. */
int rf__parse_attribute(struct parser *p, const struct rf__token **key);
/* 1 when key is a material attribute (its value read into m), 0 when not. */
int rf__parse_material_attribute(struct parser *p, const struct rf__token *key,
                                 struct material *m);
int rf__parse_unknown_attribute(struct parser *p, const struct rf__token *key,
                                const char *what, const char *expected);

/* parse_mesh.c: the mesh statement, after its keyword kw. */
int rf__parse_mesh(struct parser *p, const struct rf__token *kw);
/* parse_shape.c: a probe's shape attributes (rotate, matrix, sphere,
 * proxy, proxy_rotate, proxy_matrix): 1 when key is one (its values read
 * into pr; a sphere's radius into *radius), 0 when not. */
int rf__parse_probe_shape(struct parser *p, const struct rf__token *key,
                          struct rf_scene_probe *pr, double *radius);
/* After the statement: the sphere's box from its radius, the proxy
 * sphere's around the capture point, the capture point inside the
 * influence; index is the probe's (0: the room's). */
int rf__probe_shape_finish(struct parser *p, const struct rf__token *kw,
                           struct rf_scene_probe *pr, double radius, size_t index);
/* sky.c: the sky statement, after its keyword kw. */
int rf__parse_sky(struct parser *p, const struct rf__token *kw);

#endif
