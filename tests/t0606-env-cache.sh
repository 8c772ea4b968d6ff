#!/bin/sh
test_description='reflect-shade keeps the environments it prefilters in a cache'
. "$srcdir/tests/lib.sh"

# every run of this test has a cache of its own
XDG_CACHE_HOME=$PWD/cache
export XDG_CACHE_HOME

body () {
	sed '1,/^$/d' "$1"
}

SQ="'"

test_expect_success 'setup: a frame, a raw environment, an empty cache' '
	reflect-gbuffer -x 16 -y 9 | reflect-project >g.rfl &&
	reflect-prefilter --size=32 --levels=2 --plain -o raw.rfl 2>/dev/null
'

# raw.rfl is a chain of plain levels: shading prefilters its level 0.
test_expect_success 'the second run reads the chain the first one made' '
	reflect-shade -m hdrp --env=raw.rfl g.rfl >one.rfl 2>err1 &&
	test_grep "prefiltering the environment" err1 &&
	ls cache/reflect/*.rfl >entries &&
	test_line_count 1 entries &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >two.rfl 2>err2 &&
	! test_grep prefiltering err2 &&
	body one.rfl >a && body two.rfl >b &&
	cmp a b
'

test_expect_success '--no-cache prefilters and keeps nothing; other settings are other entries' '
	reflect-shade -m hdrp --no-cache --env=raw.rfl g.rfl >nc.rfl 2>err &&
	test_grep "prefiltering the environment" err &&
	body nc.rfl >c && cmp a c &&
	ls cache/reflect/*.rfl >entries &&
	test_line_count 1 entries &&
	reflect-shade -m hdrp --samples=16 --env=raw.rfl g.rfl >/dev/null 2>err &&
	test_grep "prefiltering the environment" err &&
	ls cache/reflect/*.rfl >entries &&
	test_line_count 2 entries
'

test_expect_success 'an entry cut short is a miss, and is written again whole' '
	for f in cache/reflect/*.rfl
	do
		head -c 1000 "$f" >cut && mv cut "$f" || return 1
	done &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >three.rfl 2>err &&
	test_grep "prefiltering the environment" err &&
	test_grep "^reflect-shade: cache entry ${SQ}$PWD/cache/reflect/[0-9a-f]*.rfl${SQ}: .*; prefiltering ${SQ}raw.rfl${SQ} again$" err &&
	body three.rfl >d && cmp a d &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >four.rfl 2>err &&
	! test_grep prefiltering err
'

# put FILE OFFSET BYTES: writes the bytes (printf escapes) over FILE at
# OFFSET, the rest of FILE as it was.
put () {
	printf "$3" | dd of="$1" bs=1 seek="$2" conv=notrunc 2>/dev/null
}

# The entry of raw.rfl with -m hdrp's defaults, alone in the cache.
entry () {
	rm -rf cache &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >/dev/null 2>&1 &&
	ls "$PWD"/cache/reflect/*.rfl
}

# A damaged entry was read as it was: a NaN texel went into the shaded
# pixels with exit 0, and a wrong but finite one went unseen.  Now each
# is found, said once on stderr, and made again: the output is the
# fresh one's, and the next run reads the new entry.
test_expect_success 'an entry with a NaN, other texels or more bytes is made again' '
	e=$(entry) &&
	size=$(wc -c <"$e") &&
	# the last float: B of the 1x1 level of face -Z
	put "$e" $((size - 4)) "\000\000\300\177" &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >nan.rfl 2>err &&
	test_grep "^reflect-shade: cache entry ${SQ}$e${SQ}: level 5, face -Z, texel (0, 0): B is nan; prefiltering ${SQ}raw.rfl${SQ} again$" err &&
	body nan.rfl >d && cmp a d &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >/dev/null 2>err &&
	! test -s err &&
	put "$e" $((size - 4)) "\000\000\200\077" &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >one.rfl 2>err &&
	test_grep "${SQ}$e${SQ}: its texels do not add up to its CACHE_SUM; prefiltering" err &&
	body one.rfl >d && cmp a d &&
	printf "more" >>"$e" &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >more.rfl 2>err &&
	test_grep "${SQ}$e${SQ}: .*; prefiltering" err &&
	body more.rfl >d && cmp a d &&
	test $(wc -c <"$e") -eq $size
'

# The key is a hash of the texels: an edit in place that keeps the
# file's size and times is another entry.  And an entry is checked
# against the environment itself: one made for another environment and
# given this one's name (and key) is refused, its level 0 differing.
test_expect_success 'an entry is used only for its own environment' '
	e=$(entry) &&
	cp raw.rfl edited.rfl &&
	# the last float of level 0, before the header of level 1
	end=$(grep -a -b -o -F "#?REFLECT1" raw.rfl | sed -n 2p | cut -d: -f1) &&
	put edited.rfl $((end - 4)) "\000\000\040\101" &&
	! cmp -s raw.rfl edited.rfl &&
	test $(wc -c <edited.rfl) -eq $(wc -c <raw.rfl) &&
	touch -r raw.rfl edited.rfl &&
	reflect-shade -m hdrp --env=edited.rfl g.rfl >edited.out 2>err &&
	test_grep "prefiltering the environment" err &&
	ls "$PWD"/cache/reflect/*.rfl >entries &&
	test_line_count 2 entries &&
	other=$(grep -v "^$e$" entries) &&
	reflect-shade -m hdrp --no-cache --env=edited.rfl g.rfl >fresh.out 2>/dev/null &&
	body edited.out >x && body fresh.out >y && cmp x y &&
	! cmp -s a x &&
	# the entry of edited.rfl under the name and key of the first
	key=$(basename "$e" .rfl) &&
	cp "$other" "$e" &&
	for k in $(grep -a -b -o -F "CACHE_KEY=" "$e" | cut -d: -f1)
	do
		put "$e" $((k + 10)) "$key" || return 1
	done &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >swapped.rfl 2>err &&
	test_grep "${SQ}$e${SQ}: its level 0 is not the environment${SQ}s; prefiltering" err &&
	body swapped.rfl >d && cmp a d
'

test_expect_success 'writers at once leave one whole entry; the cap drops the oldest' '
	rm -rf cache &&
	{ reflect-shade -m none --env=raw.rfl g.rfl >p1.rfl 2>err1 & } &&
	p1=$! &&
	{ reflect-shade -m none --env=raw.rfl g.rfl >p2.rfl 2>err2 & } &&
	p2=$! &&
	s1=0 s2=0 &&
	{ wait $p1 || s1=$?; } &&
	{ wait $p2 || s2=$?; } &&
	if test "$s1 $s2" != "0 0"
	then
		echo "the writers exited $s1 and $s2" >&2 &&
		cat err1 err2 >&2 &&
		false
	fi &&
	body p1.rfl >e && body p2.rfl >f && cmp e f &&
	ls -A cache/reflect >all &&
	test_line_count 1 all &&
	reflect-shade -m none --env=raw.rfl g.rfl 2>err >/dev/null &&
	! test_grep prefiltering err &&
	sleep 1 &&
	REFLECT_CACHE_MB=0 reflect-shade -m none --samples=16 --env=raw.rfl g.rfl \
		>/dev/null 2>&1 &&
	find cache/reflect -name "*.rfl" >entries &&
	test_line_count 0 entries
'

test_done
