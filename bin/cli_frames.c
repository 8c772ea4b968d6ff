/*
 * The frames a tool renders: a full run of -n N frames with the camera
 * on a path over them, and the part of it this run makes (--frames=A-B,
 * --frame=K).  A part is the full run's frames at those indices, pixel
 * for pixel, because every frame is made from its index and N alone:
 * the camera from rf_camera_at_frame(k, N), FRAME=k in its header (what
 * the animated modes draw their rays from).  So a farm can give each
 * machine a range and concatenate what comes back.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

rf_header *
cli_frame_header(const rf_scene *s, const struct rf_camera *cam, size_t frame,
                 size_t width, size_t height)
{
	rf_header *h;
	int rc;

	if (rf_header_create(&h) < 0 || rf_header_set_size(h, width, height) < 0)
		die_sys("out of memory");
	cli_record_command(h);
	/* A probe's env path may be too long for a header line. */
	if ((rc = rf_scene_frame_keys(s, cam, frame, h)) < 0)
		die_header_key(rc);
	return h;
}

void
cli_frames_init(struct cli_frames *f)
{
	memset(f, 0, sizeof(*f));
	f->count = 1;
	f->path.kind = RF_PATH_NONE;
}

static void
parse_orbit(const char *arg, const char *what, struct rf_camera_path *path)
{
	float deg;

	parse_floats(arg, what, &deg, 1);
	path->kind = RF_PATH_ORBIT;
	path->degrees = deg;
}

static void
parse_path(const char *arg, struct rf_camera_path *path)
{
	if (!strncmp(arg, "orbit:", 6)) {
		parse_orbit(arg + 6, "--path=orbit", path);
	} else if (!strncmp(arg, "line:", 5)) {
		float end[3];

		parse_floats(arg + 5, "--path=line", end, 3);
		path->kind = RF_PATH_LINE;
		path->end[0] = end[0];
		path->end[1] = end[1];
		path->end[2] = end[2];
	} else {
		die("--path: '%s' is neither orbit:DEGREES nor line:X,Y,Z", arg);
	}
}

/* A frame index: digits only, below 10^9 (as -n). */
static int
parse_index(const char *s, char **end, size_t *out)
{
	unsigned long long v;

	if (*s < '0' || *s > '9')
		return -1;
	errno = 0;
	v = strtoull(s, end, 10);
	if (errno || v >= 1000000000ULL)
		return -1;
	*out = (size_t)v;
	return 0;
}

static void
parse_range(struct cli_frames *f, const char *opt, const char *arg)
{
	char *end;

	f->ranged = 1;
	f->option = opt;
	f->range = arg;
	if (parse_index(arg, &end, &f->first) < 0)
		goto bad;
	f->last = f->first;
	if (!strcmp(opt, "--frames")) {
		if (*end != '-' || parse_index(end + 1, &end, &f->last) < 0)
			goto bad;
		if (f->last < f->first)
			die("--frames=%s: the range runs backwards (A-B with A <= B)", arg);
	}
	if (*end == '\0')
		return;
bad:
	die("%s=%s: expected %s", opt, arg,
	    strcmp(opt, "--frames") ? "a frame index, 0 or more" :
	    "a range of frame indices A-B, e.g. 0-15");
}

int
cli_frames_option(struct cli_frames *f, int opt, const char *arg)
{
	switch (opt) {
	case 'n': f->count = parse_count(arg, 'n', 1, 1000000000); break;
	case CLI_OPT_ORBIT: parse_orbit(arg, "--orbit", &f->path); break;
	case CLI_OPT_PATH: parse_path(arg, &f->path); break;
	case CLI_OPT_FRAMES: parse_range(f, "--frames", arg); break;
	case CLI_OPT_FRAME: parse_range(f, "--frame", arg); break;
	default: return 0;
	}
	return 1;
}

void
cli_frames_check(struct cli_frames *f)
{
	if (!f->ranged) {
		f->first = 0;
		f->last = f->count - 1;
		return;
	}
	if (f->last >= f->count)
		die("%s=%s: past the full run's last frame, %zu (-n %zu makes frames "
		    "0-%zu; give -n the full run's count)", f->option, f->range, f->count - 1,
		    f->count, f->count - 1);
}
