#!/bin/sh
test_description='reflect-info -s: per-channel min, max, mean and NaN/Inf counts'
. "$srcdir/tests/lib.sh"

# stats FILE: the statistics lines of reflect-info -s output, one blank
# between fields: "frame channel min max mean nan inf".
stats () {
	awk '
	/^frame [0-9]*:$/ { frame = $2; sub(":", "", frame); on = 0; next }
	$1 == "channel" && $2 == "min" { on = 1; next }
	on { print frame, $1, $2, $3, $4, $5, $6 }' "$1"
}

test_expect_success 'known values, NaN and Inf, two frames' '
	cat >in.txt <<-\EOF &&
	#?REFLECT1
	NCOLS=2
	NROWS=2
	NCOMP=4
	CHANNELS=a b c d
	FORMAT=ascii

	1	nan	nan	-0.5
	2	-inf	nan	0.25
	3	5	nan	1e30
	4.5	-1	inf	-1e30

	#?REFLECT1
	NCOLS=3
	NROWS=1
	NCOMP=1
	CHANNELS=a
	FORMAT=ascii

	-7 7 0.1
	EOF
	reflect-info -s in.txt >out &&
	test_grep "^	channel  *min  *max  *mean  *nan  *inf$" out &&
	stats out >got &&
	cat >expect <<-\EOF &&
	1 a 1 4.5 2.625 0 0
	1 b -1 5 2 1 1
	1 c - - - 3 1
	1 d -1e+30 1e+30 -0.0625 0 0
	2 a -7 7 0.03333333 0 0
	EOF
	diff -u expect got
'

test_expect_success 'the header is printed before the statistics' '
	sed -n "1,/channel/p" out >head &&
	test_grep "^frame 1:$" head &&
	test_grep "^	CHANNELS=a b c d$" head &&
	test_grep "^	FORMAT=ascii$" head
'

test_expect_success 'the same figures from float data' '
	{
		printf "#?REFLECT1\nNCOLS=1\nNROWS=4\nNCOMP=2\nCHANNELS=u v\n" &&
		printf "BigEndian=1\nFORMAT=float\n\n" &&
		printf "\077\200\000\000\177\300\000\000" &&
		printf "\300\000\000\000\177\200\000\000" &&
		printf "\100\100\000\000\377\200\000\000" &&
		printf "\000\000\000\000\100\240\000\000"
	} >be.rf &&
	reflect-info -s be.rf >out &&
	stats out >got &&
	cat >expect <<-\EOF &&
	1 u -2 3 0.5 0 0
	1 v 5 5 5 1 2
	EOF
	diff -u expect got
'

# 1200000 values over several blocks of rows (a block is 4 MiB): the
# counts must add up across blocks.
test_expect_success 'counts over many blocks (headerless input)' '
	head -c 4800000 /dev/zero | tr "\000" "\377" >nan.raw &&
	reflect-info -s -H -x 2000 -y 600 -c v nan.raw >out &&
	stats out >got &&
	echo "1 v - - - 1200000 0" >expect &&
	diff -u expect got &&
	head -c 2400000 /dev/zero >zero.raw &&
	reflect-info -s -H -x 1000 -y 300 -c "x y" zero.raw >out &&
	stats out >got &&
	printf "1 x 0 0 0 0 0\n1 y 0 0 0 0 0\n" >expect &&
	diff -u expect got
'

test_expect_success 'a ramp: exact mean of many values' '
	awk "BEGIN {
		print \"#?REFLECT1\"; print \"NCOLS=100\"; print \"NROWS=100\"
		print \"NCOMP=1\"; print \"CHANNELS=ramp\"; print \"FORMAT=ascii\"
		print \"\"
		for (i = 0; i < 10000; i++) print i
	}" >ramp.txt &&
	reflect-info -s ramp.txt >out &&
	stats out >got &&
	echo "1 ramp 0 9999 4999.5 0 0" >expect &&
	diff -u expect got
'

test_expect_success 'without -s there are no statistics' '
	reflect-info in.txt >out &&
	! grep "channel" out &&
	test "$(grep -c "^frame " out)" -eq 2
'

test_done
