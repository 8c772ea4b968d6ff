/* The scene model: accessors, cameras and camera paths, shared images. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/envmap.h"
#include "scene/accel.h"
#include "probe/probe-internal.h"
#include "stream/stream-internal.h"

static const double pi = 3.14159265358979323846;

rf_scene *
rf__scene_create(void)
{
	rf_scene *s = calloc(1, sizeof(*s));

	if (!s)
		return NULL;
	if (pthread_mutex_init(&s->accel_lock, NULL)) {
		free(s);
		return NULL;
	}
	s->room = 1;
	rf__material_default(&s->room_mat, 1);
	rf__pattern_default(&s->pattern);
	return s;
}

void
rf__material_default(struct material *m, int room)
{
	memset(m, 0, sizeof(*m));
	/* Objects default to the write-up's preview material, a white metal;
	 * the room is a rough, non-reflective emitter. */
	m->roughness = room ? 1.0f : 0.5f;
	m->metallic = room ? 0.0f : 1.0f;
	m->albedo[0] = m->albedo[1] = m->albedo[2] = 1.0f;
	m->mask = room ? 0.0f : 1.0f;
	m->nm.kind = NM_NONE;
	m->nm.strength = 1.0;
	m->nm.inv_scale = 1.0;
	m->nm.tiling[0] = m->nm.tiling[1] = 1.0;
}

void
rf_scene_destroy(rf_scene *s)
{
	size_t i;

	if (!s)
		return;
	rf__accel_destroy(s->accel);
	rf_cubemap_destroy(s->sky);
	pthread_mutex_destroy(&s->accel_lock);
	for (i = 0; i < s->nprobes; i++)
		free((char *)s->probes[i].env);
	for (i = 0; i < s->nimages; i++) {
		rf_image_destroy(s->images[i]);
		free(s->image_paths[i]);
	}
	free(s->images);
	free(s->image_paths);
	for (i = 0; i < s->nmeshes; i++)
		rf__mesh_free(&s->meshes[i]);
	free(s->meshes);
	free(s->lights);
	for (i = 0; i < s->nblocks; i++)
		free(s->blocks[i]);
	free(s->blocks);
	free(s->probes);
	free(s->windows);
	free(s->objects);
	free(s->name);
	free(s);
}

int
rf__scene_image(rf_scene *s, const char *path, size_t min_channels, const char *what,
                const rf_image **imgp, char *err, size_t errlen)
{
	rf_image *img;
	int rc;

	if ((*imgp = rf__scene_image_find(s, path)))
		return 0;
	if ((rc = rf_image_read(&img, path, err, errlen)) < 0)
		return rc;
	if (rf_image_nchannels(img) < min_channels) {
		rf__format(err, errlen, "%s '%s' has %zu channel%s, expected at least %zu",
		           what, path, rf_image_nchannels(img),
		           rf_image_nchannels(img) == 1 ? "" : "s", min_channels);
		rf_image_destroy(img);
		return RF_EIMAGE;
	}
	if ((rc = rf__scene_image_add(s, path, img)) < 0)
		return rc;
	*imgp = img;
	return 0;
}

int
rf__scene_image_add(rf_scene *s, const char *key, rf_image *img)
{
	rf_image **images;
	char **paths, *copy;

	images = realloc(s->images, (s->nimages + 1) * sizeof(*images));
	if (images)
		s->images = images;
	paths = realloc(s->image_paths, (s->nimages + 1) * sizeof(*paths));
	if (paths)
		s->image_paths = paths;
	if (!images || !paths || !(copy = strdup(key))) {
		rf_image_destroy(img);
		return RF_ENOMEM;
	}
	s->images[s->nimages] = img;
	s->image_paths[s->nimages++] = copy;
	return 0;
}

const rf_image *
rf__scene_image_find(const rf_scene *s, const char *key)
{
	size_t i;

	for (i = 0; i < s->nimages; i++)
		if (!strcmp(s->image_paths[i], key))
			return s->images[i];
	return NULL;
}

int
rf__scene_keep(rf_scene *s, void *block)
{
	void **blocks = realloc(s->blocks, (s->nblocks + 1) * sizeof(*blocks));

	if (!blocks) {
		free(block);
		return RF_ENOMEM;
	}
	s->blocks = blocks;
	s->blocks[s->nblocks++] = block;
	return 0;
}

/* Whether the n values from v are all finite; the first that is not. */
static int
all_finite(const float *v, size_t n, size_t *bad)
{
	size_t i;

	for (i = 0; i < n; i++)
		if (!isfinite(v[i])) {
			*bad = i;
			return 0;
		}
	return 1;
}

static int
check_mesh(const struct rf__mesh *m, char *err, size_t errlen)
{
	const char *path = m->path ? m->path : "(mesh)";
	static const char *const what[] = { "position", "normal", "tangent",
	                                    "texture coordinate", "texture coordinate" };
	const float *arrays[5];
	const size_t per[5] = { 3, 3, 4, 2, 2 };
	size_t i, bad;

	if (!m->ntriangles || !m->nvertices || !m->positions || !m->indices) {
		rf__format(err, errlen, "'%s' has no triangles", path);
		return RF_EINVAL;
	}
	if (!m->normals || !m->tangents) {
		rf__format(err, errlen, "'%s' has no %s", path,
		           m->normals ? "tangents" : "normals");
		return RF_EINVAL;
	}
	/* Embree numbers vertices and triangles in 32 bits. */
	if (m->nvertices > UINT32_MAX || m->ntriangles > UINT32_MAX / 3) {
		rf__format(err, errlen, "'%s' has %zu vertices and %zu triangles, "
		           "expected at most %u of each", path, m->nvertices,
		           m->ntriangles, (unsigned)(UINT32_MAX / 3));
		return RF_ETOOBIG;
	}
	arrays[0] = m->positions;
	arrays[1] = m->normals;
	arrays[2] = m->tangents;
	arrays[3] = m->uv[0];
	arrays[4] = m->uv[1];
	for (i = 0; i < 5; i++)
		if (arrays[i] && !all_finite(arrays[i], per[i] * m->nvertices, &bad)) {
			rf__format(err, errlen, "'%s': vertex %zu's %s is not a "
			           "finite number (NaN or infinity): fix the file", path,
			           bad / per[i], what[i]);
			return RF_EINVAL;
		}
	for (i = 0; i < 3 * m->ntriangles; i++)
		if (m->indices[i] >= m->nvertices) {
			rf__format(err, errlen, "'%s': triangle %zu names vertex %u, "
			           "expected below %zu", path, i / 3, m->indices[i],
			           m->nvertices);
			return RF_EINVAL;
		}
	for (i = 0; m->material && i < m->ntriangles; i++)
		if (m->material[i] >= m->nmaterials) {
			rf__format(err, errlen, "'%s': triangle %zu has material %u, "
			           "expected below %zu", path, i, m->material[i],
			           m->nmaterials);
			return RF_EINVAL;
		}
	if (!m->material && m->nmaterials < 1) {
		rf__format(err, errlen, "'%s' has no material", path);
		return RF_EINVAL;
	}
	return 0;
}

int
rf__scene_add_mesh(rf_scene *s, struct rf__mesh *m, char *err, size_t errlen)
{
	struct rf__mesh *meshes;
	float *padded;
	size_t i;
	int rc, j;

	if ((rc = check_mesh(m, err, errlen)) < 0)
		goto fail;
	/* Embree reads a vertex as four floats: one more after the last. */
	if (!(padded = realloc(m->positions, (3 * m->nvertices + 1) * sizeof(*padded)))) {
		rc = RF_ENOMEM;
		goto fail;
	}
	m->positions = padded;
	padded[3 * m->nvertices] = 0.0f;
	if (!(meshes = realloc(s->meshes, (s->nmeshes + 1) * sizeof(*meshes)))) {
		rc = RF_ENOMEM;
		goto fail;
	}
	s->meshes = meshes;
	for (j = 0; j < 3; j++) {
		m->bounds[j] = INFINITY;
		m->bounds[j + 3] = -INFINITY;
	}
	for (i = 0; i < m->nvertices; i++)
		for (j = 0; j < 3; j++) {
			const float v = m->positions[3 * i + j];

			m->bounds[j] = v < m->bounds[j] ? v : m->bounds[j];
			m->bounds[j + 3] = v > m->bounds[j + 3] ? v : m->bounds[j + 3];
		}
	/* A new mesh after a traced ray: the structure is built again. */
	rf__accel_destroy(s->accel);
	s->accel = NULL;
	for (i = 0; i < m->nmaterials; i++)
		for (j = 0; j < 3; j++)
			s->has_emission |= m->materials[i].emission[j] > 0.0f;
	s->meshes[s->nmeshes++] = *m;
	memset(m, 0, sizeof(*m));
	return 0;
fail:
	if (rc == RF_ENOMEM)
		rf__format(err, errlen, "%s", rf_strerror(rc));
	rf__mesh_free(m);
	memset(m, 0, sizeof(*m));
	return rc;
}

void
rf__object_prepare(struct object *o)
{
	int i;

	switch (o->kind) {
	case OBJ_SPHERE:
		o->radius2 = o->radius * o->radius;
		o->inv_radius = 1.0 / o->radius;
		for (i = 0; i < 3; i++) {
			o->min[i] = o->center[i] - o->radius;
			o->max[i] = o->center[i] + o->radius;
		}
		break;
	case OBJ_BOX:
		for (i = 0; i < 3; i++)
			o->center[i] = 0.5 * (o->min[i] + o->max[i]);
		break;
	case OBJ_RECT:
		rf__cross(o->n, o->t, o->b);
		for (i = 0; i < 3; i++) {
			double e = fabs(o->t[i]) * o->half[0] + fabs(o->b[i]) * o->half[1];

			o->min[i] = o->center[i] - e;
			o->max[i] = o->center[i] + e;
		}
		break;
	}
}

const char *
rf_scene_name(const rf_scene *s)
{
	return s->name ? s->name : "scene";
}

void
rf_scene_camera(const rf_scene *s, struct rf_camera *cam)
{
	*cam = s->camera;
}

size_t
rf_scene_nprobes(const rf_scene *s)
{
	return s->nprobes;
}

const struct rf_scene_probe *
rf_scene_probe(const rf_scene *s, size_t i)
{
	return i < s->nprobes ? &s->probes[i] : NULL;
}

size_t
rf_scene_nobjects(const rf_scene *s)
{
	return s->nobjects;
}

const char *
rf_scene_object_kind(const rf_scene *s, int objid)
{
	static const char *const kinds[] = { "sphere", "box", "rect" };

	if (objid > 0 && (size_t)objid <= s->nobjects)
		return kinds[s->objects[objid - 1].kind];
	if (objid > 0 && (size_t)objid <= s->nobjects + s->nmeshes)
		return "mesh";
	if (objid < 0 && objid >= RF_WALL_ZMIN && s->room && s->nprobes)
		return "wall";
	return NULL;
}

size_t
rf_scene_object_line(const rf_scene *s, int objid)
{
	if (objid > 0 && (size_t)objid <= s->nobjects)
		return s->objects[objid - 1].line;
	if (objid > 0 && (size_t)objid <= s->nobjects + s->nmeshes)
		return s->meshes[objid - 1 - s->nobjects].line;
	return 0;
}

int
rf_scene_inside(const rf_scene *s, const double p[3])
{
	size_t i;
	int k;

	for (i = 0; i < s->nobjects; i++) {
		const struct object *o = &s->objects[i];
		double d[3];

		switch (o->kind) {
		case OBJ_SPHERE:
			for (k = 0; k < 3; k++)
				d[k] = p[k] - o->center[k];
			if (rf__dot(d, d) < o->radius2)
				return (int)i + 1;
			break;
		case OBJ_BOX:
			for (k = 0; k < 3; k++)
				if (!(p[k] > o->min[k] && p[k] < o->max[k]))
					break;
			if (k == 3)
				return (int)i + 1;
			break;
		case OBJ_RECT:
			break; /* no volume */
		}
	}
	return 0;
}

void
rf__room_frame(rf_scene *s)
{
	const struct rf_scene_probe *r = s->nprobes ? &s->probes[0] : NULL;
	int k;

	s->room_turned = r && r->rotated;
	for (k = 0; k < 9; k++)
		s->room_rotation[k] = s->room_turned ? r->rotation[k] : k % 4 == 0;
	for (k = 0; k < 3; k++)
		s->room_center[k] = r ? 0.5 * (r->box_min[k] + r->box_max[k]) : 0.0;
}

int
rf_scene_in_room(const rf_scene *s, const double p[3])
{
	const struct rf_scene_probe *r = s->nprobes ? &s->probes[0] : NULL;
	double q[3];
	int k;

	if (!r)
		return 0;
	if (s->room_turned)
		rf__room_point_in(s, p, q);
	else
		for (k = 0; k < 3; k++)
			q[k] = p[k];
	for (k = 0; k < 3; k++)
		if (!(q[k] >= r->box_min[k] && q[k] <= r->box_max[k]))
			return 0;
	return 1;
}

int
rf_scene_trace(const rf_scene *s, const double origin[3], const double dir[3],
               struct rf_hit *hit)
{
	return rf__trace(s, origin, NULL, dir, NULL, 0, hit);
}

/* The camera's frame: forward, right and true up, all unit. */
static int
camera_frame(const struct rf_camera *c, double f[3], double r[3], double u[3])
{
	int i;

	for (i = 0; i < 3; i++)
		f[i] = c->target[i] - c->position[i];
	if (!(rf__normalize(f) > 0))
		return -1;
	rf__cross(f, c->up, r);
	if (!(rf__normalize(r) > 1e-9))
		return -2;
	rf__cross(r, f, u);
	return 0;
}

int
rf_camera_check(const struct rf_camera *c, char *err, size_t errlen)
{
	double f[3], r[3], u[3];
	int i, rc;

	for (i = 0; i < 3; i++)
		if (!isfinite(c->position[i]) || !isfinite(c->target[i]) ||
		    !isfinite(c->up[i])) {
			rf__format(err, errlen, "camera: expected finite numbers");
			return RF_EINVAL;
		}
	if (!(c->fov > 0 && c->fov < 180)) {
		rf__format(err, errlen, "camera: expected a field of view in (0, 180) "
		           "degrees, found %g", c->fov);
		return RF_EINVAL;
	}
	if ((rc = camera_frame(c, f, r, u)) == -1) {
		rf__format(err, errlen, "camera: expected a target apart from the "
		           "position");
		return RF_EINVAL;
	}
	if (rc == -2) {
		rf__format(err, errlen, "camera: expected an up vector not parallel to "
		           "the view direction");
		return RF_EINVAL;
	}
	return 0;
}

void
rf__camera_basis(const struct rf_camera *c, size_t width, size_t height,
                 struct camera_basis *cb)
{
	camera_frame(c, cb->f, cb->r, cb->u);
	cb->ty = tan(c->fov * (pi / 360.0));
	cb->tx = cb->ty * ((double)width / (double)height);
}

void
rf_camera_ray(const struct rf_camera *c, size_t width, size_t height, double px,
              double py, double dir[3])
{
	struct camera_basis cb;

	rf__camera_basis(c, width, height, &cb);
	rf__camera_dir(&cb, 2.0 * px / (double)width - 1.0,
	               1.0 - 2.0 * py / (double)height, dir);
}

void
rf_camera_at_frame(const struct rf_camera *start, const struct rf_camera_path *path,
                   size_t frame, size_t nframes, struct rf_camera *out)
{
	double a, ca, sa, dx, dz, s;
	int i;

	*out = *start;
	if (!path || nframes == 0)
		return;
	switch (path->kind) {
	case RF_PATH_NONE:
		break;
	case RF_PATH_ORBIT:
		/* Counter-clockwise seen from above (right-handed about +Y). */
		a = path->degrees * (pi / 180.0) * (double)frame / (double)nframes;
		if (a == 0)
			break; /* frame 0 is the scene's camera, to the bit */
		ca = cos(a);
		sa = sin(a);
		dx = start->position[0] - start->target[0];
		dz = start->position[2] - start->target[2];
		out->position[0] = start->target[0] + ca * dx + sa * dz;
		out->position[2] = start->target[2] - sa * dx + ca * dz;
		break;
	case RF_PATH_LINE:
		s = nframes > 1 ? (double)frame / (double)(nframes - 1) : 0.0;
		for (i = 0; i < 3; i++) {
			double step = s * (path->end[i] - start->position[i]);

			out->position[i] = start->position[i] + step;
			out->target[i] = start->target[i] + step;
		}
		break;
	}
}

int
rf_scene_frame_keys(const rf_scene *s, const struct rf_camera *cam, size_t frame,
                    rf_header *h)
{
	char key[64], buf[32];
	double camera[10];
	size_t i;
	int rc;

	for (i = 0; i < 3; i++) {
		camera[i] = cam->position[i];
		camera[i + 3] = cam->target[i];
		camera[i + 6] = cam->up[i];
	}
	camera[9] = cam->fov;
	if ((rc = rf_header_set(h, RF_KEY_SCENE, rf_scene_name(s))) < 0 ||
	    (rc = rf__header_set_numbers(h, RF_KEY_CAMERA, camera, 10)) < 0)
		return rc;
	for (i = 0; i < s->nprobes; i++) {
		const struct rf_scene_probe *p = &s->probes[i];

		struct rf_probe shape;

		rf__scene_probe_shape(p, &shape);
		if ((rc = rf__header_set_probe_keys(h, i, p->box_min, p->box_max, p->center,
		                                    p->box_projection)) < 0 ||
		    (rc = rf__probe_shape_write(h, i, &shape)) < 0)
			return rc;
		rf__header_probe_key(key, sizeof(key), i, RF_KEY_PROBE_ENV);
		if ((rc = rf_header_set(h, key, p->env ? p->env : "default")) < 0)
			return rc;
		rf__header_probe_key(key, sizeof(key), i, RF_KEY_PROBE_BLEND);
		if ((rc = rf__header_set_numbers(h, key, p->per_face ? p->face_blend : &p->blend,
		                                 p->per_face ? 6 : 1)) < 0)
			return rc;
		rf__header_probe_key(key, sizeof(key), i, RF_KEY_PROBE_IMPORTANCE);
		if (p->importance != 0.0 &&
		    (rc = rf__header_set_numbers(h, key, &p->importance, 1)) < 0)
			return rc;
	}
	snprintf(buf, sizeof(buf), "%zu", frame);
	return rf_header_set(h, RF_KEY_FRAME, buf);
}

void
rf__scene_probe_shape(const struct rf_scene_probe *sp, struct rf_probe *out)
{
	int i;

	memset(out, 0, sizeof(*out));
	for (i = 0; i < 3; i++) {
		out->center[i] = (float)sp->center[i];
		out->box_min[i] = (float)sp->box_min[i];
		out->box_max[i] = (float)sp->box_max[i];
		out->proxy_min[i] = (float)sp->proxy_min[i];
		out->proxy_max[i] = (float)sp->proxy_max[i];
	}
	out->box_projection = sp->box_projection;
	out->shape = sp->shape == RF_SHAPE_SPHERE ? RF_SHAPE_SPHERE : RF_SHAPE_BOX;
	out->rotated = sp->rotated != 0;
	out->proxy_shape = (uint32_t)sp->proxy_shape;
	out->proxy_rotated = sp->proxy_rotated != 0;
	for (i = 0; i < 9; i++) {
		out->rotation[i] = (float)sp->rotation[i];
		out->proxy_rotation[i] = (float)sp->proxy_rotation[i];
	}
}
