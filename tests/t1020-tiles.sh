#!/bin/sh
test_description='--region and --tile: tiles joined by reflect-join are the full render, byte for byte'
. "$srcdir/tests/lib.sh"

# A frame of 61 rows: 3 bands of 20, 20 and 21 rows, 4 of 15, 15, 15 and
# 16 (--tile=I/N with N not dividing the height), and odd sizes besides.
W=90
H=61

# joined OUT FILE...: the tiles put together, headerless.
joined () {
	out=$1 &&
	shift &&
	reflect-join -h "$@" >"$out"
}

test_expect_success 'setup: the full renders of a scene with objects' '
	cat >s.scene <<-\EOF &&
	probe center 0 1.5 0 box -3 0 -2 3 3 2
	camera position -2.4 1.6 1.8 target 0.6 0.8 -1 fov 60
	sphere center 0 1 0 radius 0.5 roughness 0.2
	box min 1 0 -1.5 max 2 0.8 -0.5 roughness 0.05 metallic 1
	EOF
	reflect-prefilter -q --size=16 -o room.rfl 2>/dev/null &&
	reflect-gbuffer -x $W -y $H s.scene >g.rfl &&
	reflect-gbuffer -x $W -y $H -h s.scene >g.raw &&
	reflect-project g.rfl >p.rfl &&
	test $(wc -c <g.raw) -gt $((W * H * 4 * 10))
'

test_expect_success 'gbuffer: 3 and 4 bands of rows, joined in any order' '
	for i in 0 1 2
	do
		reflect-gbuffer -x $W -y $H --tile=$i/3 s.scene >b3-$i.rfl || return 1
	done &&
	grep -a -q "^REGION=0 20 90 61$" b3-1.rfl &&
	grep -a -q "^NROWS=21$" b3-2.rfl &&
	joined j3 b3-2.rfl b3-0.rfl b3-1.rfl &&
	cmp g.raw j3 &&
	for i in 0 1 2 3
	do
		reflect-gbuffer -x $W -y $H --tile=$i/4 s.scene >b4-$i.rfl || return 1
	done &&
	grep -a -q "^NROWS=16$" b4-3.rfl &&
	cat b4-3.rfl b4-1.rfl b4-0.rfl b4-2.rfl | reflect-join -h >j4 &&
	cmp g.raw j4
'

test_expect_success 'gbuffer: a grid of regions, and --supersample' '
	reflect-gbuffer -x $W -y $H --region=0,0,37,61 s.scene >r1.rfl &&
	reflect-gbuffer -x $W -y $H --region=37,0,90,29 s.scene >r2.rfl &&
	reflect-gbuffer -x $W -y $H --region=37,29,90,61 s.scene >r3.rfl &&
	grep -a -q "^REGION=37 29 90 61$" r3.rfl &&
	joined jr r3.rfl r1.rfl r2.rfl &&
	cmp g.raw jr &&
	reflect-gbuffer -x 30 -y 20 --supersample=2 -h s.scene >ss.raw &&
	reflect-gbuffer -x 30 -y 20 --supersample=2 --region=0,0,30,7 s.scene >ss1.rfl &&
	reflect-gbuffer -x 30 -y 20 --supersample=2 --region=0,7,30,20 s.scene >ss2.rfl &&
	grep -a -q "^REGION=0 14 60 40$" ss2.rfl &&
	joined jss ss1.rfl ss2.rfl &&
	cmp ss.raw jss &&
	# rows 6 to 12 of 20, 3 more each way from an even row: 2 to 15,
	# times 3 in the stream
	reflect-gbuffer -x 30 -y 20 --supersample=3 --tile=1/3 --halo=3 -c mask -fa s.scene \
		>ss3.txt &&
	grep -q "^REGION=0 6 90 60$" ss3.txt &&
	grep -q "^NROWS=42$" ss3.txt
'

test_expect_success 'trace: bands and a region, seeds and rays of the full frame' '
	reflect-trace -q -x 48 -y 31 --samples=8 --seed=3 -h s.scene >t.raw &&
	for i in 0 1 2
	do
		reflect-trace -q -x 48 -y 31 --samples=8 --seed=3 --tile=$i/3 s.scene \
			>t-$i.rfl || return 1
	done &&
	joined jt t-1.rfl t-0.rfl t-2.rfl &&
	cmp t.raw jt &&
	reflect-trace -q -x 48 -y 31 --samples=8 --seed=3 --region=0,0,17,31 s.scene >ta.rfl &&
	reflect-trace -q -x 48 -y 31 --samples=8 --seed=3 --region=17,0,48,31 s.scene >tb.rfl &&
	joined jt2 tb.rfl ta.rfl &&
	cmp t.raw jt2
'

# A stage given tiles passes REGION on and works on the full frame's
# pixel positions; given --tile or --region on a full stream it crops.
test_expect_success 'project: tiles through it, and its own --tile of the full stream' '
	reflect-project -h g.rfl >p.raw &&
	for i in 0 1 2
	do
		reflect-project b3-$i.rfl >pt-$i.rfl &&
		reflect-project --tile=$i/3 g.rfl >pc-$i.rfl || return 1
	done &&
	grep -a -q "^REGION=0 40 90 61$" pt-2.rfl &&
	joined jp pt-0.rfl pt-1.rfl pt-2.rfl &&
	cmp p.raw jp &&
	joined jpc pc-2.rfl pc-1.rfl pc-0.rfl &&
	cmp p.raw jpc
'

for m in approx footprint raytraced:samples=4:pattern=white raytraced:samples=4:pattern=blue
do
	test_expect_success "shade -m $m: tiles joined are the full frame" '
		reflect-shade -q -m $m --final --env=room.rfl -h p.rfl >s.raw &&
		for i in 0 1 2 3
		do
			reflect-shade -q -m $m --final --env=room.rfl --tile=$i/4 p.rfl \
				>st-$i.rfl || return 1
		done &&
		joined js st-3.rfl st-2.rfl st-1.rfl st-0.rfl &&
		cmp s.raw js
	'
done

# The noise is drawn from the pixel's place in the full frame: the same
# tile with its REGION taken out (so at the top left) draws other noise.
test_expect_success 'raytraced white noise: the tile'"'"'s offset is what seeds it' '
	reflect-shade -q -m raytraced:samples=4:pattern=white --env=room.rfl --tile=2/4 \
		-fa p.rfl >tile.txt &&
	grep -q "^REGION=0 30 90 61$" tile.txt &&
	grep -v "^REGION=" tile.txt >moved.txt &&
	reflect-shade -q -m raytraced:samples=4:pattern=white --env=room.rfl -h moved.txt \
		>moved.raw &&
	reflect-shade -q -m raytraced:samples=4:pattern=white --env=room.rfl -h tile.txt \
		>again.raw &&
	reflect-shade -q -m raytraced:samples=4:pattern=white --env=room.rfl --tile=2/4 -h \
		p.rfl >tile.raw &&
	test $(wc -c <moved.raw) -eq $(wc -c <tile.raw) &&
	! cmp -s moved.raw tile.raw
'

test_expect_success 'occlude: tiles of a shaded stream joined' '
	reflect-shade -q --final --env=room.rfl p.rfl >s.rfl &&
	reflect-occlude -h s.rfl >o.raw &&
	reflect-occlude --region=0,0,50,61 s.rfl >o1.rfl &&
	reflect-occlude --region=50,0,90,61 s.rfl >o2.rfl &&
	joined jo o2.rfl o1.rfl &&
	cmp o.raw jo
'

# a-trous with its 5 passes reads 2 + 4 + 8 + 16 + 32 = 62 pixels each
# way: a tile rendered with --halo=62 and filtered with --tile is the
# filtered full frame's; with less the filter says what halo it needs.
test_expect_success 'atrous: tiles made with a halo, filtered and cut, are the filtered frame' '
	reflect-shade -q -m raytraced:samples=4:pattern=white --final --env=room.rfl p.rfl \
		>n.rfl &&
	reflect-filter -q -h n.rfl >f.raw &&
	for i in 0 1 2
	do
		reflect-gbuffer -x $W -y $H --tile=$i/3 --halo=62 s.scene |
		reflect-project |
		reflect-shade -q -m raytraced:samples=4:pattern=white --final --env=room.rfl |
		reflect-filter -q --tile=$i/3 >f-$i.rfl || return 1
	done &&
	joined jf f-0.rfl f-2.rfl f-1.rfl &&
	cmp f.raw jf
'

test_expect_success 'atrous: narrow columns with a halo, and passes=2 with a halo of 6' '
	reflect-filter -q -m atrous:passes=2 -h n.rfl >f2.raw &&
	reflect-shade -q -m raytraced:samples=4:pattern=white --final --env=room.rfl \
		--region=20,0,70,61 --halo=6 p.rfl >mid.rfl &&
	grep -a -q "^REGION=14 0 90 61$" mid.rfl &&
	reflect-filter -q -m atrous:passes=2 --region=20,0,70,61 mid.rfl >c2.rfl &&
	reflect-filter -q -m atrous:passes=2 --region=0,0,20,61 n.rfl >c1.rfl &&
	reflect-filter -q -m atrous:passes=2 --region=70,0,90,61 n.rfl >c3.rfl &&
	joined jf2 c3.rfl c1.rfl c2.rfl &&
	cmp f2.raw jf2 &&
	reflect-filter -q -m atrous:passes=2 -h mid.rfl >whole.raw &&
	! cmp -s f2.raw whole.raw
'

# quad pairs rows 2k and 2k + 1: a halo starts on an even row, so that
# band 1 (from row 20, its halo of 1 from row 18) pairs as the frame.
test_expect_success 'quad: tiles with a halo of 1 are the filtered frame' '
	reflect-filter -q -m quad -h n.rfl >q.raw &&
	for i in 0 1 2
	do
		reflect-shade -q -m raytraced:samples=4:pattern=white --final --env=room.rfl \
			--tile=$i/3 --halo=1 p.rfl >qh-$i.rfl &&
		reflect-filter -q -m quad --tile=$i/3 qh-$i.rfl >q-$i.rfl || return 1
	done &&
	grep -a -q "^REGION=0 18 90 61$" qh-1.rfl &&
	joined jq q-2.rfl q-0.rfl q-1.rfl &&
	cmp q.raw jq
'

test_expect_success 'atrous: a halo too short is refused with the one it needs' '
	reflect-gbuffer -x $W -y $H --tile=1/3 --halo=10 s.scene | reflect-project |
	reflect-shade -q --env=room.rfl >short.rfl &&
	test_expect_code 1 reflect-filter -q --tile=1/3 short.rfl >out 2>err &&
	test_one_line_message reflect-filter err &&
	test_grep "make it with --halo=62" err &&
	test_grep "reads 62 pixels" err
'

test_expect_success 'bad regions and tiles are refused, naming the option' '
	test_expect_code 1 reflect-gbuffer -x $W -y $H --region=0,0,91,10 s.scene >out 2>err &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "past the frame.s 90x61 pixels" err &&
	test_expect_code 1 reflect-gbuffer -x $W -y $H --region=5,5,5,9 s.scene >out 2>err &&
	test_grep "holds no pixel" err &&
	test_expect_code 1 reflect-trace -x $W -y $H --region=1,2,3 s.scene >out 2>err &&
	test_grep "expected X0,Y0,X1,Y1" err &&
	test_expect_code 1 reflect-trace -x $W -y $H --tile=3/3 s.scene >out 2>err &&
	test_grep "no band 3 of 3" err &&
	test_expect_code 1 reflect-gbuffer -x $W -y $H --tile=0/62 s.scene >out 2>err &&
	test_grep "N at most 61" err &&
	test_expect_code 1 reflect-gbuffer -x $W -y $H --tile=1/0 s.scene >out 2>err &&
	test_grep "expected I/N" err &&
	test_expect_code 1 reflect-project --tile=0/2 --region=0,0,1,1 g.rfl >out 2>err &&
	test_grep "give one of them" err &&
	test_expect_code 1 reflect-project --region=0,0,10,30 b3-0.rfl >out 2>err &&
	test_one_line_message reflect-project err &&
	test_grep "holds pixels 0,0,90,20 of a 90x61 frame, not all of the region" err
'

test_expect_success 'join refuses overlaps, gaps and tiles that do not match' '
	test_expect_code 1 reflect-join b3-0.rfl b3-1.rfl b3-1.rfl >out 2>err &&
	test_one_line_message reflect-join err &&
	test_grep "overlaps" err &&
	test_expect_code 1 reflect-join b3-0.rfl b4-1.rfl b3-2.rfl >out 2>err &&
	test_grep "overlaps" err &&
	test_expect_code 1 reflect-join b3-0.rfl b3-2.rfl >out 2>err &&
	test_one_line_message reflect-join err &&
	test_grep "no tile holds pixel 0,20 of the 90x61 frame" err &&
	test_expect_code 1 reflect-join b3-0.rfl pt-1.rfl pt-2.rfl >out 2>err &&
	test_grep "other channels than" err &&
	reflect-gbuffer -x 40 -y $H --tile=1/3 s.scene >narrow.rfl &&
	test_expect_code 1 reflect-join b3-0.rfl narrow.rfl >out 2>err &&
	test_grep "tile of a 40x61 frame" err &&
	test_expect_code 1 reflect-join b3-0.rfl b3-1.rfl b3-2.rfl b3-2.rfl >out 2>err &&
	test_grep "a tile too many" err
'

test_expect_success 'join: frames of an animation, each put together' '
	reflect-gbuffer -x 30 -y 20 -n 3 --orbit=30 -h s.scene >anim.raw &&
	reflect-gbuffer -x 30 -y 20 -n 3 --orbit=30 --tile=0/2 s.scene >a0.rfl &&
	reflect-gbuffer -x 30 -y 20 -n 3 --orbit=30 --tile=1/2 s.scene >a1.rfl &&
	joined ja a0.rfl a1.rfl &&
	cmp anim.raw ja &&
	reflect-join a1.rfl a0.rfl >anim.rfl &&
	test $(grep -a -c "^NCOLS=30$" anim.rfl) -eq 3 &&
	test $(grep -a -c "^NROWS=20$" anim.rfl) -eq 3 &&
	test "$(grep -a "^FRAME=" anim.rfl | tr "\n" " ")" = "FRAME=0 FRAME=1 FRAME=2 " &&
	! grep -a -q "^REGION=" anim.rfl
'

# accumulate: frames of raytraced white noise (another draw each
# frame), accumulated in tiles two ways, given tiles and cutting them
# itself, and the mean with its standard errors and the ema of the
# full frames
test_expect_success 'accumulate: tiles of the frames joined are the accumulated frame' '
	reflect-gbuffer -x 30 -y 20 -n 3 s.scene | reflect-project |
		reflect-shade -q --env=room.rfl -m raytraced:samples=2:animate=1:pattern=white \
		>fr.rfl &&
	for m in mean ema
	do
		reflect-accumulate -h -m $m --stats fr.rfl >acc.raw &&
		reflect-accumulate -m $m --stats --tile=0/3 fr.rfl >t0.rfl &&
		reflect-accumulate -m $m --stats --tile=2/3 fr.rfl >t2.rfl &&
		reflect-accumulate -m $m --stats --region=0,6,30,13 fr.rfl >t1.rfl &&
		joined jacc t2.rfl t1.rfl t0.rfl &&
		cmp acc.raw jacc || return 1
	done &&
	for t in 0 1
	do
		reflect-gbuffer -x 30 -y 20 -n 3 --tile=$t/2 s.scene | reflect-project |
		reflect-shade -q --env=room.rfl -m raytraced:samples=2:animate=1:pattern=white |
		reflect-accumulate -m mean >b$t.rfl || return 1
	done &&
	reflect-accumulate -h -m mean fr.rfl >acc.raw &&
	joined jb b1.rfl b0.rfl &&
	cmp acc.raw jb
'

test_expect_success 'a stream without REGION reads and writes as before' '
	reflect-project -fa g.rfl >plain.txt &&
	! grep -q "^REGION=" plain.txt &&
	reflect-join g.rfl >whole.rfl &&
	reflect-join -h g.rfl >whole.raw &&
	cmp g.raw whole.raw
'

test_done
