/* The probe from command-line options or the stream's PROBE_* keys. */
#include <errno.h>
#include <math.h>
#include <string.h>

#include "cli_probe.h"

/* n numbers separated by commas or spaces; 0 on success. */
static int
scan_floats(const char *s, float *out, int n)
{
	char *end;
	int i;

	for (i = 0; i < n; i++) {
		double v;

		while (*s == ' ' || (i && *s == ','))
			s++;
		errno = 0;
		v = strtod(s, &end);
		if (end == s || errno == ERANGE || !isfinite(v))
			return -1;
		out[i] = (float)v;
		s = end;
	}
	while (*s == ' ')
		s++;
	return *s ? -1 : 0;
}

static int
check_box(struct rf_probe *probe, const char *from, char *err, size_t errlen)
{
	int i;

	for (i = 0; i < 3; i++)
		if (!(probe->box_min[i] < probe->box_max[i])) {
			snprintf(err, errlen, "%s: the box is empty on axis %c "
			         "(min %g, max %g)", from, "XYZ"[i],
			         (double)probe->box_min[i], (double)probe->box_max[i]);
			return -1;
		}
	return 0;
}

int
probe_resolve(const struct probe_opts *o, const rf_header *h,
              struct rf_probe *probe, char *err, size_t errlen)
{
	float box[6];
	const char *v;
	int i;

	memset(probe, 0, sizeof(*probe));
	probe->box_projection = 1;
	if (o->box) {
		if (scan_floats(o->box, box, 6) < 0) {
			snprintf(err, errlen, "--box: '%s' needs 6 comma-separated "
			         "numbers XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX", o->box);
			return -1;
		}
	} else if ((v = rf_header_get(h, "PROBE_BOX"))) {
		if (scan_floats(v, box, 6) < 0) {
			snprintf(err, errlen, "header key PROBE_BOX: '%s' needs 6 numbers",
			         v);
			return -1;
		}
	} else {
		snprintf(err, errlen, "no probe box: give --box=XMIN,YMIN,ZMIN,XMAX,"
		         "YMAX,ZMAX or a stream with a PROBE_BOX key");
		return PROBE_MISSING;
	}
	for (i = 0; i < 3; i++) {
		probe->box_min[i] = box[i];
		probe->box_max[i] = box[i + 3];
	}
	if (check_box(probe, o->box ? "--box" : "PROBE_BOX", err, errlen) < 0)
		return -1;
	if (o->center) {
		if (scan_floats(o->center, probe->center, 3) < 0) {
			snprintf(err, errlen, "--center: '%s' needs 3 comma-separated "
			         "numbers X,Y,Z", o->center);
			return -1;
		}
	} else if ((v = rf_header_get(h, "PROBE_CENTER"))) {
		if (scan_floats(v, probe->center, 3) < 0) {
			snprintf(err, errlen, "header key PROBE_CENTER: '%s' needs 3 "
			         "numbers", v);
			return -1;
		}
	} else {
		for (i = 0; i < 3; i++)
			probe->center[i] = 0.5f * (probe->box_min[i] + probe->box_max[i]);
	}
	v = o->projection ? o->projection : rf_header_get(h, "PROBE_BOX_PROJECTION");
	if (v) {
		if (!strcmp(v, "1") || !strcmp(v, "on"))
			probe->box_projection = 1;
		else if (!strcmp(v, "0") || !strcmp(v, "off"))
			probe->box_projection = 0;
		else {
			snprintf(err, errlen, "box projection must be on or off, not '%s'",
			         v);
			return -1;
		}
	}
	return 0;
}

void
probe_to_header(const struct rf_probe *probe, rf_header *h)
{
	char buf[256];

	snprintf(buf, sizeof(buf), "%.9g %.9g %.9g %.9g %.9g %.9g",
	         (double)probe->box_min[0], (double)probe->box_min[1],
	         (double)probe->box_min[2], (double)probe->box_max[0],
	         (double)probe->box_max[1], (double)probe->box_max[2]);
	rf_header_set(h, "PROBE_BOX", buf);
	snprintf(buf, sizeof(buf), "%.9g %.9g %.9g", (double)probe->center[0],
	         (double)probe->center[1], (double)probe->center[2]);
	rf_header_set(h, "PROBE_CENTER", buf);
	rf_header_set(h, "PROBE_BOX_PROJECTION", probe->box_projection ? "1" : "0");
}
