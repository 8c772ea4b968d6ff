#!/bin/sh
test_description='broken plugins are refused, each with a message naming the file, the versions and the fix'
. "$srcdir/tests/lib.sh"

P=$REFLECT_TEST_PLUGINS

# refused NAME REGEX: reflect-project refuses the test plugin NAME given
# as a path and given by name through REFLECT_PLUGIN_PATH: exit status 1,
# nothing on stdout, one line on stderr naming the file, whose rest
# matches REGEX; both ways give the same message.
refused () {
	test_expect_code 1 reflect-project -m "$P/$1.so" <gbuf >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin '$P/$1\.so': $2$" err &&
	test_expect_code 1 env REFLECT_PLUGIN_PATH="$P" \
		reflect-project -m "$1" <gbuf >out 2>err.name &&
	test_line_count 0 out &&
	cmp err err.name
}

test_expect_success 'setup: versions and a G-buffer' '
	reflect-project -V >version &&
	sed -n "s/^reflect-project (reflect) //p" version >release &&
	sed -n "s/^plugin ABI //p" version >abi &&
	test_line_count 1 release &&
	test "$(cat abi)" = 1.3 &&
	cat >gbuf <<-\EOF
	#?REFLECT1
	NCOLS=1
	NROWS=1
	NCOMP=9
	CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z
	FORMAT=ascii

	0	0	0	0	1	0	0	1	0
	EOF
'

test_expect_success 'the test plugins were built' '
	for p in bad_major bad_minor bad_size no_entry bad_name \
		bad_param_flags bad_flags no_summary shade_kind echo_params bad_optional
	do
		test -f "$P/$p.so" || return 1
	done
'

test_expect_success 'a good plugin loads both ways (the harness works)' '
	reflect-project -fa -m "$P/echo_params.so" <gbuf >out &&
	test_grep "^CHANNELS=.* echo.scale" out &&
	REFLECT_PLUGIN_PATH="$P" reflect-project -fa -m echo_params <gbuf >out &&
	test_grep "^CHANNELS=.* echo.scale" out
'

test_expect_success 'major version 2.0: names both versions, rebuild or remove' '
	rel=$(cat release) &&
	refused bad_major "built for plugin ABI 2\.0, but this reflect ($rel) supports ABI 1\.3; rebuild it against this reflect.s <reflect/plugin\.h>, or remove it"
'

test_expect_success 'newer minor 1.99: names both versions, upgrade or rebuild' '
	rel=$(cat release) &&
	refused bad_minor "built for plugin ABI 1\.99, newer than the ABI 1\.3 of this reflect ($rel); upgrade reflect, or rebuild the plugin against this reflect.s <reflect/plugin\.h>"
'

test_expect_success 'descriptor smaller than its ABI says: sizes and versions' '
	rel=$(cat release) &&
	refused bad_size "built for plugin ABI 1\.0, its descriptor is 20 bytes, less than the 120 bytes of that ABI (this reflect ($rel) supports ABI 1\.3); it was built with a wrong header: set size to sizeof(struct rf_plugin) from this reflect.s <reflect/plugin\.h> and rebuild it, or remove it"
'

test_expect_success 'no rf_plugin_entry: not a reflect plugin, how to define it' '
	refused no_entry "not a reflect plugin, it exports no rf_plugin_entry(); define it with RF_PLUGIN_DEFINE(descriptor) from <reflect/plugin\.h>, or remove the file from the plugin path"
'

test_expect_success 'name differs from the file: both names, rename the file or the name' '
	refused bad_name "its descriptor is named .other_name., but a plugin.s name must equal its file name; rename the file to .projection-other_name\.so. or .other_name\.so., or set the name to .bad_name."
'

test_expect_success 'unknown parameter flag bits: the bits, versions, allowed flags' '
	rel=$(cat release) &&
	refused bad_param_flags "built for plugin ABI 1\.3, its parameter .gain. sets flag bits 0x10 that this ABI does not define (this reflect ($rel) supports ABI 1\.3); use only RF_PARAM_INTEGER, RF_PARAM_BOOL, RF_PARAM_CHOICE and RF_PARAM_STRING and rebuild it"
'

test_expect_success 'unknown descriptor flags: the bits, versions, set them to 0' '
	rel=$(cat release) &&
	refused bad_flags "built for plugin ABI 1\.3, its descriptor sets flags 0x4 that ABI 1\.3 does not define (this reflect ($rel) supports ABI 1\.3); clear them and rebuild it"
'

test_expect_success 'an optional input that is also an input: which list, fix it' '
	refused bad_optional "its descriptor has no valid optional input list (NULL-terminated, names unique, none of them an input); fill it in and rebuild the plugin"
'

test_expect_success 'missing summary: which field, fill it in' '
	refused no_summary "its descriptor has no summary; fill it in and rebuild the plugin"
'

test_expect_success 'a shade plugin is not a projection mode: which tool takes it' '
	refused shade_kind "it is a shade mode, not a projection mode; use it with reflect-shade"
'

test_expect_success 'a real plugin under another file name is refused' '
	cp "$builddir/plugins/.libs/projection-box.so" mybox.so &&
	test_expect_code 1 reflect-project -m ./mybox.so <gbuf >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .\./mybox\.so.: its descriptor is named .box., but a plugin.s name must equal its file name; rename the file to .projection-box\.so. or .box\.so., or set the name to .mybox.$" err
'

test_expect_success 'a file that is not a shared object: said so, never loaded' '
	mkdir junk &&
	echo "not an ELF file" >junk/garbage.so &&
	test_expect_code 1 reflect-project -m junk/garbage.so <gbuf >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .junk/garbage\.so.: not a shared object (no ELF header)$" err &&
	test_expect_code 1 env REFLECT_PLUGIN_PATH="$PWD/junk" \
		reflect-project -m garbage <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .$PWD/junk/garbage\.so.: not a shared object (no ELF header)$" err
'

# A plugin cut short (a copy that ran out of room, a build that was
# killed): dlopen would map its segments past the end of the file and
# fault on them (SIGBUS, exit 135).  Cut at every part of the file.
test_expect_success 'a truncated plugin is refused with its size, never loaded' '
	mkdir cut &&
	size=$(wc -c <"$builddir/plugins/.libs/projection-box.so") &&
	for at in 40 100 2000 $((size / 2)) $((size - 100)) $((size - 1))
	do
		head -c $at "$builddir/plugins/.libs/projection-box.so" >cut/box.so &&
		test_expect_code 1 reflect-project -m cut/box.so <gbuf >out 2>err &&
		test_line_count 0 out &&
		test_one_line_message reflect-project err &&
		test_grep "^reflect-project: plugin .cut/box\.so.: not a whole shared object: $at bytes, its headers need [0-9]* (truncated when it was copied or built?)$" err ||
		return 1
	done
'

# Without section headers (e_shoff and e_shnum 0, as sstrip leaves a
# file) the dynamic symbols are found through PT_DYNAMIC and its hash
# table: such a plugin loads, such a library is still told apart.
test_expect_success 'a plugin without section headers: its symbols through PT_DYNAMIC' '
	mkdir nosec &&
	cp "$builddir/plugins/.libs/projection-infinite.so" nosec/infinite.so &&
	cp "$P/not_plugin.so" nosec/ &&
	for f in nosec/infinite.so nosec/not_plugin.so
	do
		printf "\000\000\000\000\000\000\000\000" |
		dd of=$f bs=1 seek=40 conv=notrunc 2>/dev/null &&
		printf "\000\000\000\000" | dd of=$f bs=1 seek=60 conv=notrunc 2>/dev/null ||
		return 1
	done &&
	reflect-project -v -m nosec/infinite.so <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: mode .infinite. from .nosec/infinite\.so.$" err &&
	test_expect_code 1 reflect-project -m nosec/not_plugin.so <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .nosec/not_plugin\.so.: not a reflect plugin, it exports no rf_plugin_entry()" err
'

test_expect_success 'a library that is no plugin is refused without running it' '
	test_expect_code 1 reflect-project -m "$P/not_plugin.so" <gbuf >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .$P/not_plugin\.so.: not a reflect plugin, it exports no rf_plugin_entry()" err
'

test_expect_success 'a plugin built for another machine is refused before dlopen' '
	cp "$builddir/plugins/.libs/projection-box.so" box.so &&
	# e_machine 183 (AArch64), or 62 (x86-64) when this is AArch64
	machine=$(od -An -tu2 -j18 -N2 box.so | tr -d " ") &&
	if test "$machine" = 183
	then
		printf "\076\000" | dd of=box.so bs=1 seek=18 conv=notrunc 2>/dev/null &&
		other=62
	else
		printf "\267\000" | dd of=box.so bs=1 seek=18 conv=notrunc 2>/dev/null &&
		other=183
	fi &&
	test_expect_code 1 reflect-project -m ./box.so <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .\./box\.so.: built for another machine (ELF machine $other, 64-bit little-endian), this reflect runs on ELF machine $machine, 64-bit little-endian; rebuild it here$" err
'

test_expect_success 'a missing file and a directory given as paths' '
	test_expect_code 1 reflect-project -m ./nosuch.so <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: cannot open plugin .\./nosuch\.so.: No such file or directory$" err &&
	mkdir dir.so &&
	test_expect_code 1 reflect-project -m ./dir.so <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .\./dir\.so.: not a regular file; give the path of a \.so file$" err
'

test_expect_success 'a refused plugin found first is not passed over for a later one' '
	mkdir first &&
	cp "$P/bad_major.so" first/box.so &&
	test_expect_code 1 env REFLECT_PLUGIN_PATH="$PWD/first:$builddir/plugins/.libs" \
		reflect-project -m box <gbuf >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: plugin .$PWD/first/box\.so.: built for plugin ABI 2\.0" err
'

# A plugin that needs a library that is gone: the loader's message, and
# the hint that ldd(1) tells which (only here, where it helps).
if command -v cc >/dev/null 2>&1
then
	test_expect_success 'a plugin whose library is missing: the message names ldd' '
		mkdir -p gone &&
		echo "int gone_answer(void) { return 42; }" >gone/gone.c &&
		echo "int gone_answer(void); int rf_plugin_entry(void) { return gone_answer(); }" \
			>gone/needs.c &&
		cc -fPIC -shared -o gone/libgone.so gone/gone.c &&
		cc -fPIC -shared -o gone/needs_gone.so gone/needs.c -Lgone -lgone &&
		rm gone/libgone.so &&
		test_expect_code 1 reflect-project -m gone/needs_gone.so <gbuf >out 2>err &&
		test_one_line_message reflect-project err &&
		test_grep "cannot load it: .*libgone\.so.*; ldd(1) on the plugin shows which library is missing$" err
	'
else
	test_skip 'a plugin whose library is missing' 'no cc'
fi

test_done
