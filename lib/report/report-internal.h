/* Internal to lib/report: a report's contents, measured (report.c) and
 * written as a page (page.c). */
#ifndef REFLECT_REPORT_INTERNAL_H
#define REFLECT_REPORT_INTERNAL_H

#include "reflect/report.h"

/* The exposures linear pictures are shown at, in stops from the
 * pictures' own values: whole stops, as the viewer steps through them
 * (report.c says why these are images and not floats); -4 to +3 unless
 * rf_report_stops chooses others, at most RF__REPORT_NSTOPS of them
 * from RF_REPORT_STOP_LIMIT down or up. */
#define RF__REPORT_STOP_MIN (-4)
#define RF__REPORT_STOP_MAX 3
#define RF__REPORT_NSTOPS 16

/* A picture as the page holds it: PNG files in base64, one an exposure
 * (display pictures: the first alone). */
struct rf__report_picture {
	char *name, *path, *caption;
	char *shots[RF__REPORT_NSTOPS];
	char *heat;                 /* the FLIP map (modes only) */
	struct rf_report_errors e;  /* modes only */
};

struct rf_report {
	rf_picture *truth;
	int col[3];                 /* the truth's colour: R G B, else spec.* */
	size_t width, height;
	int srgb;                   /* display pictures: one exposure, LDR-FLIP */
	int stop_lo, nstops;        /* linear pictures' exposures: stop_lo, stop_lo + 1... */
	double ppd, start, stop;    /* FLIP's viewing, HDR-FLIP's exposures */
	int nexposures;
	struct rf__report_picture *pics; /* 0: the truth, then the modes */
	size_t npics, cap;
};

/* The page (page.c); the caller checks fp for a failed write. */
void rf__report_page(const rf_report *r, FILE *fp, const char *title);

#endif
