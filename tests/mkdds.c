/* mkdds FILE N LEVELS: a float RGBA DDS cube whose face f at level k holds
 * (f + 10 k, 1, 2) everywhere, for the shell tests. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static void
put32(FILE *f, uint32_t v)
{
	unsigned char b[4] = { v & 255, (v >> 8) & 255, (v >> 16) & 255, v >> 24 };

	fwrite(b, 1, 4, f);
}

int
main(int argc, char **argv)
{
	uint32_t n, levels, face, k, i, s;
	FILE *f;

	if (argc != 4 || !(f = fopen(argv[1], "wb")))
		return 1;
	n = (uint32_t)atoi(argv[2]);
	levels = (uint32_t)atoi(argv[3]);
	fwrite("DDS ", 1, 4, f);
	put32(f, 124);
	put32(f, 0x1 | 0x2 | 0x4 | 0x1000 | 0x20000); /* caps height width format mips */
	put32(f, n);
	put32(f, n);
	put32(f, n * 16);
	put32(f, 0);
	put32(f, levels);
	for (i = 0; i < 11; i++)
		put32(f, 0);
	put32(f, 32);          /* pixel format: size */
	put32(f, 0x4);         /* FourCC */
	put32(f, 116);         /* A32B32G32R32F */
	for (i = 0; i < 5; i++)
		put32(f, 0);
	put32(f, 0x1000 | 0x8 | 0x400000); /* texture, complex, mipmap */
	put32(f, 0x200 | 0xFC00);          /* cubemap, all six faces */
	for (i = 0; i < 3; i++)
		put32(f, 0);
	for (face = 0; face < 6; face++)
		for (k = 0, s = n; k < levels; k++, s /= 2)
			for (i = 0; i < s * s; i++) {
				float px[4] = { (float)(face + 10 * k), 1.0f, 2.0f, 1.0f };

				fwrite(px, sizeof(float), 4, f);
			}
	return fclose(f) != 0;
}
