#!/bin/sh
test_description='a third-party plugin, built out of tree against the installed header only'
. "$srcdir/tests/lib.sh"

# The build tree is installed into a prefix under the trash directory.
# The example plugin of reflect-plugin(7), doc/examples/sphere.c, is
# copied to a directory outside the source and build trees and compiled
# there with nothing but the installed header, found through pkg-config.
#
# `make install prefix=DIR` moves the files but not the paths recorded
# at configure time (the .pc files' prefix= line, the tools' default
# plugin directory).  So pkg-config runs with --define-prefix, which
# takes the prefix from where the .pc file lies, as for any relocated
# install, and the tools get their plugin directory from the environment.

prefix=$PWD/prefix
oot=$(mktemp -d "${TMPDIR:-/tmp}/reflect-oot.XXXXXX") || {
	echo "Bail out! mktemp -d failed"
	exit 1
}

pc () {
	PKG_CONFIG_PATH="$prefix/lib/pkgconfig" PKG_CONFIG_LIBDIR= \
		pkg-config --define-prefix "$@"
}

# The installed reflect-project, its plugin directory and the new one.
installed () {
	LD_LIBRARY_PATH="$prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
	REFLECT_PLUGIN_PATH="$oot" \
	REFLECT_PLUGIN_SYSTEM_PATH="$(cat plugindir)" \
		"$prefix/bin/reflect-project" "$@"
}

data () {
	awk '/^#\?REFLECT1$/ { h = 1; next } h && /^$/ { h = 0; next } !h' "$1"
}

test_expect_success 'make install into a temporary prefix' '
	if ! (
		unset MAKEFLAGS MFLAGS MAKELEVEL &&
		make -C "$builddir" install prefix="$prefix" >install.log 2>&1
	)
	then
		tail -n 20 install.log &&
		false
	fi &&
	test -x "$prefix/bin/reflect-project" &&
	test -f "$prefix/lib/pkgconfig/reflect-plugin.pc" &&
	(cd "$prefix/lib/reflect-1" && ls *.so) >plugins &&
	cat >expect <<-\EOF &&
	accumulate-ema.so
	accumulate-mean.so
	filter-atrous.so
	filter-quad.so
	occlusion-box.so
	occlusion-horizon.so
	projection-bevel.so
	projection-box.so
	projection-infinite.so
	shade-approx.so
	shade-footprint.so
	shade-godot.so
	shade-hdrp.so
	shade-none.so
	shade-raytraced.so
	EOF
	diff -u expect plugins
'

test_expect_success 'the headers are installed as <reflect/plugin.h>' '
	if ! test -f "$prefix/include/reflect/plugin.h"
	then
		echo "no $prefix/include/reflect/plugin.h; installed headers:" &&
		find "$prefix/include" -type f &&
		false
	fi &&
	test -f "$prefix/include/reflect/reflect.h" &&
	cmp "$srcdir/include/reflect/plugin.h" "$prefix/include/reflect/plugin.h"
'

test_expect_success 'pkg-config: plugindir and Cflags point inside the prefix' '
	pc --variable=plugindir reflect-plugin >plugindir &&
	echo "$prefix/lib/reflect-1" >expect &&
	diff expect plugindir &&
	pc --cflags reflect-plugin >cflags &&
	test_grep "^-I$prefix/include *$" cflags &&
	pc --libs reflect-plugin >libs &&
	! grep -e -l libs
'

# Linking statically, pkg-config --static --libs reflect is all a
# program is given: every library the shared libreflect needs must be
# in it: libc, the dynamic loader and the sanitizers' runtimes aside
# (CI's second build links those through its -fsanitize flags, which a
# static user gives himself, not through reflect.pc), and in that build
# the C++ and GCC runtimes the sanitizers pull in.
test_expect_success 'pkg-config --static: every library libreflect needs' '
	pc --static --libs reflect >libs &&
	test_grep "^-L$prefix/lib -lreflect " libs &&
	readelf -d "$prefix/lib/libreflect.so" |
	sed -n "s/.*(NEEDED).*\[lib\([^.]*\)\.so.*/\1/p" >needed &&
	test_grep "^png" needed &&
	while read lib
	do
		case $lib in
		c|ld-linux*|asan|ubsan|lsan|tsan) continue ;;
		stdc++|gcc_s) ! grep -x asan needed >/dev/null || continue ;;
		esac &&
		tr " " "\\n" <libs | grep -x -e "-l$lib" >/dev/null || {
			echo "libreflect needs lib$lib: -l$lib is not in $(cat libs)" >&2 &&
			return 1
		}
	done <needed
'

test_expect_success 'sphere.c builds outside the trees with only the installed header' '
	cp "$srcdir/doc/examples/sphere.c" "$oot/" &&
	(
		cd "$oot" &&
		cc -std=c11 -Wall -Wextra -pedantic -Werror -fPIC -shared \
			$(pc --cflags reflect-plugin) sphere.c -o sphere.so -lm &&
		cc -std=c11 -M $(pc --cflags reflect-plugin) sphere.c
	) >deps &&
	test -f "$oot/sphere.so" &&
	tr " \\\\" "\\n\\n" <deps | grep "reflect/" >used &&
	echo "$prefix/include/reflect/plugin.h" >expect &&
	diff expect used
'

test_expect_success 'the installed reflect-project lists it with its parameter' '
	installed -l >out 2>err &&
	test_line_count 0 err &&
	tab=$(printf "\\t") &&
	test_grep "^sphere${tab}sphere proxy: look up where the reflected ray leaves a sphere around the capture point$" out &&
	test_grep "^  file: $oot/sphere\.so (version 1\.0, plugin ABI 1\.3, reflect developers, public domain)$" out &&
	test_grep "^  reads: P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z$" out &&
	test_grep "^    radius=5${tab}radius of the proxy sphere around the capture point (\[0\.001, 1e+06\])$" out &&
	test_grep "^box${tab}" out &&
	test_grep "^  file: $(cat plugindir)/projection-box\.so " out
'

# The G-buffer: probe centre C = (0,0,0), sphere radius r = 2.  For each
# pixel R = 2 (N.V) N - V; with o = P - C, b = o.R, k = o.o - r^2 the hit
# is t = -b + sqrt(b^2 - k) along R, D = (P + t R - C) / r.
#
# 1. P=(0,0,0) N=V=(0,1,0): R=(0,1,0); b=0, k=-4, t=2.
#    D=(0,1,0), hit.dist 2, probe.dist 2.
# 2. P=(1,0,0) N=V=(0,1,0): R=(0,1,0); b=0, k=1-4=-3, t=sqrt(3)=1.7320508.
#    hit (1, 1.7320508, 0), D=(0.5, 0.8660254, 0), probe.dist 2.
# 3. P=(0,-1,0) N=(0,1,0) V=(0.6,0.8,0): N.V=0.8, R=1.6 N - V =
#    (-0.6, 0.8, 0); b=-0.8, k=1-4=-3, t=0.8+sqrt(0.64+3)=0.8+1.9078784
#    =2.7078784; hit (-0.6t, -1+0.8t, 0) = (-1.6247270, 1.1663027, 0),
#    D = hit/2 = (-0.8123635, 0.5831514, 0), probe.dist 2.
# 4. P=(0,1,0) N=V=(0,1,0): R=(0,1,0); b=1, k=1-4=-3, t=-1+sqrt(1+3)=1.
#    D=(0,1,0), hit.dist 1, probe.dist 2.
# 5. P=(3,0,0): |P-C|=3 > r, outside: N=(1,0,0) V=(0,0,1): N.V=0,
#    R=-V=(0,0,-1); D=R, both distances inf.
test_expect_success 'sphere:radius=2 computes the hand-checked values' '
	cat >gbuf <<-\EOF &&
	#?REFLECT1
	NCOLS=5
	NROWS=1
	NCOMP=9
	CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z
	FORMAT=ascii

	0	0	0	0	1	0	0	1	0
	1	0	0	0	1	0	0	1	0
	0	-1	0	0	1	0	0.6	0.8	0
	0	1	0	0	1	0	0	1	0
	3	0	0	1	0	0	0	0	1
	EOF
	installed -fa -m sphere:radius=2 --box=-10,-10,-10,10,10,10 \
		--center=0,0,0 gbuf >out &&
	test_grep "^CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist$" out &&
	test_grep "^PROJECTION=sphere:radius=2$" out &&
	data out >got &&
	cat >expect <<-\EOF &&
	0 0 0 0 1 0 0 1 0       0 1 0       0 1 0                       2 2
	1 0 0 0 1 0 0 1 0       0 1 0       0.5 0.8660254 0             1.7320508 2
	0 -1 0 0 1 0 0.6 0.8 0  -0.6 0.8 0  -0.8123635 0.5831514 0      2.7078784 2
	0 1 0 0 1 0 0 1 0       0 1 0       0 1 0                       1 2
	3 0 0 1 0 0 0 0 1       0 0 -1      0 0 -1                      inf inf
	EOF
	test_cmp_numbers expect got 2e-6 &&
	cp got full &&
	installed -v -m sphere:radius=2 --box=-10,-10,-10,10,10,10 \
		--center=0,0,0 gbuf >/dev/null 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .sphere. from .$oot/sphere\.so. (radius=2)$" err
'

# The default radius is 5: pixel 1 then hits at (0,5,0).  With box
# projection off every pixel looks up R itself, as the box mode does.
test_expect_success 'the default radius; box projection off' '
	sed -n "1,8p" gbuf | sed "s/^NCOLS=5/NCOLS=1/" >one &&
	installed -fa -m sphere --box=-10,-10,-10,10,10,10 --center=0,0,0 one >out &&
	data out | cut -f 10- >got &&
	echo "0 1 0 0 1 0 5 5" >expect &&
	test_cmp_numbers expect got &&
	installed -fa -m sphere:radius=2 --box=-10,-10,-10,10,10,10 \
		--center=0,0,0 --box-projection=off gbuf >out &&
	data out | sed -n 3p | cut -f 10- >got &&
	echo "-0.6 0.8 0 -0.6 0.8 0 inf inf" >expect &&
	test_cmp_numbers expect got
'

test_expect_success 'its parameter is checked by the host; create() reports errors' '
	test_expect_code 1 installed -m sphere:radius=0 --box=-1,-1,-1,1,1,1 gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .sphere.: parameter .radius. is 0, out of its range (in \[0\.001, 1e+06\])$" err &&
	test_expect_code 1 installed -m sphere gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .sphere.: no probe: give --box and --center, or a stream with PROBE_BOX and PROBE_CENTER$" err
'

test_expect_success 'the uninstalled tools load it as well' '
	REFLECT_PLUGIN_PATH="$oot" reflect-project -fa -m sphere:radius=2 \
		--box=-10,-10,-10,10,10,10 --center=0,0,0 gbuf >out2 &&
	data out2 >got2 &&
	test_cmp_numbers full got2 0
'

# The installed reflect-shade, with the examples built below.
shade () {
	LD_LIBRARY_PATH="$prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
	REFLECT_PLUGIN_PATH="$oot/ex" REFLECT_PLUGIN_SYSTEM_PATH="$(cat plugindir)" \
		"$prefix/bin/reflect-shade" "$@"
}

# The installed examples and their Makefile, built where an author
# would copy them: ratio (an effective-roughness model) and taps (four
# reads of the lobe through sample_many and texel_solid_angle).
test_expect_success 'the installed examples build with their Makefile' '
	ex="$prefix/share/doc/reflect/examples" &&
	test -f "$ex/Makefile" && test -f "$ex/ratio.c" && test -f "$ex/taps.c" &&
	test -f "$ex/reflect-mode-sphere.7" && test -f "$ex/room-floor.scene" &&
	mkdir "$oot/ex" && cp "$ex"/* "$oot/ex/" &&
	cat >"$oot/pc" <<-EOF &&
	#!/bin/sh
	PKG_CONFIG_PATH="$prefix/lib/pkgconfig" PKG_CONFIG_LIBDIR= exec pkg-config --define-prefix "\$@"
	EOF
	chmod +x "$oot/pc" &&
	(unset MAKEFLAGS MFLAGS MAKELEVEL && make -C "$oot/ex" PKG_CONFIG="$oot/pc" \
		CFLAGS="-O2 -Werror -pedantic" >make.log 2>&1) &&
	test -f "$oot/ex/sphere.so" && test -f "$oot/ex/ratio.so" && test -f "$oot/ex/taps.so"
'

# ratio: alpha' = r^2 lerp(1, min(1, d/L), strength), written as its
# square root.  r = 0.5, d = 1, L = 2, strength 1: alpha' = 0.125,
# 0.353553; strength 0.5: 0.1875, 0.433013; d = 3 > L: r itself; +inf
# distances: r itself.
test_expect_success 'the installed reflect-shade runs ratio: by hand' '
	cat >rgb <<-\EOF &&
	#?REFLECT1
	NCOLS=4
	NROWS=1
	NCOMP=6
	CHANNELS=roughness hit.dist probe.dist D.X D.Y D.Z
	FORMAT=ascii

	0.5	1	2	0	1	0
	0.5	3	2	0	1	0
	0.8	inf	inf	0	1	0
	0.3	0	5	0	1	0
	EOF
	shade -fa -m ratio rgb >out 2>/dev/null &&
	data out | cut -f7 >got &&
	printf "%s\n" 0.353553 0.5 0.8 0 >expect &&
	test_cmp_numbers expect got 1e-6 &&
	shade -fa -m ratio:strength=0.5 rgb >out 2>/dev/null &&
	data out | sed -n 1p | cut -f7 >got &&
	echo 0.433013 >expect &&
	test_cmp_numbers expect got 1e-6
'

# taps under a sky of one radiance in every level: 1 whatever the lobe;
# at roughness 0, the mirror read none makes.
test_expect_success 'the installed reflect-shade runs taps: a uniform sky, a mirror' '
	awk "BEGIN { n = 8; for (k = 0; k < 4; k++) {
		printf \"#?REFLECT1\\nENVMAP=CUBE\\nLEVEL=%d\\nLEVELS=4\\nPREFILTER=ggx\\n\", k
		printf \"MAPPING=unity\\nSTEPS=3\\nNCOLS=%d\\nNROWS=%d\\n\", n, 6 * n
		printf \"NCOMP=3\\nCHANNELS=R G B\\nFORMAT=ascii\\n\\n\"
		for (j = 0; j < 6 * n * n; j++) print 0.75, 0.75, 0.75
		n = n / 2 } }" >sky.rfl &&
	shade -fa -m taps --env=sky.rfl rgb >out 2>/dev/null &&
	data out | cut -f7-9 >got &&
	printf "0.75 0.75 0.75\n%.0s" 1 2 3 4 >expect &&
	test_cmp_numbers expect got 1e-6 &&
	cat >mirror <<-\EOF &&
	#?REFLECT1
	NCOLS=4
	NROWS=1
	NCOMP=6
	CHANNELS=roughness hit.dist probe.dist D.X D.Y D.Z
	FORMAT=ascii

	0	1	2	0	1	0
	0	1	2	0.6	0.8	0
	0	1	2	-0.48	0.6	-0.64
	0	1	2	0	0	-1
	EOF
	shade -fa -m none mirror >n.txt 2>/dev/null &&
	shade -fa -m taps mirror >t.txt 2>/dev/null &&
	data n.txt | cut -f8-10 >a &&
	data t.txt | cut -f7-9 >b &&
	test_cmp_numbers a b 1e-5
'

# The installed tools with nothing set but XDG_DATA_HOME: the plugins
# beside the library, the user plugin directory under $oot/xdg.
user () {
	env -u REFLECT_PLUGIN_PATH -u REFLECT_PLUGIN_SYSTEM_PATH -u LD_LIBRARY_PATH \
		XDG_DATA_HOME="$oot/xdg" "$prefix/bin/$@"
}

test_expect_success 'make install-user: the installed tools find the examples, nothing set' '
	(unset MAKEFLAGS MFLAGS MAKELEVEL && XDG_DATA_HOME="$oot/xdg" \
		make -C "$oot/ex" PKG_CONFIG="$oot/pc" install-user >make.log 2>&1) &&
	u="$oot/xdg/reflect/plugins" &&
	test -f "$u/sphere.so" && test -f "$u/ratio.so" && test -f "$u/taps.so" &&
	user reflect-project -m sphere --help >out 2>err &&
	test_line_count 0 err &&
	test_grep "^  file: $u/sphere\.so (version 1\.0, plugin ABI 1\.3, reflect developers, public domain)$" out &&
	test_grep "^  found in: the user plugin directory$" out &&
	# its man page, installed beside it, as reflect-plugin(7) asks
	test -f "$u/reflect-mode-sphere.7" &&
	test_grep "^  man page: $u/reflect-mode-sphere\.7$" out &&
	user reflect-project -fa -m sphere:radius=2 --box=-10,-10,-10,10,10,10 \
		--center=0,0,0 gbuf >out3 &&
	data out3 >got3 &&
	test_cmp_numbers full got3 0 &&
	user reflect-shade -fa -m ratio rgb >out 2>/dev/null &&
	data out | cut -f7 >got &&
	printf "%s\n" 0.353553 0.5 0.8 0 >expect &&
	test_cmp_numbers expect got 1e-6 &&
	user reflect-info --plugins >out &&
	tab=$(printf "\t") &&
	test_grep "^  $u${tab}the user plugin directory$" out &&
	test_grep "^projection${tab}sphere${tab}$u/sphere\.so${tab}the user plugin directory$" out &&
	test_grep "^shade${tab}taps${tab}$u/taps\.so${tab}the user plugin directory$" out &&
	test_grep "^projection${tab}box${tab}.*/lib/reflect-1/projection-box\.so${tab}the installed plugin directory$" out
'

# The modes installed with reflect: their man pages in the prefix's man7.
test_expect_success '-m MODE --help names an installed mode.s installed man page' '
	user reflect-shade -m approx --help >out &&
	test_grep "^  found in: the installed plugin directory$" out &&
	test_grep "^  man page: $prefix/share/man/man7/reflect-mode-approx\.7$" out &&
	user reflect-occlude -m box --help >out &&
	test_grep "^  man page: $prefix/share/man/man7/reflect-mode-occlusion-box\.7$" out &&
	user reflect-project -m box --help >out &&
	test_grep "^  man page: $prefix/share/man/man7/reflect-mode-box\.7$" out
'

# taps reads the GGX-prefiltered chain: a tap standing for a quarter of
# the lobe's median cone (half-angle atan alpha) reads at the lod of the
# lobe whose cone is half as wide, roughness_to_lod(sqrt(tan(atan(alpha)
# / 2))).  Under a sky whose every level is one value (level k: k + 1),
# what a read at a lod gives is what mode none gives at that lod's
# roughness: taps at r equals none at r' = sqrt(tan(atan(r^2) / 2)).
# (The rule of texel sizes read levels 0.3 to 1.7 finer or coarser.)
test_expect_success 'taps reads each tap at the lod of its share of the lobe' '
	awk "BEGIN { n = 8; for (k = 0; k < 4; k++) {
		printf \"#?REFLECT1\\nENVMAP=CUBE\\nLEVEL=%d\\nLEVELS=4\\nPREFILTER=ggx\\n\", k
		printf \"MAPPING=unity\\nSTEPS=3\\nNCOLS=%d\\nNROWS=%d\\n\", n, 6 * n
		printf \"NCOMP=3\\nCHANNELS=R G B\\nFORMAT=ascii\\n\\n\"
		for (j = 0; j < 6 * n * n; j++) print k + 1, k + 1, k + 1
		n = n / 2 } }" >levels.rfl &&
	for r in 0.2 0.45 0.7 1
	do
		printf "%s\t1\t2\t0.6\t0.8\t0\n" $r || return 1
	done >rows &&
	{ sed -n 1,7p mirror && cat rows; } >lobes &&
	awk -F "\t" "{ a = \$1 * \$1; printf \"%.9g\\t1\\t2\\t0.6\\t0.8\\t0\\n\", sqrt(sin(atan2(a, 1) / 2) / cos(atan2(a, 1) / 2)) }" rows >narrow &&
	{ sed -n 1,7p mirror && cat narrow; } >shares &&
	shade -fa -m taps --env=levels.rfl lobes >t.txt 2>/dev/null &&
	shade -fa -m none --env=levels.rfl shares >n.txt 2>/dev/null &&
	data t.txt | cut -f7-9 >a &&
	data n.txt | cut -f8-10 >b &&
	test_cmp_numbers b a 1e-5 &&
	# and those are between the levels, not at one
	cut -f1 a >lods &&
	awk "\$1 <= 1.001 || \$1 >= 3.999 { bad = 1 } END { exit bad }" lods
'

test_expect_success 'clean up the out-of-tree directory' '
	rm -rf "$oot"
'

# The installed tools with nothing set: libreflect through their $ORIGIN
# run path, the plugins and the image module beside the library, in the
# prefix given to make install (not the configured one) and after the
# whole tree has moved.
test_expect_success 'an installed tree runs where it lies, and moved' '
	mv "$prefix" moved &&
	clean="env -u LD_LIBRARY_PATH -u REFLECT_PLUGIN_PATH -u REFLECT_PLUGIN_SYSTEM_PATH" &&
	$clean moved/bin/reflect-gbuffer -x 8 -y 6 >g.rfl &&
	$clean moved/bin/reflect-project -v g.rfl >p.rfl 2>err &&
	test_grep "mode .box. from .$PWD/moved/bin/../lib/reflect-1/projection-box.so." err &&
	$clean moved/bin/reflect-shade --final p.rfl >s.rfl 2>/dev/null &&
	if test -f moved/lib/reflect/reflect-oiio.so
	then
		$clean moved/bin/reflect-export -o s.tif s.rfl &&
		test -s s.tif
	fi &&
	mv moved "$prefix"
'

test_done
