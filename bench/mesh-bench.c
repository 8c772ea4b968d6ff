/*
 * Benchmark of ray casting through the scene's Embree BVH (issue 30): a
 * room holding 7 x 7 icospheres of 20480 triangles (1,003,520 in all),
 * built in memory as the mesh loader would hand them over, to a 1920 x
 * 1080 G-buffer, the BVH's build included (it is built by the G-buffer's
 * creation); then each scene named on the command line (the analytic
 * ones of doc/examples) the same way.  Median wall time of 5 runs, each on
 * a fresh scene.  Not part of make check.
 *
 *	bench/mesh-bench [-j THREADS] [SCENE...]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "scene/scene-internal.h"
#include "reflect/scene.h"

#define RUNS 5
#define W 1920
#define H 1080

static double
clock_seconds(clockid_t id)
{
	struct timespec t;

	clock_gettime(id, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double
now(void)
{
	return clock_seconds(CLOCK_MONOTONIC);
}

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

/* An icosphere: each face of the icosahedron split into n^2 triangles
 * (n = 2^levels), vertices on the sphere, normals radial. */
static int
add_icosphere(rf_scene *s, const double c[3], double r, int levels, size_t line)
{
	static const int faces[20][3] = {
		{ 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 },
		{ 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 },
		{ 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 },
		{ 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 }
	};
	const double g = (1.0 + sqrt(5.0)) / 2.0;
	const double base[12][3] = {
		{ -1, g, 0 }, { 1, g, 0 }, { -1, -g, 0 }, { 1, -g, 0 },
		{ 0, -1, g }, { 0, 1, g }, { 0, -1, -g }, { 0, 1, -g },
		{ g, 0, -1 }, { g, 0, 1 }, { -g, 0, -1 }, { -g, 0, 1 }
	};
	const size_t n = (size_t)1 << levels, pv = (n + 1) * (n + 2) / 2;
	struct rf__mesh m;
	size_t f, i, j, v = 0, t = 0;
	char err[256];

	memset(&m, 0, sizeof(m));
	m.line = line;
	m.path = strdup("icosphere");
	m.nvertices = 20 * pv;
	m.ntriangles = 20 * n * n;
	m.positions = malloc(3 * m.nvertices * sizeof(float));
	m.normals = malloc(3 * m.nvertices * sizeof(float));
	m.tangents = malloc(4 * m.nvertices * sizeof(float));
	m.uv[0] = calloc(2 * m.nvertices, sizeof(float));
	m.indices = malloc(3 * m.ntriangles * sizeof(uint32_t));
	m.nmaterials = 1;
	m.materials = calloc(1, sizeof(*m.materials));
	if (!m.path || !m.positions || !m.normals || !m.tangents || !m.uv[0] || !m.indices ||
	    !m.materials)
		return RF_ENOMEM;
	m.materials[0].base_colour[0] = m.materials[0].base_colour[1] = 0.8f;
	m.materials[0].base_colour[2] = m.materials[0].base_colour[3] = 0.8f;
	m.materials[0].roughness = 0.3f;
	m.materials[0].metallic = 1.0f;
	m.materials[0].mask = 1.0f;
	for (f = 0; f < 20; f++) {
		const size_t first = v;

		for (i = 0; i <= n; i++)
			for (j = 0; j <= n - i; j++) {
				double p[3], len = 0, tl;
				int k;

				for (k = 0; k < 3; k++) {
					p[k] = (base[faces[f][0]][k] * (double)(n - i - j) +
					        base[faces[f][1]][k] * (double)i +
					        base[faces[f][2]][k] * (double)j) / (double)n;
					len += p[k] * p[k];
				}
				len = sqrt(len);
				for (k = 0; k < 3; k++) {
					m.normals[3 * v + (size_t)k] = (float)(p[k] / len);
					m.positions[3 * v + (size_t)k] = (float)(c[k] + r * p[k] / len);
				}
				/* the tangent: +Y x N, or +X at the poles */
				tl = sqrt(p[0] * p[0] + p[2] * p[2]);
				m.tangents[4 * v] = tl > 1e-9 ? (float)(p[2] / tl) : 1.0f;
				m.tangents[4 * v + 1] = 0.0f;
				m.tangents[4 * v + 2] = tl > 1e-9 ? (float)(-p[0] / tl) : 0.0f;
				m.tangents[4 * v + 3] = 1.0f;
				v++;
			}
#define IDX(a, b) (first + (a) * (n + 1) - (a) * ((a) - 1) / 2 + (b))
		for (i = 0; i < n; i++)
			for (j = 0; j < n - i; j++) {
				m.indices[3 * t] = (uint32_t)IDX(i, j);
				m.indices[3 * t + 1] = (uint32_t)IDX(i + 1, j);
				m.indices[3 * t + 2] = (uint32_t)IDX(i, j + 1);
				t++;
				if (j + 1 < n - i) {
					m.indices[3 * t] = (uint32_t)IDX(i + 1, j);
					m.indices[3 * t + 1] = (uint32_t)IDX(i + 1, j + 1);
					m.indices[3 * t + 2] = (uint32_t)IDX(i, j + 1);
					t++;
				}
			}
#undef IDX
	}
	if (rf__scene_add_mesh(s, &m, err, sizeof(err)) < 0) {
		fprintf(stderr, "mesh-bench: %s\n", err);
		exit(1);
	}
	return 0;
}

/* The last minute's load average, to say how busy the machine was. */
static double
load(void)
{
	FILE *fp = fopen("/proc/loadavg", "r");
	double l = -1;

	if (fp) {
		if (fscanf(fp, "%lf", &l) != 1)
			l = -1;
		fclose(fp);
	}
	return l;
}

static const char grid_text[] =
	"camera position 0 6 7 target 0 0.5 0 fov 50\n"
	"probe center 0 2 0 box -6 0 -6 6 8 8\n";

static rf_scene *
grid_scene(size_t *ntris)
{
	rf_scene *s = NULL;
	char err[256];
	int i, j;

	if (rf_scene_parse(&s, grid_text, strlen(grid_text), "grid.scene", err, sizeof(err)) < 0) {
		fprintf(stderr, "mesh-bench: %s\n", err);
		exit(1);
	}
	*ntris = 0;
	for (i = 0; i < 7; i++)
		for (j = 0; j < 7; j++) {
			const double c[3] = { (i - 3) * 1.2, 0.6, (j - 3) * 1.2 };

			if (add_icosphere(s, c, 0.55, 5, 3) < 0)
				exit(1);
			*ntris += s->meshes[s->nmeshes - 1].ntriangles;
		}
	return s;
}

/* Seconds from the G-buffer's creation (which builds the BVH) to its last
 * row; *build the creation alone; *cpu the CPU seconds of both, every
 * thread's (on a machine shared with other work the wall time grows, the
 * CPU time much less). */
static double
gbuffer_time(const rf_scene *s, int threads, float *out, double *build, double *cpu)
{
	struct rf_camera cam;
	rf_gbuffer *g = NULL;
	char err[256];
	double c0 = clock_seconds(CLOCK_PROCESS_CPUTIME_ID), t0 = now(), t1;

	rf_scene_camera(s, &cam);
	if (rf_gbuffer_create(&g, s, W, H, NULL, threads, err, sizeof(err)) < 0 ||
	    rf_gbuffer_set_camera(g, &cam, err, sizeof(err)) < 0) {
		fprintf(stderr, "mesh-bench: %s\n", err);
		exit(1);
	}
	t1 = now();
	rf_gbuffer_render(g, out, 0, H);
	rf_gbuffer_destroy(g);
	*build = t1 - t0;
	*cpu = clock_seconds(CLOCK_PROCESS_CPUTIME_ID) - c0;
	return now() - t0;
}

static void
report(const char *name, size_t ntris, double *total, double *build, double *cpu)
{
	double render[RUNS];
	int r;

	for (r = 0; r < RUNS; r++)
		render[r] = total[r] - build[r];
	qsort(total, RUNS, sizeof(double), cmp_double);
	qsort(build, RUNS, sizeof(double), cmp_double);
	qsort(render, RUNS, sizeof(double), cmp_double);
	qsort(cpu, RUNS, sizeof(double), cmp_double);
	printf("%-20s %9zu %9.3f %9.3f %9.3f %9.3f\n", name, ntris, total[RUNS / 2],
	       build[RUNS / 2], render[RUNS / 2], cpu[RUNS / 2]);
}

int
main(int argc, char **argv)
{
	int threads = 2, opt, r, a;
	float *out = malloc((size_t)W * H * 32 * sizeof(float));
	double total[RUNS], build[RUNS], cpu[RUNS];
	size_t ntris = 0;

	while ((opt = getopt(argc, argv, "j:")) != -1) {
		if (opt != 'j') {
			fprintf(stderr, "usage: mesh-bench [-j THREADS] [SCENE...]\n");
			return 1;
		}
		threads = atoi(optarg);
	}
	if (!out)
		return 2;
	printf("1920x1080 G-buffer, %d threads, median of %d runs\n", threads, RUNS);
	printf("load average %.2f\n", load());
	printf("%-20s %9s %9s %9s %9s %9s\n", "scene", "triangles", "total s", "build s",
	       "render s", "CPU s");
	for (r = 0; r < RUNS; r++) {
		rf_scene *s = grid_scene(&ntris);

		total[r] = gbuffer_time(s, threads, out, &build[r], &cpu[r]);
		rf_scene_destroy(s);
	}
	report("7x7 icospheres", ntris, total, build, cpu);
	for (a = optind; a < argc; a++) {
		const char *base = strrchr(argv[a], '/') ? strrchr(argv[a], '/') + 1 : argv[a];

		for (r = 0; r < RUNS; r++) {
			rf_scene *s = NULL;
			char err[256];
			FILE *fp = fopen(argv[a], "r");

			if (!fp) {
				fprintf(stderr, "mesh-bench: cannot open '%s'\n", argv[a]);
				return 1;
			}
			if (rf_scene_read(&s, fp, argv[a], err, sizeof(err)) < 0) {
				fprintf(stderr, "mesh-bench: %s\n", err);
				return 1;
			}
			fclose(fp);
			total[r] = gbuffer_time(s, threads, out, &build[r], &cpu[r]);
			rf_scene_destroy(s);
		}
		report(base, 0, total, build, cpu);
	}
	free(out);
	return 0;
}
