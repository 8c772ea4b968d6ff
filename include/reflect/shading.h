/*
 * libreflect: shading with a prefiltered environment.
 *
 * The pass that turns each pixel's effective roughness into a lod of the
 * environment's one mapping and samples the chain there, and the shader
 * that builds reflect-shade(1)'s frames around it from one description.
 * The roughness models themselves are plugins (RF_KIND_SHADE); the
 * split-sum environment BRDF (the DFG table) is in reflect/surface.h,
 * included here.
 */
#ifndef REFLECT_SHADING_H
#define REFLECT_SHADING_H

#include "reflect/reflect.h"
#include "reflect/envmap.h"
#include "reflect/plugin.h"
#include "reflect/probe.h"
#include "reflect/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- blending probes ------------------------------------------------- */

/* Where what no probe covers comes from: the first probe's environment
 * along R, without parallax; nothing, the probes' weights scaled to 1
 * where any covers a pixel; or a sky, an environment of its own along R. */
enum rf_blend_fallback {
	RF_BLEND_INFINITE = 0,
	RF_BLEND_NONE = 1,
	RF_BLEND_SKY = 2
};

/* ---- the sampling pass of reflect-shade -------------------------------- */

/* RF_SHADE_ROUGHNESS, the channel a shade mode writes, is in plugin.h. */

/*
 * A pass over a stream that already has RF_SHADE_ROUGHNESS and the
 * lookup direction D.X D.Y D.Z (or, with mode_radiance, spec.R spec.G
 * spec.B a mode computed itself): for every pixel it samples the
 * environment at D with lod = rf_roughness_to_lod(mapping, steps,
 * roughness.eff) and writes spec.R spec.G spec.B.  Pixels whose `mask`
 * is 0 (walls) get the environment seen directly instead: lod 0 in the
 * direction from the probe centre to P (a fractional mask blends the
 * two).  With `final` it also writes R G B = spec (F0 A + B), F0 =
 * lerp(0.04, albedo, metallic); a stream without metallic or albedo is a
 * white metal (the missing one counts as 1).  Every other channel is
 * kept; channels of the same names are overwritten.  Rows are spread
 * over threads; the bytes do not depend on their number.  The pass alone
 * shades rows that have these channels; rf_shader (below) builds it with
 * the mode's stage, the probes and their environments, as reflect-shade
 * does.
 */
/* What reflect-shade(1) asks of its environment: --mapping, --steps,
 * --samples for a prefilter on the fly, --prefiltered (as_given). */
struct rf_shade_env_options {
	int mapping_set;         /* 1: `mapping` was asked for */
	enum rf_mapping mapping;
	float steps;             /* 0: the chain's, or its last level */
	unsigned samples;        /* GGX samples when prefiltering; 0: default */
	int as_given;            /* a chain's levels with the options' mapping
	                            and steps, whatever it says it was made with */
	int raw_ok;              /* a raw environment is sampled as it is (a
	                            mode tracing its own rays reads level 0) */
	int nthreads;
	/* Called with done 0 as the prefilter starts, then as levels are
	 * done; may be NULL. */
	void (*progress)(void *arg, double done, double total);
	void *progress_arg;
	/* Where prefiltered raw environments are kept between runs (NULL:
	 * nowhere), under a hash of the texels and the prefilter's
	 * parameters, at most cache_bytes (0: 256 MB), oldest out first. */
	const char *cache_dir;
	size_t cache_bytes;
	/* Called with a line when an entry of the cache is found damaged
	 * (cut short, a NaN, texels that do not match its checksum, not this
	 * environment's), before it is made again; may be NULL. */
	void (*note)(void *arg, const char *msg);
	void *note_arg;
};
/* Takes what rf_envmap_load gave (loaded, info; named `name` in
 * messages, NULL for the embedded room) and makes the chain a shading
 * pass samples: *env is loaded itself when it is a GGX chain, whose
 * mapping and steps must agree with the options unless as_given; else a
 * chain prefiltered from loaded's level 0 with the options' mapping
 * and steps (with raw_ok, loaded as it is, steps 0).  Either way loaded
 * is the callee's (destroyed on failure or
 * when a new chain replaces it). */
RF_EXTERN int rf_shade_environment(rf_cubemap **env, enum rf_mapping *mapping,
                                   float *steps, rf_cubemap *loaded,
                                   const struct rf_chain_info *info, const char *name,
                                   const struct rf_shade_env_options *o, char *err,
                                   size_t errlen);

typedef struct rf_shade rf_shade;

/* The final colour's BRDF term (reflect-shade --final=...). */
enum rf_final {
	RF_FINAL_NONE = 0,     /* no R G B */
	RF_FINAL_SPLIT_SUM = 1, /* spec (F0 A + B) */
	RF_FINAL_UNITY = 2,    /* Unity Standard's surface reduction and grazing term */
	RF_FINAL_HDRP = 3      /* HDRP's FGD with multiple-scattering compensation */
};
/* "split-sum", "unity" or "hdrp"; RF_EINVAL for anything else. */
RF_EXTERN int rf_final_parse(const char *name, enum rf_final *final);

struct rf_shade_options {
	int final;    /* also R G B: an enum rf_final (1, any true value of
	                 before, is the split sum) */
	int nthreads; /* < 1 means 1 */
	/* 1: the mode wrote spec.R spec.G spec.B itself (a Monte-Carlo mode
	 * sampling through the host's services): reflective pixels keep
	 * them, and only walls and the final colour are done here. */
	int mode_radiance;
	/* 1: every mirror read at lod (the write-up's debug view of mips),
	 * whatever the mode's roughness; a mode writing radiance is not
	 * affected. */
	int force_lod;
	float lod;
	/* With final: 1 adds the diffuse light of the environment's
	 * irradiance (9 spherical harmonics of its level 0), albedo (1 -
	 * metallic) E(N) / pi, to R G B and writes it as diffuse.R G B;
	 * box (with diffuse) reads E along N box-projected from P, as the
	 * specular lookup is. */
	int diffuse;
	int diffuse_box;
};

RF_EXTERN int rf_shade_create(rf_shade **s, const struct rf_shade_options *o);
/* The diffuse light's coefficients as a chain file kept them (after
 * rf_shade_set_environment, which projects level 0 itself otherwise). */
RF_EXTERN void rf_shade_set_irradiance(rf_shade *s, const float sh9[27]);
/* The probe box the diffuse light's box projection uses, for the frames
 * that follow (NULL: none, the irradiance at N itself). */
struct rf_probe;
RF_EXTERN void rf_shade_set_probe(rf_shade *s, const struct rf_probe *probe);
RF_EXTERN void rf_shade_destroy(rf_shade *s);
/* Checks the channels of a frame and makes its output header (valid
 * until the next call).  center: the probe's capture point, or NULL when
 * there is none (then a stream with a mask channel is refused).  err
 * names a missing channel. */
RF_EXTERN int rf_shade_begin_frame(rf_shade *s, const rf_header *in,
                                   const float center[3], rf_header **out,
                                   char *err, size_t errlen);
/* The i-th channel the pass writes (spec.R spec.G spec.B, then R G B
 * with final), in the order it appends them; NULL past the last. */
RF_EXTERN const char *rf_shade_channel(const rf_shade *s, size_t i);
/* The environment every following rf_shade_run samples; the cube stays
 * the caller's, and must outlive the pass or the next call. */
RF_EXTERN int rf_shade_set_environment(rf_shade *s, const rf_cubemap *env,
                                        enum rf_mapping mapping, float steps);
/* nrows rows of the frame: in with the input header's channels, out with
 * the output header's.  When the input header has every output channel
 * already (see rf_stage_reserve_channel) in may be out: the rows are
 * shaded in place. */
RF_EXTERN int rf_shade_run(rf_shade *s, const float *in, float *out, size_t nrows);
/* Invalid input (rf_invalid in reflect.h) in what the pass reads itself:
 * mask (in [0, 1]); D where the mirror shows and P where the wall does
 * (finite); emission.R G B where they show (finite, not negative); with
 * final the material where the mirror shows (roughness, metallic and
 * albedo in [0, 1], N and V directions); with mode_radiance the spec the
 * mode wrote (finite, not negative).  Under RF_INVALID_ERROR (the
 * default) the run returns RF_EINVAL with the first such pixel in
 * rf_shade_error (rf_shader_error puts its stage's first); under CLAMP
 * each is clamped (NaN to 0, a radiance's +inf to the largest float),
 * under ZERO the pixel's outputs are 0; under both a D or P that is not
 * finite reads black.  Radiance that adds up past the float range is written
 * as the largest float: the outputs are always finite. */
RF_EXTERN void rf_shade_set_invalid(rf_shade *s, enum rf_invalid policy);
RF_EXTERN const char *rf_shade_error(const rf_shade *s);
/* Pixels of the frame whose input the pass clamped or zeroed (a pixel
 * the mode's stage repaired too is counted by each). */
RF_EXTERN size_t rf_shade_invalid_count(const rf_shade *s);

/* ---- a frame shaded as reflect-shade shades it ------------------------ */

/*
 * The whole of reflect-shade(1) over a stream: the shade mode's stage and
 * the sampling pass, and what they need, built here from a description
 * of the shading (struct rf_shader_options) and each frame's header: the
 * frame's probe (rf_probe_resolve), its environment (the options' env,
 * else the frame's PROBE_ENV, else the embedded room) and, for blending,
 * its other probes' (PROBEk_ENV) and the sky's, each loaded, prefiltered
 * as rf_shade_environment makes it and kept across frames while they
 * name the same; a plugin host for every probe, and for a mode that
 * traces its own rays a stage for every probe, their rows laid out as
 * the pass's.  For each frame: rf_shader_begin_frame, rf_shader_run over
 * its rows in blocks (any order, any size), rf_shader_end_frame.
 */
typedef struct rf_shader rf_shader;

/* Loads the environment `name` (a path, or "default": the embedded
 * room) as rf_envmap_load does, with o as it takes them (o->from_header:
 * the name came from a stream's header); the chain's info into *info.
 * 0, or an error with its message in err. */
typedef int rf_shader_load_fn(void *arg, rf_cubemap **c, struct rf_chain_info *info,
                              const char *name, const struct rf_envmap_options *o,
                              char *err, size_t errlen);

struct rf_shader_options {
	/* The shade mode (RF_KIND_SHADE) and its parameters
	 * (rf_plugin_parse_params); both must outlive the shader.  spec is
	 * what the output's SHADE key says (NULL: the mode's name). */
	const struct rf_plugin *mode;
	const double *values;
	const char *spec;
	int nthreads;  /* for the stages and the pass; < 1 means 1 */
	uint32_t seed; /* for modes that draw samples */
	/* Invalid input, in the stages and the pass (rf_shade_set_invalid). */
	enum rf_invalid invalid;

	/* The probe, as rf_probe_resolve takes it: --box, --center and
	 * --box-projection as given (NULL: the frame's keys).  A frame
	 * without a box has no probe; center (three comma-separated numbers)
	 * still places the capture point its walls are seen from. */
	const char *box, *center, *projection;

	/* The environment: env for every frame (NULL: each frame's
	 * PROBE_ENV, else the embedded room), loaded with envmap (its
	 * prefiltered flag also takes a chain as given: as_given of
	 * rf_shade_env_options) by load (NULL: rf_envmap_load, NaN texels
	 * replaced as envmap says counted in a note), then sampled with
	 * mapping (mapping_set), steps and samples as in
	 * rf_shade_env_options, prefiltered chains kept in cache_dir (NULL:
	 * nowhere), at most cache_bytes (0: 256 MB). */
	const char *env;
	struct rf_envmap_options envmap;
	rf_shader_load_fn *load;
	void *load_arg;
	int mapping_set;
	enum rf_mapping mapping;
	float steps;
	unsigned samples;
	const char *cache_dir;
	size_t cache_bytes;

	/* The pass (rf_shade_options): final, an enum rf_final; with it
	 * diffuse (1, the default) and diffuse_box; force_lod and lod. */
	int final;
	int diffuse, diffuse_box;
	int force_lod;
	float lod;

	/* Blending the frame's probes (1, the default; 0 shades with the
	 * first alone): at most max_probes (2) a pixel, with normal_fade,
	 * what none covers from fallback, the sky's environment named by sky
	 * (loaded by rf_shader_create, so that one that cannot be read is
	 * refused at once). */
	int blend;
	unsigned max_probes;
	int normal_fade;
	enum rf_blend_fallback fallback;
	const char *sky;

	/* Called with each frame's output header before the shader sets its
	 * keys (SHADE, ENV_MAPPING, ENV_STEPS, with env PROBE_ENV, the
	 * probe's), e.g. to record the command (rf_header_add_command); an
	 * error returned fails rf_shader_begin_frame with it.  May be NULL. */
	int (*header)(void *arg, rf_header *out);
	void *header_arg;
	/* A prefilter's progress: done 0 as it starts (a cached chain
	 * never does), with line saying what it prefilters ("prefiltering
	 * the environment 'x' (64x64 per face, 7 levels)", NULL when not
	 * worth one), then as levels are done.  May be NULL. */
	void (*progress)(void *arg, const char *line, double done, double total);
	void *progress_arg;
	/* A line worth telling that is no error: a damaged cache entry made
	 * again, NaN texels replaced, and with verbose which environment
	 * each probe reads and how.  May be NULL. */
	void (*note)(void *arg, const char *msg);
	void *note_arg;
	int verbose;
};

/* Defaults: everything 0 or NULL but blend 1, max_probes 2, diffuse 1,
 * envmap as rf_envmap_options_init makes it. */
RF_EXTERN void rf_shader_options_init(struct rf_shader_options *o);
/* A shader for frames of o->mode.  With fallback RF_BLEND_SKY the sky is
 * loaded (and prefiltered) here: err says why it cannot be. */
RF_EXTERN int rf_shader_create(rf_shader **s, const struct rf_shader_options *o,
                               char *err, size_t errlen);
RF_EXTERN void rf_shader_destroy(rf_shader *s);
/* Takes the next frame's header: checks that the mode and the pass find
 * their channels (before any environment is loaded, so that a stream
 * that cannot be shaded fails at once), loads what the frame's probes
 * need, and makes the output header, valid until the next call.  err
 * names the missing channel, the key that does not parse, the
 * environment that cannot be loaded. */
RF_EXTERN int rf_shader_begin_frame(rf_shader *s, const rf_header *in, rf_header **out,
                                    char *err, size_t errlen);
/* Rows y..y+nrows of the frame, in (the input header's channels) to out
 * (the output header's): each row through the mode's stage, then
 * shaded while it is in cache.  RF_EINVAL with rf_shader_error for a
 * pixel that breaks a rule (see rf_shade_set_invalid and
 * rf_stage_run), RF_EPLUGIN with it when the mode gave up. */
RF_EXTERN int rf_shader_run(rf_shader *s, const float *in, float *out, size_t y,
                            size_t nrows);
/* The frame's first refusal (the mode's stage's, else the pass's), ""
 * when there was none. */
RF_EXTERN const char *rf_shader_error(const rf_shader *s);
/* Pixels of the frame whose input the stage or the pass clamped or
 * zeroed (one both repaired counted by each), and those whose outputs
 * of the mode were (rf_stage_invalid_output_count). */
RF_EXTERN size_t rf_shader_invalid_count(const rf_shader *s);
RF_EXTERN size_t rf_shader_invalid_output_count(const rf_shader *s);
/* Lets the frame's stages and hosts go (rf_shader_begin_frame and
 * rf_shader_destroy do too). */
RF_EXTERN void rf_shader_end_frame(rf_shader *s);

#ifdef __cplusplus
}
#endif

#endif
