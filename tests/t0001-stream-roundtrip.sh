#!/bin/sh
test_description='a stream goes through a tool unchanged in values and channels'
. "$srcdir/tests/lib.sh"

test_expect_success 'ascii G-buffer through project keeps its channels' '
	cat >in.txt <<-\EOF &&
	#?REFLECT1
	NCOLS=2
	NROWS=1
	NCOMP=10
	CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z extra
	PROBE_BOX=-3 0 -2 3 3 2
	PROBE_CENTER=0 1.5 0
	FORMAT=ascii

	0	1	0	0	1	0	0	1	0	7.5
	1	1	0	1	0	0	1	0	0	-2
	EOF
	reflect-project -fa in.txt >out.txt &&
	test_grep "^CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z extra R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist$" out.txt &&
	test_grep "^reflect-project -fa in.txt$" out.txt &&
	test_grep "^PROJECTION=box$" out.txt &&
	sed -n "/^$/,\$p" out.txt | sed 1d >data.txt &&
	test_line_count 2 data.txt &&
	cat >expect <<-\EOF &&
	0 1 0 0 1 0 0 1 0 7.5   0 1 0   0 1 0   2 1.5
	1 1 0 1 0 0 1 0 0 -2    1 0 0   0.986393924 -0.164398987 0   2 3.04138127
	EOF
	test_cmp_numbers expect data.txt 1e-6
'

test_expect_success 'the command line is recorded in the order it was given' '
	reflect-project in.txt -fa --center=0,1,0 >out2.txt &&
	test_grep "^reflect-project in.txt -fa --center=0,1,0$" out2.txt
'

test_done
