#!/bin/sh
test_description='-m mode:key=value: values reach the plugin, bad ones are refused clearly'
. "$srcdir/tests/lib.sh"

P=$REFLECT_TEST_PLUGINS
tab=$(printf "\t")
export REFLECT_PLUGIN_PATH="$P:$REFLECT_PLUGIN_PATH"

# Channels of echo_params, after the input's P.X N.X:
#   echo.scale echo.offset echo.count echo.invert echo.shape (the values
#   create() got), echo.nx = N.X * scale + offset, echo.y (the span's row),
#   echo.frame (the span's frame).
data () {
	awk '/^#\?REFLECT1$/ { h = 1; next } h && /^$/ { h = 0; next } !h' "$1"
}

# refused SPEC REGEX: -m SPEC exits 1 with one line matching REGEX and
# writes nothing on stdout.
refused () {
	test_expect_code 1 reflect-project -fa -m "$1" <gbuf >out 2>err &&
	test_line_count 0 out &&
	test_one_line_message reflect-project err &&
	test_grep "^reflect-project: $2$" err
}

test_expect_success 'setup: a G-buffer of two frames' '
	cat >gbuf <<-\EOF
	#?REFLECT1
	NCOLS=2
	NROWS=2
	NCOMP=2
	CHANNELS=P.X N.X
	FORMAT=ascii

	9	0.5
	9	-1
	9	2
	9	0
	#?REFLECT1
	NCOLS=1
	NROWS=1
	NCOMP=2
	CHANNELS=N.X P.X
	FRAME=7
	FORMAT=ascii

	4	8
	EOF
'

test_expect_success 'defaults reach the plugin' '
	reflect-project -fa -m echo_params <gbuf >out &&
	test_grep "^CHANNELS=P.X N.X echo.scale echo.offset echo.count echo.invert echo.shape echo.nx echo.y echo.frame$" out &&
	test_grep "^CHANNELS=N.X P.X echo.scale" out &&
	test_grep "^PROJECTION=echo_params$" out &&
	data out >got &&
	cat >expect <<-\EOF &&
	9  0.5  1 0 3 0 0   0.5  0 0
	9  -1   1 0 3 0 0   -1   0 0
	9  2    1 0 3 0 0   2    1 0
	9  0    1 0 3 0 0   0    1 0
	4  8    1 0 3 0 0   4    0 7
	EOF
	test_cmp_numbers expect got
'

test_expect_success 'a value of every type reaches the plugin' '
	reflect-project -fa -m echo_params:scale=2.5:offset=-7.25:count=8:invert=on:shape=square \
		<gbuf >out &&
	test_grep "^PROJECTION=echo_params:scale=2.5:offset=-7.25:count=8:invert=on:shape=square$" out &&
	data out >got &&
	cat >expect <<-\EOF &&
	9  0.5  2.5 -7.25 8 1 1   -6     0 0
	9  -1   2.5 -7.25 8 1 1   -9.75  0 0
	9  2    2.5 -7.25 8 1 1   -2.25  1 0
	9  0    2.5 -7.25 8 1 1   -7.25  1 0
	4  8    2.5 -7.25 8 1 1   2.75   0 7
	EOF
	test_cmp_numbers expect got
'

test_expect_success 'bounds are inclusive; bools by word; a choice by name' '
	reflect-project -fa -m echo_params:scale=4:count=8:invert=yes:shape=round:offset=1e3 \
		<gbuf >out &&
	data out | sed -n 1p >got &&
	echo "9 0.5 4 1000 8 1 0 1002 0 0" >expect &&
	test_cmp_numbers expect got &&
	reflect-project -fa -m echo_params:scale=0.5:count=1:invert=off \
		<gbuf >out &&
	data out | sed -n 1p >got &&
	echo "9 0.5 0.5 0 1 0 0 0.25 0 0" >expect &&
	test_cmp_numbers expect got
'

test_expect_success 'parameters after a path' '
	reflect-project -fa -m "$P/echo_params.so:count=2" <gbuf >out &&
	data out | sed -n 1p >got &&
	echo "9 0.5 1 0 2 0 0 0.5 0 0" >expect &&
	test_cmp_numbers expect got
'

test_expect_success 'an empty parameter (a stray colon) is refused, not ignored' '
	for spec in "echo_params:" "echo_params::count=2" "echo_params:count=2:" \
		"echo_params:count=2::gain=1"
	do
		test_expect_code 1 reflect-project -m "$spec" <gbuf >/dev/null 2>err &&
		test_one_line_message reflect-project err &&
		test_grep "colon\|:" err &&
		test_grep "no parameter after it\|empty parameter" err || return 1
	done
'

test_expect_success 'threads: every row gets its own values and its row number' '
	reflect-project -fa -j 2 -m echo_params:offset=1 <gbuf >out2 &&
	reflect-project -fa -j 1 -m echo_params:offset=1 <gbuf >out1 &&
	data out2 >got2 &&
	data out1 >got1 &&
	test_cmp_numbers got1 got2 &&
	cut -f 9 got2 >rows &&
	printf "%s\n" 0 0 1 1 0 >expect &&
	diff expect rows
'

test_expect_success 'unknown key: names it and lists the known ones' '
	refused echo_params:size=2 "mode .echo_params. has no parameter .size. (it has: scale, offset, count, invert, shape)" &&
	refused box:radius=1 "mode .box. has no parameter .radius. (it takes none)"
'

test_expect_success 'not a number: names the key, the range and the value' '
	refused echo_params:scale=big "mode .echo_params.: parameter .scale. needs a number (in \[0\.5, 4\]), not .big." &&
	refused echo_params:scale=2x "mode .echo_params.: parameter .scale. needs a number (in \[0\.5, 4\]), not .2x." &&
	refused echo_params:offset=nan "mode .echo_params.: parameter .offset. needs a number (any number), not .nan." &&
	refused echo_params:scale= "mode .echo_params.: parameter .scale. needs a number (in \[0\.5, 4\]), not .."
'

test_expect_success 'out of range: shows the allowed range' '
	refused echo_params:scale=5 "mode .echo_params.: parameter .scale. is 5, out of its range (in \[0\.5, 4\])" &&
	refused echo_params:scale=0.4999 "mode .echo_params.: parameter .scale. is 0\.4999, out of its range (in \[0\.5, 4\])" &&
	refused echo_params:count=9 "mode .echo_params.: parameter .count. is 9, out of its range (an integer in \[1, 8\])"
'

test_expect_success 'an integer parameter refuses a fraction' '
	refused echo_params:count=2.5 "mode .echo_params.: parameter .count. must be an integer in \[1, 8\], not 2\.5"
'

test_expect_success 'a bool refuses other words' '
	refused echo_params:invert=maybe "mode .echo_params.: parameter .invert. must be 0 or 1 (or off/on, no/yes, false/true), not .maybe."
'

test_expect_success 'a choice refuses what is not among its names' '
	refused echo_params:shape=oval "mode .echo_params.: parameter .shape. must be one of round|square|fail, not .oval." &&
	refused echo_params:shape=1 "mode .echo_params.: parameter .shape. must be one of round|square|fail, not .1."
'

test_expect_success 'a key without a value' '
	refused echo_params:scale "mode .echo_params.: parameter .scale. has no value (write scale=VALUE)" &&
	refused echo_params:count=2:invert "mode .echo_params.: parameter .invert. has no value (write invert=VALUE)"
'

test_expect_success 'a key given twice' '
	refused echo_params:count=2:count=2 "mode .echo_params.: parameter .count. is given twice"
'

test_expect_success 'create() fails: its message, on one line, exit 1' '
	refused echo_params:shape=fail "mode .echo_params.: shape=fail asked for a failure in create"
'

# A mode that gives up in run() (the host's fail(), plugin ABI 1.1): exit
# status 1 and its message on one line, at any thread count; the row the
# mode names is its own (counted from 1).
test_expect_success 'run() gives up: its message, one line, exit 1' '
	reflect-gbuffer -x 4 -y 6 >rows.rfl &&
	for j in 1 3
	do
		test_expect_code 1 reflect-project -j$j -m "$P/bail_at_row.so:row=2" <rows.rfl \
			>/dev/null 2>err &&
		test_one_line_message reflect-project err &&
		test_grep "frame 1, mode .bail_at_row.: row 3 is one it cannot take at all$" err ||
		return 1
	done &&
	reflect-project -m "$P/bail_at_row.so:row=999" <rows.rfl >/dev/null
'

# string_param: table=FILE's first number as echo.table, label's length
# as echo.label (default "abc": 3).
test_expect_success 'string parameters: defaults, given text, a file opened from the working directory' '
	reflect-project -fa -m string_param <gbuf >out &&
	data out | sed -n 1p | cut -f3,4 >got &&
	printf "0\t3\n" >expect &&
	diff expect got &&
	mkdir -p sub && echo 42.5 >sub/t.txt &&
	(cd sub && reflect-project -fa -m "string_param:table=t.txt:label=hello world" \
		<../gbuf >../out) &&
	data out | sed -n 1p | cut -f3,4 >got &&
	printf "42.5\t11\n" >expect &&
	diff expect got &&
	reflect-project -v -m string_param:label=x <gbuf 2>err >/dev/null &&
	test_grep "(table=.. label=.x.)" err
'

test_expect_success 'string parameters: the plugin reports what it could not load' '
	test_expect_code 1 reflect-project -m string_param:table=nope.txt <gbuf >/dev/null 2>err &&
	test_grep "string_param.*cannot open .nope.txt.: No such file or directory" err &&
	: >empty.txt &&
	test_expect_code 1 reflect-project -m string_param:table=empty.txt <gbuf >/dev/null 2>err &&
	test_grep "empty.txt.: no number in it" err
'

test_expect_success 'string parameters: -l shows them; ABI 1.0 may not have them' '
	reflect-project -l >list 2>/dev/null &&
	sed -n "/^string_param$tab/,/^[^ ]/p" list >sp &&
	test_grep "^    label=abc${tab}a text (a string)$" sp &&
	test_expect_code 1 reflect-project -m string_abi_1_0 <gbuf >/dev/null 2>err &&
	test_grep "built for plugin ABI 1.0, its parameter .table. sets flag bits 0x8 that this ABI does not define" err
'

test_done
