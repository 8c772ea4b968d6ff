/*
 * Runs a fuzz harness once on each file named (or in each directory
 * named), without libFuzzer: make check replays the corpora and the
 * reproductions of bugs found so far this way, with the compiler the
 * build uses (and the sanitizers, in ./run-tests --sanitize).
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int
run_file(const char *path)
{
	FILE *fp = fopen(path, "rb");
	unsigned char *buf = NULL;
	size_t len = 0, cap = 0, n;

	if (!fp) {
		perror(path);
		return 1;
	}
	for (;;) {
		if (len == cap) {
			unsigned char *grown = realloc(buf, cap = cap ? 2 * cap : 65536);

			if (!grown) {
				fclose(fp);
				free(buf);
				return 1;
			}
			buf = grown;
		}
		if (!(n = fread(buf + len, 1, cap - len, fp)))
			break;
		len += n;
	}
	fclose(fp);
	LLVMFuzzerTestOneInput(buf, len);
	free(buf);
	printf("ran %s (%zu bytes)\n", path, len);
	return 0;
}

int
main(int argc, char **argv)
{
	int i, bad = 0;

	for (i = 1; i < argc; i++) {
		struct stat st;
		DIR *d;
		struct dirent *e;
		char path[4096];

		if (stat(argv[i], &st) == 0 && S_ISDIR(st.st_mode) && (d = opendir(argv[i]))) {
			while ((e = readdir(d)))
				if (e->d_name[0] != '.') {
					snprintf(path, sizeof(path), "%s/%s", argv[i], e->d_name);
					bad |= run_file(path);
				}
			closedir(d);
		} else {
			bad |= run_file(argv[i]);
		}
	}
	return bad;
}
