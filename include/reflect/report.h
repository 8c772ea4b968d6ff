/*
 * libreflect: a report of modes against the truth, as reflect-report(1)
 * writes it: one HTML page that holds everything it shows (the pictures
 * as PNG data, its script and style), with each mode's errors (relative
 * RMSE, PSNR, FLIP), a viewer that flips and wipes between the pictures,
 * and each mode's FLIP map.  Included by reflect/reflect.h; a program may
 * include either.
 */
#ifndef REFLECT_REPORT_H
#define REFLECT_REPORT_H

#include <stdio.h>

#include "reflect/reflect.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rf_report rf_report;

/* A report against the truth at path (a stream or an image file, as
 * rf_picture_read reads them), whose colour is R G B, else spec.R spec.G
 * spec.B; every value finite.  RF_EIO, RF_EFORMAT... with err saying
 * what and how to fix it. */
RF_EXTERN int rf_report_create(rf_report **r, const char *path, char *err, size_t errlen);
RF_EXTERN void rf_report_destroy(rf_report *r);

/* The exposures linear pictures are shown at: the whole stops lo to hi
 * (default -4 to +3), each a PNG a picture, which is most of a page's
 * size; called before the first rf_report_add.  RF_EINVAL when lo > hi,
 * either is beyond RF_REPORT_STOP_LIMIT stops, more than 16 are asked
 * for or a mode is added already; RF_ENOMEM.  Display pictures are shown
 * as they are, at one exposure, whatever the stops. */
#define RF_REPORT_STOP_LIMIT 16
RF_EXTERN int rf_report_stops(rf_report *r, int lo, int hi);

/* Adds a mode: its name (shown, and unique), the picture at path, of the
 * truth's size, colour and encoding (linear or display sRGB), every
 * value finite; ns its time in nanoseconds a pixel (NaN: not known).
 * The errors are measured here, FLIP on nthreads threads. */
RF_EXTERN int rf_report_add(rf_report *r, const char *name, const char *path, double ns,
                            int nthreads, char *err, size_t errlen);
/* A mode's caption (NULL: none); RF_EINVAL for no such mode. */
RF_EXTERN int rf_report_caption(rf_report *r, const char *name, const char *text);
/* A mode's time, as rf_report_add takes it; RF_EINVAL for no such mode. */
RF_EXTERN int rf_report_time(rf_report *r, const char *name, double ns);
/* The mode of that name's index, or -1. */
RF_EXTERN int rf_report_find(const rf_report *r, const char *name);
RF_EXTERN size_t rf_report_nmodes(const rf_report *r);

/* A mode's figures against the truth. */
struct rf_report_errors {
	double rel_rmse;  /* RMSE over the mean of the truth (reflect-compare's relative) */
	double psnr;      /* dB, peak 1 */
	double flip;      /* FLIP's mean: HDR-FLIP for linear pictures, else LDR-FLIP */
	double ns;        /* nanoseconds a pixel, NaN: not known */
};
RF_EXTERN void rf_report_errors(const rf_report *r, size_t mode, struct rf_report_errors *e);

/* Writes the page, titled title, to fp; RF_EIO with err when a write
 * fails (fp is the caller's to close), RF_ENOMEM. */
RF_EXTERN int rf_report_write(rf_report *r, FILE *fp, const char *title, char *err,
                              size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
