/* Unit tests of the chain a shading pass samples (rf_shade_environment). */
#include "reflect/shading.h"
#include "tap.h"

static rf_cubemap *
room(size_t size, size_t levels)
{
	rf_cubemap *c;

	if (rf_cubemap_create(&c, size, levels) < 0)
		return NULL;
	rf_default_environment_cube(c);
	if (levels > 1)
		rf_cubemap_box_chain(c, 1);
	return c;
}

TEST(raw_is_prefiltered_with_the_options)
{
	struct rf_shade_env_options o = { 0 };
	struct rf_chain_info info = { 0 };
	rf_cubemap *env, *raw = room(16, 1), *ref;
	struct rf_prefilter_options pf;
	enum rf_mapping m;
	float steps, a[3], b[3], dir[3] = { 0.2f, 0.5f, -0.8f };
	char err[256];

	ASSERT(raw);
	o.mapping_set = 1;
	o.mapping = RF_MAPPING_EXACT;
	o.samples = 32;
	ASSERT_EQ(rf_shade_environment(&env, &m, &steps, raw, &info, "raw.exr", &o, err,
	                               sizeof(err)), 0);
	/* 16 halves to 1: five levels, steps 4, the mapping asked for. */
	ASSERT_EQ(rf_cubemap_levels(env), 5);
	ASSERT(steps == 4.0f);
	ASSERT_EQ(m, RF_MAPPING_EXACT);
	/* The bytes of rf_prefilter with the same options. */
	raw = room(16, 1);
	ASSERT_EQ(rf_cubemap_create(&ref, 16, 5), 0);
	rf_prefilter_defaults(&pf);
	pf.mapping = RF_MAPPING_EXACT;
	pf.steps = 4;
	pf.samples = 32;
	ASSERT_EQ(rf_prefilter(raw, ref, &pf, err, sizeof(err)), 0);
	rf_cubemap_sample(env, dir, 2.5f, a);
	rf_cubemap_sample(ref, dir, 2.5f, b);
	ASSERT(!memcmp(a, b, sizeof(a)));
	rf_cubemap_destroy(env);
	rf_cubemap_destroy(ref);
	rf_cubemap_destroy(raw);
	/* One texel a face cannot make levels. */
	info.prefiltered = 0;
	ASSERT_EQ(rf_shade_environment(&env, &m, &steps, room(1, 1), &info, "tiny.exr", &o,
	                               err, sizeof(err)), RF_EINVAL);
	ASSERT(strstr(err, "the environment 'tiny.exr' is 1 texels a face"));
	ASSERT(env == NULL);
}

TEST(chain_keeps_its_mapping_unless_told)
{
	struct rf_shade_env_options o = { 0 };
	struct rf_chain_info info = { 1, RF_MAPPING_UNITY, 3.0f, 64, 1 };
	rf_cubemap *chain = room(8, 4), *env;
	enum rf_mapping m;
	float steps;
	char err[256];

	/* No options: the chain as it is, its mapping and steps. */
	ASSERT_EQ(rf_shade_environment(&env, &m, &steps, chain, &info, "c.rfl", &o, err,
	                               sizeof(err)), 0);
	ASSERT(env == chain);
	ASSERT_EQ(m, RF_MAPPING_UNITY);
	ASSERT(steps == 3.0f);
	/* Another mapping would pick the wrong levels: refused... */
	o.mapping_set = 1;
	o.mapping = RF_MAPPING_LINEAR;
	ASSERT_EQ(rf_shade_environment(&env, &m, &steps, chain, &info, "c.rfl", &o, err,
	                               sizeof(err)), RF_EINVAL);
	ASSERT(strstr(err, "'c.rfl' was prefiltered with mapping unity and steps 3"));
	/* ...unless the options describe the chain. */
	chain = room(8, 4);
	o.as_given = 1;
	o.steps = 2.5f;
	ASSERT_EQ(rf_shade_environment(&env, &m, &steps, chain, &info, "c.rfl", &o, err,
	                               sizeof(err)), 0);
	ASSERT_EQ(m, RF_MAPPING_LINEAR);
	ASSERT(steps == 2.5f);
	rf_cubemap_destroy(env);
}

int
main(void)
{
	RUN(raw_is_prefiltered_with_the_options);
	RUN(chain_keeps_its_mapping_unless_told);
	TAP_DONE();
}
