#!/bin/sh
test_description='an image header that claims more than its file holds: refused before any allocation'
. "$srcdir/tests/lib.sh"

# A 913-byte Radiance HDR file claiming 20000 x 20000 cost 4.8 GB and 20 s
# before its reader found the data missing.  Every reader now checks the
# header's size first (lib/image/bounds.c): at most 2^28 values, and no
# more than the file can hold.

SQ="'"
PY=
for p in "${PYTHON3:-}" /usr/bin/python3 python3
do
	test -n "$p" && command -v "$p" >/dev/null 2>&1 && { PY=$p; break; }
done

# refused FILE: reflect-import says, in one line within 10 s and under
# 1 GB of memory, that the image is out of range.
# (Address space limits do not mix with the sanitizers: none there.)
limit=1500000
grep -q fsanitize "$builddir/Makefile" && limit=unlimited
refused () {
	(ulimit -v $limit && exec timeout 10 reflect-import "$1") >out 2>err
	test $? -eq 1 &&
	test_one_line_message reflect-import err &&
	test_grep "^reflect-import: ${SQ}$1${SQ}: a [0-9]*x[0-9]* image of [0-9]* channels is out of range" err &&
	test ! -s out
}

test_expect_success 'the 913-byte HDR claiming 20000 x 20000' '
	printf "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 20000 +X 20000\n" >big.hdr &&
	head -c 860 /dev/zero >>big.hdr &&
	test $(wc -c <big.hdr) -eq 913 &&
	refused big.hdr
'

test_expect_success 'the same, named by a scene' '
	printf "probe box -5 -5 -5 5 5 5\nsphere center 0 0 -2 radius 0.5 normalmap image big.hdr\n" >s.scene &&
	test_expect_code 1 timeout 10 reflect-gbuffer -x 4 -y 4 s.scene >out 2>err &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "out of range" err
'

# A constant image is the smallest an HDR file of its size can be: its
# scanlines are run-length coded at 2 bytes for 127 pixels.
test_expect_success 'an HDR file holds at least its scanlines: one byte short is refused' '
	head -c $((300 * 40 * 3 * 4)) /dev/zero |
		reflect-export -H -x 300 -y 40 -c R,G,B -o zero.hdr &&
	reflect-import zero.hdr | reflect-info >info &&
	test_grep "NCOLS=300" info &&
	size=$(wc -c <zero.hdr) &&
	head -c $((size - 1)) zero.hdr >short.hdr &&
	refused short.hdr &&
	test_grep "its $((size - 1)) bytes cannot hold it ($size needed)" err &&
	head -c $((size / 2)) zero.hdr >half.hdr &&
	refused half.hdr
'

if test -n "$PY"
then
	test_expect_success 'a PNG and a TIFF that claim 2^28 values in 100 bytes' '
		$PY - <<-\PYEOF &&
		import struct, zlib
		def chunk(t, d):
		    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
		ihdr = struct.pack(">IIBBBBB", 16384, 16384, 8, 0, 0, 0, 0)
		png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\0" * 64)) + chunk(b"IEND", b"")
		open("big.png", "wb").write(png)
		# a baseline TIFF: 16000 x 16000 grey, one strip that is not there
		tags = [(256, 4, 16000), (257, 4, 16000), (258, 3, 8), (259, 3, 1), (262, 3, 1),
		        (273, 4, 200), (277, 3, 1), (278, 4, 16000), (279, 4, 256000000)]
		ifd = struct.pack("<H", len(tags))
		for tag, typ, val in tags:
		    ifd += struct.pack("<HHII", tag, typ, 1, val) if typ == 4 else struct.pack("<HHIHH", tag, typ, 1, val, 0)
		ifd += struct.pack("<I", 0)
		open("big.tif", "wb").write(b"II*\0" + struct.pack("<I", 8) + ifd + b"\0" * 40)
		PYEOF
		test $(wc -c <big.png) -lt 200 &&
		refused big.png &&
		test_grep "cannot hold it" err &&
		refused big.tif &&
		test_grep "cannot hold it" err &&
		REFLECT_READERS=module refused big.png
	'
	# libpng reads and zeroes a whole text chunk before it looks at
	# it: 300 bytes claiming a 700 MB tEXt chunk cost 707 MB.
	test_expect_success 'a PNG chunk we do not use costs no memory, whatever it claims' '
		$PY - <<-\PYEOF &&
		import struct, zlib
		def chunk(t, d, n=None):
		    n = len(d) if n is None else n
		    return struct.pack(">I", n) + t + d + struct.pack(">I", zlib.crc32(t + d))
		ihdr = struct.pack(">IIBBBBB", 4, 2, 8, 0, 0, 0, 0)
		head = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr)
		idat = chunk(b"IDAT", zlib.compress(b"\0" * 10)) + chunk(b"IEND", b"")
		text = chunk(b"tEXt", b"Comment\0" + b"x" * 200, 700 << 20)
		open("claims.png", "wb").write(head + text + idat)
		open("texts.png", "wb").write(head + chunk(b"tEXt", b"Comment\0" + b"x" * 200) +
		                              chunk(b"zTXt", b"Comment\0\0" + zlib.compress(b"y" * 300)) +
		                              chunk(b"iCCP", b"p\0\0" + zlib.compress(b"junk")) + idat)
		PYEOF
		cat >peak.py <<-\PYEOF &&
		import resource, subprocess, sys
		r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=open("err", "w"))
		kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
		print("status", r.returncode, "peak", kb, "KB")
		sys.exit(r.returncode != 1 or kb > 200000)
		PYEOF
		$PY peak.py reflect-import claims.png &&
		test_one_line_message reflect-import err &&
		test_grep "claims.png${SQ}: the file ends inside a chunk: truncated or damaged" err &&
		reflect-import texts.png | reflect-info >info &&
		test_grep "NCOLS=4" info &&
		test_grep "NROWS=2" info
	'
else
	test_skip 'a PNG and a TIFF that claim 2^28 values in 100 bytes' 'no python3'
	test_skip 'a PNG chunk we do not use costs no memory, whatever it claims' 'no python3'
fi

test_done
