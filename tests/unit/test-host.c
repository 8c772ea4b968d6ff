/* Unit tests of the host services every tool gives its plugins. */
#include "reflect/host.h"
#include "tap.h"

TEST(table_follows_the_settings)
{
	rf_plugin_host *h;
	const struct rf_host *t;
	struct rf_probe probe = { { 1, 2, 3 }, { -1, -2, -3 }, { 4, 5, 6 }, 0 };
	rf_header *frame;
	rf_cubemap *c;
	float dir[3] = { 0.3f, -0.2f, 0.9f }, got[3], want[3];

	ASSERT_EQ(rf_header_create(&frame), 0);
	ASSERT_EQ(rf_header_set(frame, "SCENE", "room"), 0);
	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	t = rf_plugin_host_table(h);
	ASSERT_EQ(t->size, sizeof(struct rf_host));
	ASSERT_EQ(t->abi_major, RF_PLUGIN_ABI_MAJOR);
	ASSERT_EQ(t->abi_minor, RF_PLUGIN_ABI_MINOR);
	/* Nothing set: keys absent, no probe, no sampling. */
	ASSERT(t->header_get(t->ctx, "SCENE") == NULL);
	ASSERT(t->probe == NULL);
	ASSERT(t->sample == NULL && t->roughness_to_lod == NULL &&
	       t->lod_to_roughness == NULL);
	ASSERT(t->lod_steps == 0.0f && t->seed == 0);

	rf_plugin_host_set_frame(h, frame);
	ASSERT_STR_EQ(t->header_get(t->ctx, "SCENE"), "room");
	ASSERT(t->header_get(t->ctx, "CAMERA") == NULL);
	/* The probe is a copy: the caller's may go. */
	rf_plugin_host_set_probe(h, &probe);
	probe.center[0] = 99;
	ASSERT(t->probe && t->probe->center[0] == 1 && t->probe->box_max[2] == 6 &&
	       t->probe->box_projection == 0);
	rf_plugin_host_set_probe(h, NULL);
	ASSERT(t->probe == NULL);

	/* Sampling is rf_cubemap_sample, the mapping rf_roughness_to_lod. */
	ASSERT_EQ(rf_cubemap_create(&c, 8, 4), 0);
	rf_default_environment_cube(c);
	rf_cubemap_box_chain(c, 1);
	rf_plugin_host_set_environment(h, c, RF_MAPPING_EXACT, 3);
	rf_plugin_host_set_seed(h, 7);
	ASSERT(t->sample && t->roughness_to_lod && t->lod_to_roughness);
	ASSERT(t->lod_steps == 3.0f && t->seed == 7);
	t->sample(t->ctx, dir, 1.25f, got);
	rf_cubemap_sample(c, dir, 1.25f, want);
	ASSERT(!memcmp(got, want, sizeof(got)));
	ASSERT(t->roughness_to_lod(t->ctx, 0.4f) ==
	       rf_roughness_to_lod(RF_MAPPING_EXACT, 3, 0.4f));
	ASSERT(t->lod_to_roughness(t->ctx, 2.0f) ==
	       rf_lod_to_roughness(RF_MAPPING_EXACT, 3, 2.0f));
	rf_plugin_host_set_environment(h, NULL, RF_MAPPING_EXACT, 3);
	ASSERT(t->sample == NULL && t->lod_steps == 0.0f);

	rf_plugin_host_destroy(h);
	rf_cubemap_destroy(c);
	rf_header_destroy(frame);
}

int
main(void)
{
	RUN(table_follows_the_settings);
	TAP_DONE();
}
