#!/bin/sh
test_description='image files go through a module loaded only when needed'
. "$srcdir/tests/lib.sh"

test_expect_success 'stages that touch no image file run without the module' '
	cat >gb.txt <<-\EOF &&
	#?REFLECT1
	NCOLS=1
	NROWS=1
	NCOMP=9
	CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z
	PROBE_BOX=-3 0 -2 3 3 2
	FORMAT=ascii

	0 1 0 0 1 0 0 1 0
	EOF
	REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so reflect-project gb.txt >out.rfl &&
	REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so reflect-info -s out.rfl >info &&
	test_grep "hit.dist" info &&
	REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so reflect-prefilter --size=8 >/dev/null
'

test_expect_success 'PNG and OpenEXR are written without the module' '
	reflect-project gb.txt >p.rfl &&
	REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so \
		reflect-export -c all -o x.exr p.rfl &&
	REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so \
		reflect-export -c all --half -o h.exr p.rfl &&
	REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so \
		reflect-export -c hit.dist --srgb=off -o x.png p.rfl &&
	REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so \
		reflect-export -c R --depth=16 -o x16.png p.rfl &&
	test -s x.exr && test -s h.exr && test -s x.png && test -s x16.png
'

test_expect_success 'a missing module is one clear message when an image is needed' '
	test_expect_code 1 env REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so \
		reflect-export -c all -o x.tif p.rfl 2>err &&
	test_one_line_message reflect-export err &&
	test_grep "cannot load the image module ./nonexistent/reflect-oiio.so." err &&
	echo "an image file" >some.exr &&
	test_expect_code 1 env REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so \
		reflect-prefilter some.exr 2>err &&
	test_one_line_message reflect-prefilter err &&
	test_grep "cannot load the image module" err
'

test_expect_success 'a library that is not the module is refused' '
	lib=$(ls "$builddir"/plugins/.libs/projection-box.so) &&
	test_expect_code 1 env REFLECT_IMAGE_MODULE="$lib" reflect-export -c all -o x.tif p.rfl 2>err &&
	test_grep "is not reflect.s image module" err
'

test_expect_success 'the module found next to libreflect works' '
	reflect-export -c all -o x.exr p.rfl &&
	reflect-prefilter --plain --levels=2 --size=8 --dump=cube 2>/dev/null &&
	test -s level0-cube.exr
'

# OpenEXR and PNG files are read by libreflect itself: scanline images as
# reflect-export writes them (float and half), a tiled MIP-mapped cube
# chain as reflect-prefilter writes it, 8- and 16-bit colour and grey
# PNG; the same names in the same order and the same values as the
# module reads (REFLECT_READERS=module).
test_expect_success 'OpenEXR and PNG are read without the module, as the module reads them' '
	reflect-prefilter --size=16 -o chain.exr 2>/dev/null &&
	reflect-gbuffer -x 24 -y 12 | reflect-project >g.rfl &&
	REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so \
		reflect-shade -h -m hdrp --final --env=chain.exr g.rfl >own &&
	REFLECT_READERS=module reflect-shade -h -m hdrp --final --env=chain.exr g.rfl >module &&
	cmp own module &&
	reflect-shade -fa -m none --final --env=chain.exr g.rfl >shaded.txt &&
	reflect-export -c all -o all.exr shaded.txt &&
	reflect-export -c all --half -o half.exr shaded.txt &&
	reflect-export -o c8.png shaded.txt &&
	reflect-export --depth=16 -c R,G,B,mask -o c16.png shaded.txt &&
	reflect-export -c spec.G -o grey.png shaded.txt &&
	for f in all.exr half.exr chain.exr c8.png c16.png grey.png
	do
		REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so \
			"$builddir/tests/imgdump" $f >own.txt || return 1
		REFLECT_READERS=module "$builddir/tests/imgdump" $f >module.txt || return 1
		cmp own.txt module.txt || return 1
	done &&
	REFLECT_IMAGE_MODULE=/nonexistent/reflect-oiio.so "$builddir/tests/imgdump" all.exr |
		sed -n 2p >names &&
	test_grep "^R G B depth mask" names &&
	test_grep " spec.R spec.G spec.B" names
'

# The module is C++ (OpenImageIO), the tools C: an exception that crossed
# into them ended the process (std::terminate, status 134).  Under a limit
# on address space, reading a TIFF threw std::system_error from a thread
# the reader could not start, and loading the module threw from a
# library's constructor inside dlopen.  Each limit of the ladder either
# reads the file or refuses with one line and status 2 (system error).
test_expect_success 'no exception leaves the module, under ulimit -v' '
	if grep -q fsanitize "$builddir/Makefile"
	then
		echo "# skipped: address space limits do not mix with the sanitizers"
		return 0
	fi &&
	reflect-gbuffer -x 16 -y 16 | reflect-export -c albedo.R,albedo.G,albedo.B -o a.tif &&
	for v in 400000 430000 460000 480000 500000 540000 800000
	do
		got=$(ulimit -v $v && { reflect-import a.tif >out 2>err; echo $?; }) &&
		echo "ulimit -v $v: status $got" &&
		case $got in
		0) test -s out ;;
		2) test_one_line_message reflect-import err ;;
		*) cat err && false ;;
		esac || return 1
	done
'

test_done
