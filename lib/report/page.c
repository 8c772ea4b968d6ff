/*
 * The report as one HTML page that names nothing outside itself: the
 * pictures as data: URIs, the style and the script (report.css,
 * report.js, compiled in as assets.h) inline.  The figures are in the
 * table twice, shown rounded and in data-v at full precision, for the
 * sort and for scripts that read the page.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "report/assets.h"
#include "report/report-internal.h"

/* Text as HTML holds it, in an element or a quoted attribute. */
static void
html(FILE *fp, const char *s)
{
	for (; *s; s++)
		switch (*s) {
		case '&': fputs("&amp;", fp); break;
		case '<': fputs("&lt;", fp); break;
		case '>': fputs("&gt;", fp); break;
		case '"': fputs("&quot;", fp); break;
		case '\'': fputs("&#39;", fp); break;
		default: putc(*s, fp);
		}
}

/* A JSON string inside a <script> element: no "</script" can close it
 * early, as every '<' is escaped. */
static void
json(FILE *fp, const char *s)
{
	putc('"', fp);
	for (; *s; s++) {
		const unsigned char c = (unsigned char)*s;

		if (c == '"' || c == '\\')
			fprintf(fp, "\\%c", c);
		else if (c < 0x20 || c == 0x7f || c == '<' || c == '>' || c == '&')
			fprintf(fp, "\\u%04x", c);
		else
			putc(c, fp);
	}
	putc('"', fp);
}

/* A figure's cell: data-v exact (empty when not known), the text
 * rounded. */
static void
cell(FILE *fp, double v, const char *fmt)
{
	if (isnan(v)) {
		fputs("<td class=\"num\" data-v=\"\">&ndash;</td>", fp);
		return;
	}
	if (isinf(v)) {
		fprintf(fp, "<td class=\"num\" data-v=\"%s\">%s&infin;</td>", v > 0 ? "Infinity"
		                                                                   : "-Infinity",
		        v > 0 ? "" : "&minus;");
		return;
	}
	fprintf(fp, "<td class=\"num\" data-v=\"%.9g\">", v);
	fprintf(fp, fmt, v);
	fputs("</td>", fp);
}

static void
head(const rf_report *r, FILE *fp, const char *title)
{
	fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
	      "<meta name=\"generator\" content=\"reflect-report\">\n<title>", fp);
	html(fp, title);
	fputs("</title>\n<style>\n", fp);
	fputs(rf__report_css, fp);
	fputs("</style>\n</head>\n<body>\n<h1>", fp);
	html(fp, title);
	fputs("</h1>\n<p class=\"about\">Against the truth <code>", fp);
	html(fp, r->pics[0].path);
	fprintf(fp, "</code>, %zu&times;%zu pixels, %s pictures. ", r->width, r->height,
	        r->srgb ? "display (sRGB)" : "linear");
	if (r->srgb)
		fprintf(fp, "FLIP is LDR-FLIP at %.4g pixels per degree.", r->ppd);
	else
		fprintf(fp, "FLIP is HDR-FLIP at %.4g pixels per degree, %d exposures from %.4g "
		        "to %.4g stops.", r->ppd, r->nexposures, r->start, r->stop);
	fputs(" Relative RMSE and PSNR (peak 1) are reflect-compare's.</p>\n", fp);
}

static void
table(const rf_report *r, FILE *fp)
{
	size_t i;

	fputs("<h2>Errors</h2>\n<table class=\"errors\" id=\"errors\">\n<thead><tr>"
	      "<th>mode</th><th>relative RMSE</th><th>PSNR (dB)</th><th>FLIP</th>"
	      "<th>ns / pixel</th></tr></thead>\n<tbody>\n", fp);
	for (i = 1; i < r->npics; i++) {
		const struct rf__report_picture *p = &r->pics[i];

		fprintf(fp, "<tr data-pic=\"%zu\"><td>", i);
		html(fp, p->name);
		fputs("</td>", fp);
		cell(fp, p->e.rel_rmse, "%.4g");
		cell(fp, p->e.psnr, "%.2f");
		cell(fp, p->e.flip, "%.4f");
		cell(fp, p->e.ns, "%.3g");
		fputs("</tr>\n", fp);
	}
	fputs("</tbody>\n</table>\n", fp);
}

/* The exposure the viewer starts at: the pictures' own values, or the
 * stop nearest them. */
static int
stop0(const rf_report *r)
{
	if (r->srgb || r->stop_lo > 0)
		return 0;
	return r->stop_lo + r->nstops - 1 < 0 ? r->nstops - 1 : -r->stop_lo;
}

static void
viewer(const rf_report *r, FILE *fp)
{
	fputs("<h2>Viewer</h2>\n<div class=\"controls\">\n"
	      "<label>A <select id=\"sel-a\"></select></label>\n"
	      "<label>B <select id=\"sel-b\"></select></label>\n"
	      "<label>wipe <input type=\"range\" id=\"wipe\" min=\"0\" max=\"100\" "
	      "value=\"100\"></label>\n"
	      "<label>exposure <input type=\"range\" id=\"exposure\" min=\"0\" max=\"", fp);
	fprintf(fp, "%d\" step=\"1\" value=\"%d\"></label> <span id=\"exposure-value\"></span>\n",
	        r->srgb ? 0 : r->nstops - 1, stop0(r));
	fputs("<button id=\"fit\">fit</button> <button id=\"one\">1:1</button>\n</div>\n"
	      "<p class=\"keys\">Keys: 0 shows the truth as A, 1 to 9 a mode, &larr; and "
	      "&rarr; the previous or next; + (or =) and &minus; the exposure. The slider wipes from A "
	      "(left) to B (right). The wheel zooms, a drag pans, a double click fits; the "
	      "picture and its FLIP map move together.</p>\n"
	      "<div class=\"views\">\n"
	      "<div class=\"view\" id=\"view-pic\"><div class=\"layer\" id=\"layer-pic\">"
	      "<div id=\"pics-a\"></div><div class=\"wipe\" id=\"wipe-b\"></div>"
	      "<div class=\"wipe-line\" id=\"wipe-line\"></div></div>"
	      "<span class=\"tag\" id=\"tag-a\"></span>"
	      "<span class=\"tag right\" id=\"tag-b\"></span></div>\n"
	      "<div class=\"view\" id=\"view-heat\"><div class=\"layer\" id=\"layer-heat\">"
	      "</div><span class=\"tag\" id=\"tag-heat\"></span></div>\n</div>\n", fp);
}

static void
cards(const rf_report *r, FILE *fp)
{
	size_t i;

	fputs("<h2>FLIP maps</h2>\n<p class=\"about\">FLIP's error per pixel, 0 (black) to 1 "
	      "(pale yellow), in the magma colour map.</p>\n<div class=\"cards\">\n", fp);
	for (i = 1; i < r->npics; i++) {
		const struct rf__report_picture *p = &r->pics[i];

		fprintf(fp, "<figure class=\"card\" data-pic=\"%zu\"><img id=\"heat-%zu\" "
		        "width=\"%zu\" height=\"%zu\" alt=\"FLIP map of ", i, i, r->width, r->height);
		html(fp, p->name);
		fputs("\" src=\"data:image/png;base64,", fp);
		fputs(p->heat, fp);
		fputs("\"><figcaption><span class=\"name\">", fp);
		html(fp, p->name);
		fputs("</span> <code>", fp);
		html(fp, p->path);
		fprintf(fp, "</code> FLIP %.4f", p->e.flip);
		if (p->caption) {
			fputs("<br>", fp);
			html(fp, p->caption);
		}
		fputs("</figcaption></figure>\n", fp);
	}
	fputs("</div>\n", fp);
}

/* Every picture at every exposure, decoded once: the viewer takes its
 * pictures from here. */
static void
store(const rf_report *r, FILE *fp)
{
	const int nstops = r->srgb ? 1 : r->nstops;
	size_t i;
	int e;

	fputs("<div class=\"store\">\n", fp);
	for (i = 0; i < r->npics; i++)
		for (e = 0; e < nstops; e++) {
			fprintf(fp, "<img id=\"shot-%zu-%d\" width=\"%zu\" height=\"%zu\" alt=\"", i, e,
			        r->width, r->height);
			html(fp, r->pics[i].name);
			fputs("\" src=\"data:image/png;base64,", fp);
			fputs(r->pics[i].shots[e], fp);
			fputs("\">\n", fp);
		}
	fputs("</div>\n", fp);
}

/* What the script needs: the size, the exposures, the names. */
static void
data(const rf_report *r, FILE *fp)
{
	size_t i;
	int e;

	fprintf(fp, "<pre id=\"selftest\"></pre>\n<script type=\"application/json\" "
	        "id=\"report-data\">{\"width\": %zu, \"height\": %zu, \"stops\": [", r->width,
	        r->height);
	if (r->srgb)
		fputs("0], \"stop0\": 0", fp);
	else {
		for (e = 0; e < r->nstops; e++)
			fprintf(fp, "%s%d", e ? ", " : "", r->stop_lo + e);
		fprintf(fp, "], \"stop0\": %d", stop0(r));
	}
	fprintf(fp, ", \"linear\": %s, \"pictures\": [", r->srgb ? "false" : "true");
	for (i = 0; i < r->npics; i++) {
		fputs(i ? ", {\"name\": " : "{\"name\": ", fp);
		json(fp, r->pics[i].name);
		fputs("}", fp);
	}
	fputs("]}</script>\n<script>\n", fp);
	fputs(rf__report_js, fp);
	fputs("</script>\n</body>\n</html>\n", fp);
}

void
rf__report_page(const rf_report *r, FILE *fp, const char *title)
{
	head(r, fp, title);
	table(r, fp);
	viewer(r, fp);
	cards(r, fp);
	store(r, fp);
	data(r, fp);
}
