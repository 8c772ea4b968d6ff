#!/bin/sh
test_description='doc/strip lays images side by side with their labels'
. "$srcdir/tests/lib.sh"

strip="$builddir/doc/strip"
imgdump="$builddir/tests/imgdump"

test_expect_success 'two grey images become one strip, labelled, with a rule' '
	printf "#?REFLECT1\nNCOLS=40\nNROWS=20\nNCOMP=3\nCHANNELS=R G B\nFORMAT=ascii\n\n" >grey.txt &&
	awk "BEGIN { for (i = 0; i < 800; i++) print 0.5, 0.5, 0.5 }" >>grey.txt &&
	reflect-export --srgb=off -o a.png grey.txt &&
	reflect-export --srgb=off -o b.png grey.txt &&
	"$strip" -s 1 -o s.png none=a.png hdrp=b.png &&
	"$imgdump" -8 s.png >dump &&
	test_grep "^82 20 3$" dump &&
	sed 1,2d dump >px &&
	# row 0 is untouched grey; (40, y) and (41, y) are the rule; the
	# label box starts at (4, 4) and its first glyph row of "n" is row
	# 9 (box 4 + padding 3 + glyph row 2).
	awk "NR == 1 && \$1 != 128 { exit 1 }
		NR == 41 && \$1 != 0 { exit 1 }
		NR == 42 && \$1 != 0 { exit 1 }
		NR == 1 + 4 * 82 + 4 && \$1 != 38 { exit 1 }
		NR == 1 + 9 * 82 + 7 && \$1 != 255 { exit 1 }
		NR == 1 + 9 * 82 + 42 + 7 && \$1 != 255 { exit 1 }" px
'

test_expect_success 'images of different heights are refused' '
	printf "#?REFLECT1\nNCOLS=4\nNROWS=2\nNCOMP=3\nCHANNELS=R G B\nFORMAT=ascii\n\n" >small.txt &&
	awk "BEGIN { for (i = 0; i < 8; i++) print 1, 0, 0 }" >>small.txt &&
	reflect-export -o c.png small.txt &&
	test_expect_code 1 "$strip" -o t.png a=a.png c=c.png 2>err &&
	test_grep "height" err
'

test_done
