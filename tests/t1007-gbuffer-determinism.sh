#!/bin/sh
test_description='the same bytes whatever the thread count'
. "$srcdir/tests/lib.sh"

# -h: the data alone, since each header carries its own command line.
test_expect_success 'default scene: -j1, -j2 and -j3 write the same bytes' '
	reflect-gbuffer -h -x 203 -y 97 -j1 >j1.rf &&
	reflect-gbuffer -h -x 203 -y 97 -j2 >j2.rf &&
	reflect-gbuffer -h -x 203 -y 97 -j3 >j3.rf &&
	cmp j1.rf j2.rf &&
	cmp j1.rf j3.rf
'

test_expect_success 'REFLECT_THREADS is the default thread count' '
	REFLECT_THREADS=2 reflect-gbuffer -h -x 203 -y 97 >env.rf &&
	cmp j1.rf env.rf
'

test_expect_success 'animated frames, normal maps and many threads' '
	reflect-gbuffer -h -x 64 -y 48 -n 3 --orbit=90 -j1 >a.rf &&
	reflect-gbuffer -h -x 64 -y 48 -n 3 --orbit=90 -j7 >b.rf &&
	cmp a.rf b.rf
'

test_expect_success 'several blocks of rows: the same bytes' '
	reflect-gbuffer -h -x 4000 -y 70 -j1 -c objid,depth,N >a.rf &&
	reflect-gbuffer -h -x 4000 -y 70 -j2 -c objid,depth,N >b.rf &&
	cmp a.rf b.rf
'

test_done
