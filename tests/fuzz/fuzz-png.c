/*
 * libFuzzer harness for libreflect's PNG reader (lib/image/png_read.c,
 * through libpng) and the bounds it checks a header against
 * (lib/image/bounds.c): the input is written to a memory file and read
 * by its /proc path.  An image that reads is within 2^28 values and what
 * the file can hold, each value there; a refusal says why in one
 * printable line.
 */
#define HARNESS "fuzz-png"
#include "image-harness.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	image_run(data, size);
	return 0;
}
