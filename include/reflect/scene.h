/*
 * Scenes and G-buffers: a room (the probe box seen from inside), objects
 * with materials and normal maps, a camera, read from the text format of
 * reflect-scene(5), and the G-buffer ray cast from them.
 *
 * Same rules as reflect.h: 0 or a count on success, a negative rf_status
 * on failure with the reason in the caller's buffer; nothing prints.
 * Geometry is in double precision, in metres; the G-buffer is float.
 */
#ifndef REFLECT_SCENE_H
#define REFLECT_SCENE_H

#include "reflect/reflect.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rf_scene rf_scene;

/* A pinhole camera.  The ray through image point (px, py), pixels counted
 * from the top left corner (pixel centres at i + 0.5), is
 *   normalize(f + x tan(fov/2) (W/H) right + y tan(fov/2) up')
 * with x = 2 px/W - 1, y = 1 - 2 py/H, f = normalize(target - position),
 * right = normalize(cross(f, up)), up' = cross(right, f). */
struct rf_camera {
	double position[3];
	double target[3];
	double up[3];
	double fov; /* vertical field of view in degrees, in (0, 180) */
};

struct rf_scene_probe {
	double center[3];           /* capture point, inside the box */
	double box_min[3], box_max[3];
	double blend;               /* blend distance in metres (the widest face's) */
	double face_blend[6];       /* per face, +X -X +Y -Y +Z -Z */
	int per_face;               /* the scene gave six */
	double importance;          /* blending order: higher first (0) */
	int box_projection;         /* 1 on, 0 off */
	const char *env;            /* environment file (relative paths resolved
	                               against the scene file's directory), or
	                               NULL for the embedded default */
	/* Its shapes, as struct rf_probe has them (RF_SHAPE_*): the
	 * influence a box (turned about its centre by rotation, row-major,
	 * when rotated) or the sphere inscribed in the box; the proxy the
	 * influence (RF_SHAPE_SAME), a box or sphere of its own, or
	 * infinite. */
	int shape;
	int rotated;
	double rotation[9];
	int proxy_shape;
	int proxy_rotated;
	double proxy_min[3], proxy_max[3];
	double proxy_rotation[9];
};

/* Parses a scene.  `name` is the file name used in messages
 * ("name:line:column: expected ...") and, when it contains '/', the base
 * of relative paths in the scene.  Normal map images are loaded here. */
RF_EXTERN int rf_scene_parse(rf_scene **s, const char *text, size_t len,
                             const char *name, char *err, size_t errlen);
/* The same from an open file, read to its end. */
RF_EXTERN int rf_scene_read(rf_scene **s, FILE *fp, const char *name, char *err,
                            size_t errlen);
/* The embedded default scene, as text in the format, and parsed. */
RF_EXTERN const char *rf_scene_default_text(void);
RF_EXTERN int rf_scene_default(rf_scene **s, char *err, size_t errlen);
RF_EXTERN void rf_scene_destroy(rf_scene *s);

RF_EXTERN const char *rf_scene_name(const rf_scene *s);
RF_EXTERN void rf_scene_camera(const rf_scene *s, struct rf_camera *cam);
RF_EXTERN size_t rf_scene_nprobes(const rf_scene *s);
/* NULL past the end.  Probe 0 is the room. */
RF_EXTERN const struct rf_scene_probe *rf_scene_probe(const rf_scene *s, size_t i);
/* The keys of frame `frame` seen by cam: SCENE, CAMERA, each probe's
 * PROBE_BOX, PROBE_CENTER, PROBE_BOX_PROJECTION, PROBE_ENV and
 * PROBE_BLEND (the second probe's as PROBE2_BOX...), and FRAME. */
RF_EXTERN int rf_scene_frame_keys(const rf_scene *s, const struct rf_camera *cam,
                                  size_t frame, rf_header *h);
RF_EXTERN size_t rf_scene_nobjects(const rf_scene *s);

/* Object ids, as in the objid channel: objects count from 1 in the order
 * of the file, then the meshes in theirs (nobjects + 1 for the first);
 * the room's walls are negative; 0 is nothing. */
enum {
	RF_OBJID_NONE = 0,
	RF_WALL_XMAX = -1, /* the wall at x = xmax (its normal is -X) */
	RF_WALL_XMIN = -2,
	RF_WALL_YMAX = -3, /* the ceiling */
	RF_WALL_YMIN = -4, /* the floor */
	RF_WALL_ZMAX = -5,
	RF_WALL_ZMIN = -6
};

/* "sphere", "box", "rect", "mesh" (a mesh statement's triangles), "wall"
 * or NULL, and the line the object was declared on (0 when unknown). */
RF_EXTERN const char *rf_scene_object_kind(const rf_scene *s, int objid);
RF_EXTERN size_t rf_scene_object_line(const rf_scene *s, int objid);
/* The id of the first object that holds p strictly inside, or 0. */
RF_EXTERN int rf_scene_inside(const rf_scene *s, const double p[3]);
/* 1 when p lies inside the room (the first probe's box), border included. */
RF_EXTERN int rf_scene_in_room(const rf_scene *s, const double p[3]);

/* What a ray sees.  N and Ng face the ray's origin (back faces are
 * flipped, as a path tracer shades them).  When nothing is hit: t = +inf,
 * objid 0, mask 0, P = origin + 1e30 dir (finite, far outside any box),
 * N = Ng = -dir. */
struct rf_hit {
	double t; /* distance along the unit ray */
	double P[3], N[3], Ng[3];
	float roughness, metallic, albedo[3], mask;
	int objid;
	/* The surface tangent: the direction its texture's u grows in (a
	 * normal map's), made perpendicular to N; unit length. */
	double T[3];
	/* A mesh's hit: its triangle (in the mesh's order) and the
	 * barycentric coordinates of P for the triangle's second and third
	 * vertices; 0 for any other hit. */
	unsigned int prim;
	double bary[2];
};

/* dir must be a unit vector.  Returns the hit's objid. */
RF_EXTERN int rf_scene_trace(const rf_scene *s, const double origin[3],
                             const double dir[3], struct rf_hit *hit);

/* RF_EINVAL with a reason when the camera cannot make an image. */
RF_EXTERN int rf_camera_check(const struct rf_camera *cam, char *err, size_t errlen);
/* The unit ray through image point (px, py) of a width x height image. */
RF_EXTERN void rf_camera_ray(const struct rf_camera *cam, size_t width,
                             size_t height, double px, double py, double dir[3]);

/* Camera paths for animated sequences. */
enum rf_camera_path_kind {
	RF_PATH_NONE = 0,
	RF_PATH_ORBIT = 1, /* about the vertical axis through the target:
	                      frame k of n at degrees * k / n, so 360 loops */
	RF_PATH_LINE = 2   /* position and target move together in a straight
	                      line, frame k of n at k / (n - 1): the last frame
	                      ends at `end` */
};

struct rf_camera_path {
	enum rf_camera_path_kind kind;
	double degrees; /* orbit */
	double end[3];  /* line: the last frame's position */
};

RF_EXTERN void rf_camera_at_frame(const struct rf_camera *start,
                                  const struct rf_camera_path *path, size_t frame,
                                  size_t nframes, struct rf_camera *out);

/*
 * The G-buffer.  Channels, in this order when all are asked for:
 *   P.X P.Y P.Z N.X N.Y N.Z Ng.X Ng.Y Ng.Z V.X V.Y V.Z roughness metallic
 *   albedo.R albedo.G albedo.B mask objid depth
 * V is the unit vector from P to the camera, depth the distance from the
 * camera to P (+inf when nothing is hit).  No value is ever NaN.
 */
#define RF_GBUFFER_CHANNELS                                                  \
	"P.X P.Y P.Z N.X N.Y N.Z Ng.X Ng.Y Ng.Z V.X V.Y V.Z roughness "     \
	"metallic albedo.R albedo.G albedo.B mask objid depth"

typedef struct rf_gbuffer rf_gbuffer;

/* channels: names separated by spaces or commas, where P, N, Ng, V,
 * albedo, T and emission stand for their three components; NULL for all
 * (emission.R G B included when the scene emits, T never).  Rows are spread
 * over nthreads threads; the bytes never depend on it.  The scene must
 * outlive the G-buffer. */
RF_EXTERN int rf_gbuffer_create(rf_gbuffer **g, const rf_scene *s, size_t width,
                                size_t height, const char *channels, int nthreads,
                                char *err, size_t errlen);
RF_EXTERN void rf_gbuffer_destroy(rf_gbuffer *g);
RF_EXTERN size_t rf_gbuffer_nchannels(const rf_gbuffer *g);
RF_EXTERN const char *rf_gbuffer_channel(const rf_gbuffer *g, size_t i);
/* Sets the camera of the next rows (the scene's camera until then). */
RF_EXTERN int rf_gbuffer_set_camera(rf_gbuffer *g, const struct rf_camera *cam,
                                    char *err, size_t errlen);
/* Renders rows y .. y + nrows - 1 into out (width * nchannels floats a
 * row; after rf_gbuffer_set_columns, ncols * nchannels). */
RF_EXTERN int rf_gbuffer_render(rf_gbuffer *g, float *out, size_t y, size_t nrows);
/* Renders only columns x0 .. x0 + ncols - 1 of the rows from now on (a
 * tile): each pixel as the whole frame's, its ray through the same
 * point.  RF_EINVAL for no column or one past the width. */
RF_EXTERN int rf_gbuffer_set_columns(rf_gbuffer *g, size_t x0, size_t ncols);

/*
 * Baking a probe (reflect-capture(1)): the scene from probe `probe`'s
 * capture point as a cube of size x size texels a face, each texel the
 * mean over its footprint: one ray where what it sees is constant,
 * edge_samples^2 where it crosses an edge of the emission,
 * object_samples^2 where it may see an object.  Objects are lit by the
 * probe from the bounce before (bounces 0: black but for their own
 * emission and direct light; earlier bounces at bounce_size texels a
 * face); with hide_reflective, objects whose mask is set are left out.  The same
 * bytes at any thread count.
 */
struct rf_capture_options {
	size_t size;             /* texels a face (256) */
	int bounces;             /* 1 */
	int hide_reflective;     /* 0 */
	unsigned edge_samples;   /* 16 */
	unsigned object_samples; /* 4 */
	size_t bounce_size;      /* 128 */
	int nthreads;            /* 1 */
	/* How far the capture is (NULL: not told), called from the calling
	 * thread: rows of cube faces done of the total over every bounce,
	 * first with 0 done, then after each face. */
	void (*progress)(void *arg, size_t rows_done, size_t rows_total);
	void *progress_arg;
};
struct rf_cubemap;
RF_EXTERN void rf_capture_options_init(struct rf_capture_options *o);
/* A one-level cube in *cube; RF_EINVAL for a probe the scene lacks or
 * options out of range (err says which). */
RF_EXTERN int rf_scene_capture(const rf_scene *s, size_t probe,
                               const struct rf_capture_options *o,
                               struct rf_cubemap **cube, char *err, size_t errlen);

/*
 * The ground truth (reflect-trace(1)): the camera's pixel-centre rays,
 * and on reflective surfaces the one-bounce integral of a white (F = 1)
 * GGX lobe against what the scene sends out (emission, and the lights'
 * direct light on what is not reflective), over `samples` samples of the
 * visible normals a pixel; channels R G B mask objid, and with halves
 * half1.R G B and half2.R G B, the even and the odd samples' estimates.
 * Reflected rays pass through reflective objects unless objects_visible.
 * The same bytes at any thread count.
 */
struct rf_trace_options {
	unsigned samples;       /* 1024 */
	int masking_correlated; /* 0: separable Smith G1(V) G1(L), as Cycles 3.4 */
	int objects_visible;    /* 0: reflected rays see the room alone */
	int halves;
	uint32_t seed;
	int nthreads;
	/* A sample range: the pixel's samples are first .. first + samples - 1
	 * of the total a whole run traces (0: samples), sample s the point
	 * s / 2 of half s mod 2, so that runs of a split, merged by their
	 * SAMPLES, are the whole run. */
	unsigned first, total;
};
typedef struct rf_tracer rf_tracer;

RF_EXTERN void rf_trace_options_init(struct rf_trace_options *o);
RF_EXTERN int rf_tracer_create(rf_tracer **t, const rf_scene *s, size_t width,
                               size_t height, const struct rf_trace_options *o,
                               char *err, size_t errlen);
RF_EXTERN void rf_tracer_destroy(rf_tracer *t);
RF_EXTERN size_t rf_tracer_nchannels(const rf_tracer *t);
RF_EXTERN const char *rf_tracer_channel(const rf_tracer *t, size_t i);
RF_EXTERN int rf_tracer_set_camera(rf_tracer *t, const struct rf_camera *cam);
/* Rows y .. y + nrows - 1 into out (width * nchannels floats a row;
 * after rf_tracer_set_columns, ncols * nchannels). */
RF_EXTERN int rf_tracer_render(rf_tracer *t, float *out, size_t y, size_t nrows);
/* Only columns x0 .. x0 + ncols - 1 of the rows from now on (a tile),
 * each pixel as the whole frame's, its samples and seed the same.
 * RF_EINVAL for no column or one past the width. */
RF_EXTERN int rf_tracer_set_columns(rf_tracer *t, size_t x0, size_t ncols);

#ifdef __cplusplus
}
#endif

#endif
