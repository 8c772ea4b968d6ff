#!/bin/sh
test_description='-l lists the modes; -m finds them along the search path; -v names the file'
. "$srcdir/tests/lib.sh"

B=$builddir/plugins/.libs
P=$REFLECT_TEST_PLUGINS
tab=$(printf '\t')
sq="'"

test_expect_success 'setup: a G-buffer and directories of plugins' '
	cat >gbuf <<-\EOF &&
	#?REFLECT1
	NCOLS=1
	NROWS=1
	NCOMP=9
	CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z
	PROBE_BOX=-1 -1 -1 1 1 1
	FORMAT=ascii

	0	0	0	0	1	0	0	1	0
	EOF
	mkdir a b empty "we:ird" &&
	cp "$B/projection-box.so" a/ &&
	cp "$B/projection-box.so" "$B/projection-infinite.so" b/ &&
	cp "$B/projection-box.so" "we:ird/"
'

test_expect_success '-l lists bevel, box and infinite: summary, file, channels' '
	reflect-project -l >out 2>err &&
	test_line_count 0 err &&
	# a build tree from before the files were KIND-NAME.so keeps
	# NAME.so beside them, which -l lists as shadowed
	grep -v "^# " out >listed &&
	cat >expect <<-EOF &&
	bevel${tab}box projection onto the probe box with its edges and corners rounded
	  file: $B/projection-bevel.so (version 1.0, plugin ABI 1.3, reflect developers, MIT)
	  found in: REFLECT_PLUGIN_PATH
	  reads: P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z
	  reads when present: roughness
	  writes: R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist
	  parameters:
	    radius=0.5${tab}rounding radius of the box${sq}s edges and corners, world units ([0, inf))
	    offset=0${tab}grow the rounded box beyond the probe box (the write-up${sq}s shape) instead of keeping its faces on it (0 or 1)
	    roughen=0${tab}radius added per width of the lobe at the hit (0: a fixed radius) ([0, inf))
	  man page: none beside the file (reflect-plugin(7) says where one goes)
	box${tab}box projection: look up where the reflected ray leaves the probe box
	  file: $B/projection-box.so (version 1.0, plugin ABI 1.3, reflect developers, MIT)
	  found in: REFLECT_PLUGIN_PATH
	  reads: P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z
	  writes: R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist
	  man page: none beside the file (reflect-plugin(7) says where one goes)
	infinite${tab}no parallax: look up the reflection vector itself (distant environment)
	  file: $B/projection-infinite.so (version 1.0, plugin ABI 1.3, reflect developers, MIT)
	  found in: REFLECT_PLUGIN_PATH
	  reads: N.X N.Y N.Z V.X V.Y V.Z
	  writes: R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist
	  man page: none beside the file (reflect-plugin(7) says where one goes)
	EOF
	diff -u expect listed
'

test_expect_success '-l lists parameters with default, help and range' '
	REFLECT_PLUGIN_PATH="$P" reflect-project -l >out 2>err &&
	awk -v t="$tab" "\$0 ~ \"^echo_params\" t { on = 1; print; next }
		on && /^[^ ]/ { on = 0 } on" out >echo &&
	cat >expect <<-EOF &&
	echo_params${tab}test: echoes its parameters into its output channels
	  file: $P/echo_params.so (version 1.0, plugin ABI 1.3, reflect tests, MIT)
	  found in: REFLECT_PLUGIN_PATH
	  reads: N.X
	  writes: echo.scale echo.offset echo.count echo.invert echo.shape echo.nx echo.y echo.frame
	  parameters:
	    scale=1${tab}a number with a range ([0.5, 4])
	    offset=0${tab}a number without bounds ((-inf, inf))
	    count=3${tab}an integer (integer [1, 8])
	    invert=0${tab}a switch (0 or 1)
	    shape=round${tab}a choice; fail makes create fail (round|square|fail)
	  man page: none beside the file (reflect-plugin(7) says where one goes)
	EOF
	diff -u expect echo
'

test_expect_success '-l warns about every broken plugin and lists the rest' '
	REFLECT_PLUGIN_PATH="$P:$B" reflect-project -l >out 2>err &&
	for p in bad_major bad_minor bad_size bad_name \
		bad_param_flags bad_flags no_summary radiance_projection flags_abi_1_0 \
		radiance_no_spec shade_no_roughness bad_optional accumulate_channels \
		bad_param_range bad_param_name shade_both filter_outputs_abi_1_2
	do
		test_grep "^reflect-project: ignoring plugin .$P/$p\.so.: " err ||
		return 1
	done &&
	# what a plugin prints while it is listed goes to stderr, never
	# into the listing
	test_grep "^print_stdout: loaded$" err &&
	! grep "print_stdout: loaded" out &&
	test_line_count 19 err &&
	! grep "no_entry\|not_plugin" err &&
	test_grep "^box$tab" out &&
	test_grep "^infinite$tab" out &&
	test_grep "^echo_params$tab" out
'

test_expect_success '-l passes over a library that is no plugin, never loading it' '
	mkdir lib &&
	cp "$B/projection-box.so" "$REFLECT_TEST_PLUGINS/not_plugin.so" lib/ &&
	cp "$REFLECT_TEST_PLUGINS/not_plugin.so" lib/infinite.so &&
	REFLECT_PLUGIN_PATH="$PWD/lib" REFLECT_PLUGIN_SYSTEM_PATH= reflect-project -l >out 2>err &&
	test_line_count 0 err &&
	grep "^[a-z_]*$tab" out >names &&
	test_line_count 1 names &&
	test_grep "^box$tab" out &&
	! grep "not_plugin\|infinite" out
'

test_expect_success '-m passes over a library of its name for a plugin after it' '
	REFLECT_PLUGIN_PATH="$PWD/lib:$B" reflect-project -v -m infinite <gbuf >/dev/null 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .infinite. from .$B/projection-infinite\.so.$" err &&
	test_expect_code 1 env REFLECT_PLUGIN_PATH="$PWD/lib" REFLECT_PLUGIN_SYSTEM_PATH= \
		reflect-project -m infinite <gbuf >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .$PWD/lib/infinite\.so.: not a reflect plugin, it exports no rf_plugin_entry()" err
'

test_expect_success '-l warns about a truncated plugin, lists the rest, exit 0' '
	mkdir cut &&
	size=$(wc -c <"$B/projection-infinite.so") &&
	head -c $((size / 2)) "$B/projection-infinite.so" >cut/projection-infinite.so &&
	cp "$B/projection-box.so" cut/ &&
	REFLECT_PLUGIN_PATH="$PWD/cut" REFLECT_PLUGIN_SYSTEM_PATH= reflect-project -l >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: ignoring plugin .$PWD/cut/projection-infinite\.so.: not a whole shared object: $((size / 2)) bytes, its headers need [0-9]* " err &&
	test_grep "^box$tab" out &&
	! grep "^infinite$tab" out
'

test_expect_success '-l: modes of another kind are left out silently' '
	REFLECT_PLUGIN_PATH="$P:$B" reflect-project -l >out 2>err &&
	! grep shade_kind out &&
	! grep shade_kind err &&
	grep -c "^[a-z_]*$tab" out >count &&
	echo 10 >expect &&
	diff expect count
'

test_expect_success '-l reports a shadowed duplicate and the file that wins' '
	REFLECT_PLUGIN_PATH="$PWD/a:$PWD/b" reflect-project -l >out 2>err &&
	test_line_count 0 err &&
	test_grep "^box$tab" out &&
	test_grep "^  file: $PWD/a/projection-box\.so " out &&
	test_grep "^# $PWD/b/projection-box\.so: shadowed by $PWD/a/projection-box\.so, earlier in the search path$" out &&
	test_grep "^  file: $PWD/b/projection-infinite\.so " out &&
	! grep "shadowed.*infinite" out
'

test_expect_success 'every mode of ours is the file KIND-NAME.so, -m takes NAME' '
	for t in project:projection shade:shade occlude:occlusion \
		accumulate:accumulate filter:filter
	do
		tool=${t%%:*} kind=${t#*:} &&
		reflect-$tool -l >out 2>err &&
		test_line_count 0 err &&
		awk -v t="$tab" "/^[a-z]/ { split(\$0, f, t); name = f[1] }
			/^  file: / { print name, \$2 }" out >modes &&
		test -s modes &&
		while read name file
		do
			test "$file" = "$B/$kind-$name.so" ||
			return 1
		done <modes ||
		return 1
	done &&
	reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$B/projection-box\.so.$" err
'

test_expect_success 'a plain NAME.so of the right kind is found, as plugins of others are named' '
	mkdir plain &&
	cp "$B/projection-box.so" plain/box.so &&
	REFLECT_PLUGIN_PATH="$PWD/plain" REFLECT_PLUGIN_SYSTEM_PATH= \
		reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .box. from .$PWD/plain/box\.so.$" err &&
	# an earlier directory wins, whichever of the two names it holds
	REFLECT_PLUGIN_PATH="$PWD/plain" REFLECT_PLUGIN_SYSTEM_PATH="$B" \
		reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$PWD/plain/box\.so.$" err &&
	REFLECT_PLUGIN_PATH="$PWD/plain" REFLECT_PLUGIN_SYSTEM_PATH="$B" \
		reflect-project -l >out 2>err &&
	test_line_count 0 err &&
	test_grep "^  file: $PWD/plain/box\.so " out &&
	test_grep "^# $B/projection-box\.so: shadowed by $PWD/plain/box\.so, earlier in the search path$" out
'

test_expect_success 'a mode of another kind is refused naming its tool' '
	test_expect_code 1 reflect-project -m horizon <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .$B/occlusion-horizon\.so.: it is a occlusion mode, not a projection mode; use it with reflect-occlude$" err
'

test_expect_success 'NAME.so beside KIND-NAME.so (an earlier install): KIND-NAME.so wins' '
	mkdir both &&
	cp "$B/projection-box.so" both/ &&
	cp "$B/projection-box.so" both/box.so &&
	REFLECT_PLUGIN_PATH="$PWD/both" REFLECT_PLUGIN_SYSTEM_PATH= \
		reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$PWD/both/projection-box\.so.$" err &&
	REFLECT_PLUGIN_PATH="$PWD/both" REFLECT_PLUGIN_SYSTEM_PATH= reflect-project -l >out 2>err &&
	test_line_count 0 err &&
	grep "^[a-z]" out >names &&
	test_line_count 1 names &&
	test_grep "^  file: $PWD/both/projection-box\.so " out &&
	test_grep "^# $PWD/both/box\.so: shadowed by $PWD/both/projection-box\.so, earlier in the search path$" out
'

test_expect_success 'NAME.so is not shadowed by KIND-NAME.so of another kind' '
	mkdir mixed &&
	cp "$B/occlusion-box.so" mixed/ &&
	cp "$B/projection-box.so" mixed/box.so &&
	REFLECT_PLUGIN_PATH="$PWD/mixed" REFLECT_PLUGIN_SYSTEM_PATH= \
		reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$PWD/mixed/box\.so.$" err &&
	REFLECT_PLUGIN_PATH="$PWD/mixed" REFLECT_PLUGIN_SYSTEM_PATH= reflect-project -l >out 2>err &&
	test_line_count 0 err &&
	test_grep "^  file: $PWD/mixed/box\.so " out &&
	! grep shadowed out &&
	REFLECT_PLUGIN_PATH="$PWD/mixed" REFLECT_PLUGIN_SYSTEM_PATH= reflect-occlude -l >out 2>err &&
	test_line_count 0 err &&
	test_grep "^  file: $PWD/mixed/occlusion-box\.so " out &&
	! grep shadowed out
'

test_expect_success '-l: a directory named twice does not shadow itself' '
	REFLECT_PLUGIN_PATH="$PWD/a:$PWD/a/.:$PWD/a" reflect-project -l >out 2>err &&
	test_line_count 0 err &&
	! grep shadowed out &&
	test_grep "^  file: $PWD/a/projection-box\.so " out
'

test_expect_success '-v: REFLECT_PLUGIN_PATH in order, the first match wins' '
	REFLECT_PLUGIN_PATH="$PWD/a:$PWD/b" reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .box. from .$PWD/a/projection-box\.so.$" err &&
	REFLECT_PLUGIN_PATH="$PWD/b:$PWD/a" reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$PWD/b/projection-box\.so.$" err &&
	REFLECT_PLUGIN_PATH="$PWD/a:$PWD/b" reflect-project -v -m infinite <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .infinite. from .$PWD/b/projection-infinite\.so.$" err
'

test_expect_success 'REFLECT_PLUGIN_SYSTEM_PATH comes after REFLECT_PLUGIN_PATH' '
	REFLECT_PLUGIN_PATH="$PWD/a" REFLECT_PLUGIN_SYSTEM_PATH="$PWD/b" \
		reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$PWD/a/projection-box\.so.$" err &&
	REFLECT_PLUGIN_PATH="$PWD/a" REFLECT_PLUGIN_SYSTEM_PATH="$PWD/b" \
		reflect-project -v -m infinite <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .infinite. from .$PWD/b/projection-infinite\.so.$" err &&
	REFLECT_PLUGIN_PATH= REFLECT_PLUGIN_SYSTEM_PATH="$PWD/b" \
		reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$PWD/b/projection-box\.so.$" err &&
	REFLECT_PLUGIN_PATH="$PWD/a" REFLECT_PLUGIN_SYSTEM_PATH="$PWD/b" \
		reflect-project -l >out &&
	test_grep "^# $PWD/b/projection-box\.so: shadowed by $PWD/a/projection-box\.so, earlier in the search path$" out
'

test_expect_success 'an empty REFLECT_PLUGIN_SYSTEM_PATH means no system directory' '
	test_expect_code 1 env REFLECT_PLUGIN_PATH="$PWD/empty" REFLECT_PLUGIN_SYSTEM_PATH= \
		reflect-project -m box <gbuf >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: unknown projection mode .box.: no projection-box\.so or box\.so in .$PWD/empty. (-l lists the modes)$" err &&
	test_expect_code 1 env REFLECT_PLUGIN_PATH= REFLECT_PLUGIN_SYSTEM_PATH= \
		reflect-project -m box <gbuf >out 2>err &&
	test_grep "^reflect-project: unknown projection mode .box.: no projection-box\.so or box\.so in an empty search path (-l lists the modes)$" err &&
	test_expect_code 1 env REFLECT_PLUGIN_PATH= REFLECT_PLUGIN_SYSTEM_PATH= \
		reflect-project -l >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: no projection modes in an empty search path$" err
'

test_expect_success 'an unset REFLECT_PLUGIN_SYSTEM_PATH means the installed plugin directory' '
	plugindir=$(pkg-config --variable=plugindir "$builddir/reflect-plugin.pc") &&
	test -n "$plugindir" &&
	(
		unset REFLECT_PLUGIN_SYSTEM_PATH &&
		test_expect_code 1 env REFLECT_PLUGIN_PATH="$PWD/empty" \
			reflect-project -m nosuch <gbuf >out 2>err
	) &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: unknown projection mode .nosuch.: no projection-nosuch\.so or nosuch\.so in .$PWD/empty:$plugindir. (-l lists the modes)$" err
'

test_expect_success 'a name with a slash is a path, not searched for' '
	REFLECT_PLUGIN_PATH="$PWD/empty" reflect-project -v -m a/projection-box.so <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .a/projection-box\.so.$" err &&
	REFLECT_PLUGIN_PATH="$PWD/empty" reflect-project -v -m "$PWD/b/projection-box.so" <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$PWD/b/projection-box\.so.$" err &&
	test_expect_code 1 env REFLECT_PLUGIN_PATH="$PWD/a" \
		reflect-project -m ./projection-box.so <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: cannot open plugin .\./projection-box\.so.: No such file or directory$" err
'

test_expect_success 'a path may hold a colon before its last slash' '
	REFLECT_PLUGIN_PATH="$PWD/empty" reflect-project -v -m "$PWD/we:ird/projection-box.so" <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$PWD/we:ird/projection-box\.so.$" err
'

test_expect_success 'NAME.so without a slash: not found, with a hint' '
	test_expect_code 1 reflect-project -m box.so <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: unknown projection mode .box\.so.: no projection-box\.so\.so or box\.so\.so in .$B.; a path to a file needs a ./., as in \./box\.so (-l lists the modes)$" err
'

test_expect_success 'an unknown mode: a clear message, exit 1' '
	test_expect_code 1 reflect-project -m nosuch <gbuf >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: unknown projection mode .nosuch.: no projection-nosuch\.so or nosuch\.so in .$B. (-l lists the modes)$" err &&
	test_expect_code 1 reflect-project -m "no such" <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: .no such. is not a valid mode name" err
'

test_expect_success 'a plugin directory anyone may write to is refused' '
	mkdir open &&
	cp "$B/projection-box.so" open/ &&
	chmod 777 open &&
	test_expect_code 1 env REFLECT_PLUGIN_PATH="$PWD/open" \
		reflect-project -m box <gbuf >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin directory .$PWD/open. in REFLECT_PLUGIN_PATH is writable by every user (mode 0777): anyone could put a plugin there; chmod o-w .$PWD/open., or take it out of REFLECT_PLUGIN_PATH$" err &&
	test_expect_code 1 env REFLECT_PLUGIN_PATH="$PWD/a" REFLECT_PLUGIN_SYSTEM_PATH="$PWD/open" \
		reflect-project -l >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin directory .$PWD/open. in REFLECT_PLUGIN_SYSTEM_PATH is writable by every user (mode 0777): " err &&
	# a path given to -m is the user.s own choice
	reflect-project -m "$PWD/open/projection-box.so" <gbuf >out 2>err &&
	test_line_count 0 err
'

test_expect_success 'a sticky directory anyone may write to is searched, like /tmp' '
	chmod 1777 open &&
	REFLECT_PLUGIN_PATH="$PWD/open" reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .box. from .$PWD/open/projection-box\.so.$" err &&
	chmod 755 open
'

test_expect_success 'a relative plugin directory is searched, with a warning' '
	REFLECT_PLUGIN_PATH="a" reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_line_count 2 err &&
	test_grep "^reflect-project: relative directory .a. in REFLECT_PLUGIN_PATH is searched from the current directory; give an absolute path$" err &&
	test_grep "^reflect-project: mode .box. from .a/projection-box\.so.$" err &&
	REFLECT_PLUGIN_PATH="$PWD/b" REFLECT_PLUGIN_SYSTEM_PATH="a" reflect-project -l >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: relative directory .a. in REFLECT_PLUGIN_SYSTEM_PATH is searched" err &&
	test_grep "^box$tab" out
'

test_expect_success '-v names the file and the parameter values' '
	REFLECT_PLUGIN_PATH="$P" reflect-project -v -m echo_params:shape=square:count=5 \
		<gbuf >/dev/null 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .echo_params. from .$P/echo_params\.so. (scale=1 offset=0 count=5 invert=0 shape=square)$" err
'

test_expect_success 'without -v nothing goes to stderr' '
	reflect-project -m box <gbuf >/dev/null 2>err &&
	test_line_count 0 err
'

# The user plugin directory, $XDG_DATA_HOME/reflect/plugins (else
# ~/.local/share/reflect/plugins), is searched last, when it exists.
test_expect_success 'the user plugin directory: searched after the others, by default' '
	mkdir -p xdg/reflect/plugins &&
	cp "$P/echo_params.so" xdg/reflect/plugins/ &&
	test_expect_code 1 env XDG_DATA_HOME="$PWD/nowhere" \
		reflect-project -m echo_params <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: unknown projection mode .echo_params.: no projection-echo_params\.so or echo_params\.so in .$B. (-l lists the modes)$" err &&
	XDG_DATA_HOME="$PWD/xdg" reflect-project -v -m echo_params <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .echo_params. from .$PWD/xdg/reflect/plugins/echo_params\.so. " err &&
	XDG_DATA_HOME="$PWD/xdg" reflect-project -l >out &&
	awk -v t="$tab" "\$0 ~ \"^echo_params\" t { on = 1; print; next }
		on && /^[^ ]/ { on = 0 } on" out >echo &&
	test_grep "^  file: $PWD/xdg/reflect/plugins/echo_params\.so " echo &&
	test_grep "^  found in: the user plugin directory$" echo
'

test_expect_success 'without XDG_DATA_HOME (or a relative one): ~/.local/share/reflect/plugins' '
	mkdir -p home/.local/share/reflect/plugins &&
	cp "$P/echo_params.so" home/.local/share/reflect/plugins/ &&
	(
		unset XDG_DATA_HOME &&
		HOME="$PWD/home" reflect-project -v -m echo_params <gbuf >/dev/null 2>err
	) &&
	test_grep "from .$PWD/home/.local/share/reflect/plugins/echo_params\.so. " err &&
	XDG_DATA_HOME=xdg HOME="$PWD/home" reflect-project -v -m echo_params \
		<gbuf >/dev/null 2>err &&
	test_grep "from .$PWD/home/.local/share/reflect/plugins/echo_params\.so. " err
'

# The first directory wins: a mode of the user's own never replaces an
# installed one of the same kind and name; -l says which file wins.
test_expect_success 'the user plugin directory shadows nothing before it' '
	cp "$B/projection-box.so" xdg/reflect/plugins/ &&
	XDG_DATA_HOME="$PWD/xdg" reflect-project -v -m box <gbuf >/dev/null 2>err &&
	test_grep "^reflect-project: mode .box. from .$B/projection-box\.so.$" err &&
	XDG_DATA_HOME="$PWD/xdg" reflect-project -l >out &&
	test_grep "^# $PWD/xdg/reflect/plugins/projection-box\.so: shadowed by $B/projection-box\.so, earlier in the search path$" out &&
	rm xdg/reflect/plugins/projection-box.so
'

test_expect_success 'a user plugin directory anyone may write to is refused' '
	mkdir -p open/reflect/plugins &&
	chmod 777 open/reflect/plugins &&
	test_expect_code 1 env XDG_DATA_HOME="$PWD/open" \
		reflect-project -m box <gbuf >/dev/null 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin directory .$PWD/open/reflect/plugins. in the user plugin directory is writable by every user (mode 0777)" err &&
	chmod 755 open/reflect/plugins
'

test_expect_success 'reflect-info --plugins: the search path, and where each mode was found' '
	XDG_DATA_HOME="$PWD/xdg" reflect-info --plugins >out 2>err &&
	test_line_count 0 err &&
	cat >expect <<-EOF &&
	search path, in order (a mode${sq}s first file wins):
	  $B${tab}REFLECT_PLUGIN_PATH
	  $PWD/xdg/reflect/plugins${tab}the user plugin directory
	modes (kind, name, file, where it was found):
	EOF
	head -n 4 out >head &&
	diff -u expect head &&
	test_grep "^projection${tab}box${tab}$B/projection-box\.so${tab}REFLECT_PLUGIN_PATH$" out &&
	test_grep "^shade${tab}approx${tab}$B/shade-approx\.so${tab}REFLECT_PLUGIN_PATH$" out &&
	test_grep "^projection${tab}echo_params${tab}$PWD/xdg/reflect/plugins/echo_params\.so${tab}the user plugin directory$" out &&
	XDG_DATA_HOME="$PWD/nowhere" reflect-info --plugins >out &&
	test_grep "^  $PWD/nowhere/reflect/plugins${tab}the user plugin directory (not there)$" out &&
	test_expect_code 1 reflect-info --plugins gbuf 2>err &&
	test_grep "^usage: reflect-info" err
'

test_done
