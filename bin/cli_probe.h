/* The probe vocabulary shared by the tools: --box, --center, header keys. */
#ifndef REFLECT_CLI_PROBE_H
#define REFLECT_CLI_PROBE_H

#include "cli.h"

struct probe_opts {
	const char *box;    /* --box=XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX */
	const char *center; /* --center=X,Y,Z */
	const char *projection; /* --box-projection=on|off */
};

#define PROBE_MISSING (-2)
/* Fills probe from the options, else from the header's PROBE_* keys.
 * Returns 0, PROBE_MISSING when neither gives a box, or -1 for a value
 * that does not parse; err says which. */
int probe_resolve(const struct probe_opts *o, const rf_header *h,
                  struct rf_probe *probe, char *err, size_t errlen);
/* Writes the probe as PROBE_* keys. */
void probe_to_header(const struct rf_probe *probe, rf_header *h);

#endif
