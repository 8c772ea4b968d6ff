#!/bin/sh
test_description='progress on standard error: plain lines with --progress, a line redrawn on a terminal, nothing with -q or elsewhere'
. "$srcdir/tests/lib.sh"

# A line of --progress: percent, where, elapsed and (before the end) ETA.
# Rows, or the files (import, montage) or steps (compare) of a tool
# whose run is no rows.
LINE='^reflect-[a-z]*: +[0-9]+%, (frame [0-9]+(/[0-9]+)?, )?(row|file|step|picture) [0-9]+/[0-9]+, [0-9]+:[0-9][0-9] elapsed(, ETA [0-9]+:[0-9][0-9])?$'

test_expect_success 'setup' '
	cat >s.scene <<-\EOF &&
	probe center 0 1.5 0 box -3 0 -2 3 3 2
	camera position 0 1.6 2 target 0 1 0 fov 50
	sphere center 0 1 0 radius 0.9 roughness 0.3
	EOF
	reflect-gbuffer -x 48 -y 30 -n 2 s.scene >g.rfl &&
	reflect-project g.rfl >p.rfl &&
	XDG_CACHE_HOME=$PWD/cache reflect-shade p.rfl >out 2>err &&
	test_grep "prefilter" err
'

# The shaded environment is prefiltered once, and said so; it is cached now.
XDG_CACHE_HOME=$PWD/cache
export XDG_CACHE_HOME

test_expect_success 'nothing on stderr without --progress when it is no terminal' '
	reflect-gbuffer -x 48 -y 30 -n 2 s.scene >out 2>err &&
	test ! -s err &&
	reflect-trace -x 48 -y 30 --samples=16 s.scene >out 2>err &&
	test ! -s err &&
	reflect-shade p.rfl >out 2>err &&
	test ! -s err &&
	reflect-gbuffer -x 48 -y 30 s.scene >g1.rfl &&
	reflect-export -c N -o n.exr g1.rfl &&
	reflect-export -c P -o p.exr g1.rfl &&
	reflect-import n.exr p.exr >i.rfl 2>err &&
	test ! -s err &&
	reflect-compare -fa -c N.X,N.Y,N.Z g1.rfl i.rfl >out 2>err &&
	test ! -s err &&
	reflect-montage -o m.png n=g1.rfl:N.X,N.Y,N.Z:vector p=i.rfl:P.Y 2>err &&
	test ! -s err
'

# The tools whose time is in reading and writing pictures, not rows,
# count what they read and write: reflect-import and reflect-montage
# each file and the output, reflect-compare A, B, the measure and (-o)
# the map.
test_expect_success 'import, compare and montage --progress: files and steps, the same output' '
	reflect-import -h n.exr p.exr >plain &&
	reflect-import -h --progress n.exr p.exr >out 2>err &&
	cmp plain out &&
	! grep -v -E "$LINE" err &&
	tail -n 1 err >last &&
	grep -E "^reflect-import: 100%, file 3/3, [0-9]+:[0-9][0-9] elapsed$" last &&
	reflect-compare -fa -c N.X,N.Y,N.Z g1.rfl i.rfl >plain &&
	reflect-compare --progress -fa -c N.X,N.Y,N.Z g1.rfl i.rfl >out 2>err &&
	cmp plain out &&
	! grep -v -E "$LINE" err &&
	tail -n 1 err >last &&
	grep -E "^reflect-compare: 100%, step 3/3, [0-9]+:[0-9][0-9] elapsed$" last &&
	reflect-compare --metric=flip -o plain.png -fa -c N.X,N.Y,N.Z g1.rfl i.rfl >plain &&
	reflect-compare --progress --metric=flip -o out.png -fa -c N.X,N.Y,N.Z g1.rfl i.rfl \
		>out 2>err &&
	cmp plain out &&
	cmp plain.png out.png &&
	tail -n 1 err >last &&
	grep -E "^reflect-compare: 100%, step 4/4, [0-9]+:[0-9][0-9] elapsed$" last &&
	reflect-montage --progress -o out.png n=g1.rfl:N.X,N.Y,N.Z:vector p=i.rfl:P.Y 2>err &&
	cmp m.png out.png &&
	! grep -v -E "$LINE" err &&
	tail -n 1 err >last &&
	grep -E "^reflect-montage: 100%, file 3/3, [0-9]+:[0-9][0-9] elapsed$" last &&
	# -q, last, silences them
	reflect-import --progress -q n.exr >out 2>err &&
	test ! -s err &&
	reflect-compare --progress -q -fa -c N.X,N.Y,N.Z g1.rfl i.rfl >out 2>err &&
	test ! -s err &&
	reflect-montage --progress -q -o out.png n=g1.rfl:N.X 2>err &&
	test ! -s err
'

# reflect-join reads its tiles' files whole, reflect-report reads and
# scores each picture in one call: they count files, and pictures and
# the page.
test_expect_success 'join and report --progress: files and pictures, the same output' '
	reflect-gbuffer -x 48 -y 30 --tile=0/2 s.scene >t0.rfl &&
	reflect-gbuffer -x 48 -y 30 --tile=1/2 s.scene >t1.rfl &&
	reflect-join -h t1.rfl t0.rfl >plain &&
	reflect-join -h --progress t1.rfl t0.rfl >out 2>err &&
	cmp plain out &&
	! grep -v -E "$LINE" err &&
	tail -n 1 err >last &&
	grep -E "^reflect-join: 100%, file 2/2, [0-9]+:[0-9][0-9] elapsed$" last &&
	reflect-export -c N -o n.png g1.rfl &&
	reflect-export -c P -o p.png g1.rfl &&
	reflect-report -o plain.html n.png p=p.png n=n.png &&
	reflect-report --progress -o out.html n.png p=p.png n=n.png 2>err &&
	cmp plain.html out.html &&
	! grep -v -E "$LINE" err &&
	tail -n 1 err >last &&
	grep -E "^reflect-report: 100%, picture 4/4, [0-9]+:[0-9][0-9] elapsed$" last &&
	reflect-join --progress -q t0.rfl t1.rfl >out 2>err &&
	test ! -s err &&
	reflect-report --progress -q -o out.html n.png p=p.png 2>err &&
	test ! -s err
'

test_expect_success 'gbuffer --progress: lines, the last at 100% of every frame, the same stream' '
	reflect-gbuffer -x 48 -y 30 -n 3 --orbit=30 -h s.scene >plain &&
	reflect-gbuffer -x 48 -y 30 -n 3 --orbit=30 --progress -h s.scene >out 2>err &&
	cmp plain out &&
	grep -E "$LINE" err &&
	! grep -v -E "$LINE" err &&
	tail -n 1 err >last &&
	grep -E "^reflect-gbuffer: 100%, frame 3/3, row 30/30, [0-9]+:[0-9][0-9] elapsed$" last
'

# With progress showing, trace computes in smaller blocks (a 32nd of a
# frame) to report more often: its rows must not depend on that.
test_expect_success 'trace --progress: the same bytes in smaller blocks' '
	reflect-trace -x 64 -y 64 --samples=16 -n 2 --orbit=20 -h s.scene >plain &&
	reflect-trace -x 64 -y 64 --samples=16 -n 2 --orbit=20 --progress -h s.scene >out 2>err &&
	cmp plain out &&
	tail -n 1 err >last &&
	grep -E "^reflect-trace: 100%, frame 2/2, row 64/64, " last
'

# reflect-capture tells its rows over every bounce, a face at a time:
# two bounces of 6 x 8 rows (--bounce-size) and one of 6 x 16, each probe
# of -p all a frame.
test_expect_success 'capture --progress: the rows of every bounce, the same cube' '
	cat >two.scene <<-\EOF &&
	probe center 0 1.5 0 box -3 0 -2 3 3 2
	probe center 1 1 0 box 0 0 -1 2 2 1
	sphere center 0 1 0 radius 0.5
	EOF
	reflect-capture -n 16 --bounces=2 --bounce-size=8 -p all -h -o plain%d.rfl two.scene &&
	reflect-capture -n 16 --bounces=2 --bounce-size=8 -p all -h -o out%d.rfl --progress \
		two.scene 2>err &&
	cmp plain1.rfl out1.rfl && cmp plain2.rfl out2.rfl &&
	tail -n 1 err >last &&
	grep -E "^reflect-capture: 100%, frame 2/2, row 192/192, [0-9]+:[0-9][0-9] elapsed$" last &&
	! grep -v -E "$LINE" err &&
	reflect-capture -n 16 -q two.scene >out 2>err &&
	test ! -s err
'

# reflect-accumulate's result, written after the last frame, is no
# frame of its own: two frames in, two counted.
test_expect_success 'the stream stages: frame by frame, as many as come' '
	reflect-project --progress g.rfl >out 2>err &&
	tail -n 1 err >last &&
	grep -E "^reflect-project: 100%, frame 2, row 30/30, " last &&
	reflect-shade --progress p.rfl >shaded 2>err &&
	tail -n 1 err >last &&
	grep -E "^reflect-shade: 100%, frame 2, row 30/30, " last &&
	reflect-occlude --progress shaded >out 2>err &&
	grep -E "^reflect-occlude: 100%, frame 2, row 30/30, " err &&
	reflect-accumulate --progress shaded >out 2>err &&
	tail -n 1 err >last &&
	grep -E "^reflect-accumulate: 100%, frame 2, row 30/30, " last &&
	! grep "frame 3" err &&
	reflect-filter --progress shaded >out 2>err &&
	grep -E "^reflect-filter: 100%, frame 2, row 30/30, " err &&
	reflect-export --progress -o "ex%d.png" shaded 2>err &&
	grep -E "^reflect-export: 100%, frame 2, row 30/30, " err &&
	test -s ex1.png
'

test_expect_success 'prefilter --progress: the texel rows of every level' '
	reflect-prefilter --size=32 -h -o plain.rfl &&
	reflect-prefilter --size=32 -h --progress -o out.rfl 2>err &&
	cmp plain.rfl out.rfl &&
	tail -n 1 err >last &&
	grep -E "^reflect-prefilter: 100%, row 186/186, " last
'

test_expect_success '-q silences, and the last of -q and --progress wins' '
	reflect-gbuffer -x 8 -y 8 --progress -q s.scene >out 2>err &&
	test ! -s err &&
	reflect-gbuffer -x 8 -y 8 -q --progress s.scene >out 2>err &&
	grep -E "^reflect-gbuffer: 100%" err &&
	rm -rf cache &&
	reflect-shade -q p.rfl >out 2>err &&
	test ! -s err &&
	test -d cache
'

# script(1) gives the tool a terminal and records what it writes there.
# A trace of about a second or more draws the line (only after a
# second), redraws it in place and erases it at the end.
if command -v script >/dev/null
then
	test_expect_success 'on a terminal: one line, redrawn in place and erased' '
		script -q -e -c "reflect-trace -x 160 -y 90 --samples=8192 -h s.scene >t.rfl" ts >/dev/null &&
		reflect-trace -x 160 -y 90 --samples=8192 -q -h s.scene >q.rfl &&
		cmp q.rfl t.rfl &&
		esc=$(printf "\033") &&
		cr=$(printf "\r") &&
		test_grep "${cr}${esc}\[Kreflect-trace: *[0-9]*%  row [0-9]*/90  " ts &&
		sed -n "2,\$p" ts | tr -d "\n" | grep -q "${cr}${esc}\[KScript done" &&
		! grep "reflect-trace: .*${cr}reflect" ts
	'

	test_expect_success 'on a terminal with -q: nothing' '
		script -q -e -c "reflect-trace -x 160 -y 90 --samples=8192 -q s.scene >t.rfl" ts >/dev/null &&
		! grep reflect-trace: ts
	'
else
	test_skip 'on a terminal: one line, redrawn in place and erased' 'script(1) is missing'
fi

test_done
