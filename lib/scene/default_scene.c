/* The embedded default scene.  It is written in the scene format itself
 * and parsed at run time, so that it is also the format's worked example
 * (reflect-gbuffer --print-default-scene prints it). */
#include "scene/scene-internal.h"

static const char default_scene[] =
	"# reflect's default scene: the test room of the write-up \"Improved Box\n"
	"# Projected Reflections\".  Units are metres and degrees; +Y is up.\n"
	"name default\n"
	"\n"
	"# The probe's box is also the room, drawn with its walls facing in.\n"
	"# The capture point and the box are those of the worked test vectors\n"
	"# (tests/t0402-shade-vectors.sh).  The environment is reflect's own: the\n"
	"# same room seen from the capture point.\n"
	"probe center 0 1.5 0 box -3 0 -2 3 3 2 env default blend 1 projection on\n"
	"\n"
	"# What the room's walls emit: each wall's colour in a checker of 0.5 m\n"
	"# cells with bright grid lines, and two HDR windows with mullions.  The\n"
	"# embedded environment is this room seen from the capture point, so\n"
	"# reflect-capture of this scene with its reflective objects hidden gives\n"
	"# it back.  Window corners are in each wall's (u, v): (z, y) on the x\n"
	"# walls, (x, y) on the z walls.\n"
	"pattern cell 0.5 line-width 0.05 base 0.42 checker 0.18 line 3 line-white 1\n"
	"wall +x pattern 0.8 0.25 0.2\n"
	"wall -x pattern 0.2 0.65 0.25\n"
	"wall +y pattern 0.85 0.85 0.8\n"
	"wall -y pattern 0.45 0.35 0.28\n"
	"wall +z pattern 0.2 0.3 0.85\n"
	"wall -z pattern 0.85 0.75 0.2\n"
	"window +x min -1.2 1 max 0.2 2.3 radiance 18 15.5 12 mullions 0.06 0.05 0.05 0.05\n"
	"window -z min -1.8 1.1 max -0.4 2.5 radiance 10 11.5 14 mullions 0.06 0.05 0.05 0.05\n"
	"\n"
	"# Eye height, from a front corner across the room, so that the floor\n"
	"# mirror shows the spheres, the pillars and the far walls.\n"
	"camera position -2.6 1.6 1.8 target 0.9 0.45 -1 up 0 1 0 fov 55\n"
	"\n"
	"# A mirror 1 cm above the floor: glossy, so that contact hardening\n"
	"# shows where the spheres and pillars meet it.\n"
	"rect plane y 0.01 min -2.9 -1.9 max 2.9 1.9 roughness 0.2\n"
	"\n"
	"# Spheres from smooth to rough, resting 1.5 cm above the mirror.\n"
	"sphere center -2 0.325 -0.5 radius 0.3 roughness 0.05\n"
	"sphere center -1 0.325 -0.5 radius 0.3 roughness 0.25\n"
	"sphere center  0 0.325 -0.5 radius 0.3 roughness 0.45\n"
	"sphere center  1 0.325 -0.5 radius 0.3 roughness 0.7\n"
	"sphere center  2 0.325 -0.5 radius 0.3 roughness 0.9\n"
	"\n"
	"# Pillars, floor to ceiling: what a box projection cannot know about.\n"
	"# Painted (not metal), one tiled, one bumpy.\n"
	"box min -1.7 0 -1.6 max -1.3 3 -1.2 roughness 0.6 metallic 0 albedo 0.8 0.8 0.8\n"
	"box min  1.3 0 -1.6 max  1.7 3 -1.2 roughness 0.4 metallic 0 albedo 0.8 0.8 0.8 \\\n"
	"    normalmap tiles scale 0.2 strength 0.5\n"
	"box min  2.2 0  0.6 max  2.6 3  1.0 roughness 0.5 metallic 0 albedo 0.8 0.8 0.8 \\\n"
	"    normalmap bumps scale 0.1 strength 0.3\n";

const char *
rf_scene_default_text(void)
{
	return default_scene;
}

int
rf_scene_default(rf_scene **s, char *err, size_t errlen)
{
	return rf_scene_parse(s, default_scene, sizeof(default_scene) - 1, "<default>",
	                      err, errlen);
}
