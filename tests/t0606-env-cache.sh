#!/bin/sh
test_description='reflect-shade keeps the environments it prefilters in a cache'
. "$srcdir/tests/lib.sh"

# every run of this test has a cache of its own
XDG_CACHE_HOME=$PWD/cache
export XDG_CACHE_HOME

body () {
	sed '1,/^$/d' "$1"
}

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
	body three.rfl >d && cmp a d &&
	reflect-shade -m hdrp --env=raw.rfl g.rfl >four.rfl 2>err &&
	! test_grep prefiltering err
'

test_expect_success 'writers at once leave one whole entry; the cap drops the oldest' '
	rm -rf cache &&
	reflect-shade -m none --env=raw.rfl g.rfl >p1.rfl 2>/dev/null &
	reflect-shade -m none --env=raw.rfl g.rfl >p2.rfl 2>/dev/null &
	wait &&
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
