/*
 * The probe's header keys: PROBE_BOX, PROBE_CENTER, PROBE_BOX_PROJECTION,
 * PROBE_BEVEL and PROBE_BLEND, and PROBE2_*, PROBE3_*, ... for the
 * frame's other probes.  Written and read here only, so that the keys
 * reflect-gbuffer writes and those reflect-shade reads are one word;
 * numbers as %.9g (a float's value exactly, and back to the same float),
 * separated by spaces.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "probe/probe-internal.h"
#include "stream/stream-internal.h"

int
rf__header_set_probe_keys(rf_header *h, size_t index, const double box_min[3],
                          const double box_max[3], const double center[3],
                          int box_projection)
{
	char box_key[64], center_key[64], projection_key[64];
	double box[6];
	int rc, i;

	/* The first probe keeps the plain names that every tool reads. */
	if (index == 0) {
		snprintf(box_key, sizeof(box_key), "%s", RF_KEY_PROBE_BOX);
		snprintf(center_key, sizeof(center_key), "%s", RF_KEY_PROBE_CENTER);
		snprintf(projection_key, sizeof(projection_key), "%s",
		         RF_KEY_PROBE_BOX_PROJECTION);
	} else {
		rf__header_probe_key(box_key, sizeof(box_key), index, RF_KEY_PROBE_BOX);
		rf__header_probe_key(center_key, sizeof(center_key), index, RF_KEY_PROBE_CENTER);
		rf__header_probe_key(projection_key, sizeof(projection_key), index,
		                     RF_KEY_PROBE_BOX_PROJECTION);
	}
	for (i = 0; i < 3; i++) {
		box[i] = box_min[i];
		box[i + 3] = box_max[i];
	}
	if ((rc = rf__header_set_numbers(h, box_key, box, 6)) < 0 ||
	    (rc = rf__header_set_numbers(h, center_key, center, 3)) < 0)
		return rc;
	return rf_header_set(h, projection_key, box_projection ? "1" : "0");
}

int
rf__header_probes_distant(rf_header *h)
{
	char box[64], projection[64];
	size_t i;
	int rc;

	/* the list ends where rf_probe_list_read's does: at a probe without
	 * a box */
	for (i = 0; i < RF_PROBES_MAX; i++) {
		rf__header_probe_key(box, sizeof(box), i, RF_KEY_PROBE_BOX);
		if (!rf_header_get(h, box))
			break;
		rf__header_probe_key(projection, sizeof(projection), i,
		                     RF_KEY_PROBE_BOX_PROJECTION);
		if ((rc = rf_header_set(h, projection, "0")) < 0)
			return rc;
	}
	return 0;
}

void
rf__header_probe_key(char *buf, size_t size, size_t index, const char *key)
{
	/* PROBE_BOX of probe 2 is PROBE2_BOX. */
	if (index == 0 || strncmp(key, "PROBE_", 6))
		snprintf(buf, size, "%s", key);
	else
		snprintf(buf, size, "PROBE%zu_%s", index + 1, key + 6);
}

int
rf_probe_to_header(const struct rf_probe *probe, rf_header *h)
{
	double mn[3], mx[3], c[3];
	int i;

	for (i = 0; i < 3; i++) {
		mn[i] = probe->box_min[i];
		mx[i] = probe->box_max[i];
		c[i] = probe->center[i];
	}
	if ((i = rf__header_set_probe_keys(h, 0, mn, mx, c, probe->box_projection)) < 0 ||
	    (i = rf__probe_shape_write(h, 0, probe)) < 0)
		return i;
	if (probe->bevel > 0.0f) {
		char v[64];

		snprintf(v, sizeof(v), "%.9g%s", (double)probe->bevel,
		         probe->bevel_grown ? " grown" : "");
		return rf_header_set(h, RF_KEY_PROBE_BEVEL, v);
	}
	return rf_header_unset(h, RF_KEY_PROBE_BEVEL);
}


int
rf_probe_resolve(struct rf_probe *probe, const rf_header *h, const char *box_arg,
                 const char *center_arg, const char *projection_arg, char *err,
                 size_t errlen)
{
	float box[6];
	const char *v;
	int i;

	memset(probe, 0, sizeof(*probe));
	probe->box_projection = 1;
	if (box_arg) {
		if (rf__scan_floats(box_arg, box, 6) < 0) {
			rf__format(err, errlen, "--box: '%s' needs 6 comma-separated "
			           "numbers XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX", box_arg);
			return RF_EINVAL;
		}
	} else if ((v = rf_header_get(h, RF_KEY_PROBE_BOX))) {
		if (rf__scan_floats(v, box, 6) < 0) {
			rf__format(err, errlen, "header key %s: '%s' needs 6 numbers",
			           RF_KEY_PROBE_BOX, v);
			return RF_EINVAL;
		}
	} else {
		rf__format(err, errlen, "no probe box: give --box=XMIN,YMIN,ZMIN,XMAX,"
		           "YMAX,ZMAX or a stream with a %s key", RF_KEY_PROBE_BOX);
		return RF_ENOTFOUND;
	}
	for (i = 0; i < 3; i++) {
		probe->box_min[i] = box[i];
		probe->box_max[i] = box[i + 3];
		if (!(probe->box_min[i] < probe->box_max[i])) {
			rf__format(err, errlen, "%s: the box is empty on axis %c (min %g, "
			           "max %g)", box_arg ? "--box" : RF_KEY_PROBE_BOX, "XYZ"[i],
			           (double)probe->box_min[i], (double)probe->box_max[i]);
			return RF_EINVAL;
		}
	}
	if (center_arg) {
		if (rf__scan_floats(center_arg, probe->center, 3) < 0) {
			rf__format(err, errlen, "--center: '%s' needs 3 comma-separated "
			           "numbers X,Y,Z", center_arg);
			return RF_EINVAL;
		}
	} else if ((v = rf_header_get(h, RF_KEY_PROBE_CENTER))) {
		if (rf__scan_floats(v, probe->center, 3) < 0) {
			rf__format(err, errlen, "header key %s: '%s' needs 3 numbers",
			           RF_KEY_PROBE_CENTER, v);
			return RF_EINVAL;
		}
	} else {
		/* Halves first: bounds near FLT_MAX would sum to infinity. */
		for (i = 0; i < 3; i++)
			probe->center[i] = 0.5f * probe->box_min[i] + 0.5f * probe->box_max[i];
	}
	if ((v = rf_header_get(h, RF_KEY_PROBE_BEVEL))) {
		const char *grown = strstr(v, " grown");
		char num[64];

		snprintf(num, sizeof(num), "%.*s", grown ? (int)(grown - v) : (int)strlen(v), v);
		if ((grown && strcmp(grown, " grown")) || rf__scan_floats(num, &probe->bevel, 1) < 0 ||
		    probe->bevel < 0.0f) {
			rf__format(err, errlen, "header key %s: '%s' needs a radius of 0 or "
			           "more, then optionally 'grown'", RF_KEY_PROBE_BEVEL, v);
			return RF_EINVAL;
		}
		probe->bevel_grown = grown != NULL;
		for (i = 0; i < 3; i++)
			if (probe->bevel > 0.5f * (probe->box_max[i] - probe->box_min[i])) {
				rf__format(err, errlen, "header key %s: radius %g is more than "
				           "half the box on axis %c (%g)", RF_KEY_PROBE_BEVEL,
				           (double)probe->bevel, "XYZ"[i],
				           0.5 * ((double)probe->box_max[i] - probe->box_min[i]));
				return RF_EINVAL;
			}
	}
	/* a box given on the command line is that box, whatever the stream's
	 * probe was */
	if (!box_arg && rf__probe_shape_read(h, 0, probe, err, errlen) < 0)
		return RF_EINVAL;
	v = projection_arg ? projection_arg : rf_header_get(h, RF_KEY_PROBE_BOX_PROJECTION);
	if (v) {
		if (!strcmp(v, "1") || !strcmp(v, "on"))
			probe->box_projection = 1;
		else if (!strcmp(v, "0") || !strcmp(v, "off"))
			probe->box_projection = 0;
		else {
			rf__format(err, errlen, "box projection must be on or off, not '%s'", v);
			return RF_EINVAL;
		}
	}
	return 0;
}

int
rf__probe_blend_parse(const char *v, float face[6])
{
	int k;

	if (rf__scan_floats(v, face, 6) < 0) {
		if (rf__scan_floats(v, face, 1) < 0)
			return RF_EINVAL;
		for (k = 1; k < 6; k++)
			face[k] = face[0];
	}
	for (k = 0; k < 6; k++)
		if (!(face[k] >= 0.0f))
			return RF_EINVAL;
	return 0;
}

/* Probe index's keys (PROBE_BOX for 0, PROBE2_BOX for 1...) into *probe
 * and its blend distance; 1 when it has a box, 0 when not, RF_EINVAL for
 * a value that does not parse. */
static int
probe_at(const rf_header *h, size_t index, struct rf_probe *probe, float *blend, char *err,
         size_t errlen)
{
	char key[64];
	float box[6];
	const char *v;
	int i;

	memset(probe, 0, sizeof(*probe));
	probe->box_projection = 1;
	*blend = 0.0f;
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_BOX);
	if (!(v = rf_header_get(h, key)))
		return 0;
	if (rf__scan_floats(v, box, 6) < 0)
		return RF_EINVAL;
	for (i = 0; i < 3; i++) {
		probe->box_min[i] = box[i];
		probe->box_max[i] = box[i + 3];
		if (!(box[i] < box[i + 3]))
			return RF_EINVAL;
		probe->center[i] = 0.5f * box[i] + 0.5f * box[i + 3];
	}
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_CENTER);
	if ((v = rf_header_get(h, key)) && rf__scan_floats(v, probe->center, 3) < 0)
		return RF_EINVAL;
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_BOX_PROJECTION);
	if ((v = rf_header_get(h, key)))
		probe->box_projection = !(!strcmp(v, "0") || !strcmp(v, "off"));
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_BLEND);
	if ((v = rf_header_get(h, key))) {
		float face[6];

		if (rf__probe_blend_parse(v, face) < 0)
			return RF_EINVAL;
		/* one number for the plugins: the widest face's */
		for (i = 0; i < 6; i++)
			*blend = face[i] > *blend ? face[i] : *blend;
	}
	if (rf__probe_shape_read(h, index, probe, err, errlen) < 0)
		return RF_EINVAL;
	return 1;
}

int
rf_probe_list_read(struct rf_probe *probes, float *blend, size_t max, const rf_header *h)
{
	size_t n = 0;
	int rc = 0;

	while (n < max && (rc = probe_at(h, n, &probes[n], &blend[n], NULL, 0)) == 1)
		n++;
	return rc < 0 && n == 0 ? rc : (int)n;
}

int
rf__probe_why_not(const rf_header *h, size_t index, char *err, size_t errlen)
{
	struct rf_probe probe;
	float blend;

	err[0] = '\0';
	return probe_at(h, index, &probe, &blend, err, errlen);
}
