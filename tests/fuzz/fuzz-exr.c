/*
 * libFuzzer harness for libreflect's OpenEXR reader (lib/image/exr_read.c,
 * through OpenEXR's C core) and the bounds it checks a header against
 * (lib/image/bounds.c): the input is written to a memory file and read
 * by its /proc path.  An image that reads is within 2^28 values and what
 * the file can hold, each value there; a refusal says why in one
 * printable line.
 */
#define HARNESS "fuzz-exr"
#include "image-harness.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	image_run(data, size);
	return 0;
}
