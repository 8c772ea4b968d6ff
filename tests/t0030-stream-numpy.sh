#!/bin/sh
test_description='the numpy examples of reflect-stream(5) read and write real streams'
. "$srcdir/tests/lib.sh"

page="$srcdir/doc/reflect-stream.5"

# The example between the comments '.\" begin-numpy-NAME' and
# '.\" end-numpy-NAME' of the man page source, roff escapes undone.
extract_example () {
	sed -n '/^\.\\" begin-numpy-'"$1"'$/,/^\.\\" end-numpy-'"$1"'$/p' "$page" |
	sed -e '/^\./d' -e 's/\\-/-/g' -e "s/\\\\(aq/'/g" -e 's/\\&//g' \
		-e 's/\\e/\\/g'
}

# A python with numpy: $PYTHON3 (from configure), else the system's (the
# python3 first on PATH may be one without numpy).
PY=
for p in "${PYTHON3:-}" /usr/bin/python3 python3
do
	test -n "$p" || continue
	if "$p" -c 'import numpy' >/dev/null 2>&1
	then
		PY=$p
		break
	fi
done

test_expect_success 'the man page holds the two examples' '
	extract_example read >read.py &&
	extract_example write >write.py &&
	test_grep "^def read_stream(f):$" read.py &&
	test_grep "^def write_frame(f, a, names, lines=()):$" write.py &&
	! grep "\\\\[-e&(]" read.py write.py &&
	test_grep "rstrip(b\"\\\\r\\\\n\")" read.py
'

if test -z "$PY"
then
	for t in 'numpy reader: float frames' 'numpy reader: ascii frames' \
		'numpy reader: its own main' 'numpy reader: big-endian data' \
		'numpy writer: reflect-info -s reads it' \
		'numpy writer: frames of any header length feed reflect-project'
	do
		test_skip "$t" 'no python3 with numpy'
	done
	test_done
fi

test_expect_success 'setup: two frames from reflect-project, float and ascii' '
	cat >gbuffer.txt <<-\EOF &&
	#?REFLECT1
	myapp.scene=kitchen01
	PROBE_BOX=-3 0 -2 3 3 2
	PROBE_CENTER=0 1.5 0
	NCOLS=3
	NROWS=1
	NCOMP=11
	CHANNELS=P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness mask
	FORMAT=ascii

	0 1 0  0 1 0  0 1 0  0.2 1
	1 1 0  1 0 0  1 0 0  0.5 1
	5 1 0  0 1 0  0 1 0  0.75 0
	EOF
	reflect-project --center=0,1,0 gbuffer.txt >box.rfs &&
	reflect-project -m infinite gbuffer.txt >inf.rfs &&
	cat box.rfs inf.rfs >two.rfs &&
	reflect-project -fa --center=0,1,0 gbuffer.txt >box.txt &&
	reflect-project -fa -m infinite gbuffer.txt >inf.txt &&
	cat box.txt inf.txt >two.txt &&
	cat >driver.py <<-\EOF &&
	import sys
	sys.path.insert(0, ".")
	from read import read_stream
	for keys, names, a in read_stream(open(sys.argv[1], "rb")):
	    print(keys["PROJECTION"], keys["myapp.scene"], a.dtype, *a.shape)
	    print(*names)
	    for y in range(a.shape[0]):
	        for x in range(a.shape[1]):
	            print(*("%.9g" % v for v in a[y, x]))
	EOF
	# Box, probe at (0,1,0): straight up from (0,1,0) leaves the box at
	# y=3 (hit.dist 2, probe.dist 2); along +X from (1,1,0) at x=3
	# (2 and 3); (5,1,0) is outside the box: D=R, distances +inf.
	# Infinite: D=R and +inf everywhere.
	names="P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness mask R.X R.Y R.Z D.X D.Y D.Z hit.dist probe.dist" &&
	cat >expect <<-EOF
	box kitchen01 float32 1 3 19
	$names
	0 1 0 0 1 0 0 1 0 0.200000003 1 0 1 0 0 1 0 2 2
	1 1 0 1 0 0 1 0 0 0.5 1 1 0 0 1 0 0 2 3
	5 1 0 0 1 0 0 1 0 0.75 0 0 1 0 0 1 0 inf inf
	infinite kitchen01 float32 1 3 19
	$names
	0 1 0 0 1 0 0 1 0 0.200000003 1 0 1 0 0 1 0 inf inf
	1 1 0 1 0 0 1 0 0 0.5 1 1 0 0 1 0 0 inf inf
	5 1 0 0 1 0 0 1 0 0.75 0 0 1 0 0 1 0 inf inf
	EOF
'

test_expect_success 'numpy reader: float frames' '
	"$PY" driver.py two.rfs >out &&
	test_cmp_numbers expect out 1e-6
'

test_expect_success 'numpy reader: ascii frames' '
	"$PY" driver.py two.txt >out &&
	test_cmp_numbers expect out 1e-6
'

test_expect_success 'numpy reader: its own main' '
	"$PY" read.py <two.rfs >out &&
	test_line_count 2 out &&
	test_grep "^(1, 3, 19) P.X P.Y P.Z N.X .* hit.dist probe.dist$" out &&
	"$PY" read.py <two.txt >out2 &&
	cmp out out2
'

test_expect_success 'numpy reader: big-endian data' '
	# 1.5 and -2 as big-endian floats
	printf "#?REFLECT1\nNCOLS=2\nNROWS=1\nNCOMP=1\nCHANNELS=v\nBigEndian=1\nFORMAT=float\n\n\077\300\000\000\300\000\000\000" >be.rfs &&
	reflect-info -s be.rfs >info &&
	awk "\$1 == \"v\" { print \$2, \$3, \$4 }" info >stats &&
	echo "-2 1.5 -0.25" >expect.stats &&
	test_cmp_numbers expect.stats stats &&
	cat >be.py <<-\EOF &&
	import sys
	sys.path.insert(0, ".")
	from read import read_stream
	for keys, names, a in read_stream(open("be.rfs", "rb")):
	    print(*names, *a.ravel())
	EOF
	"$PY" be.py >out &&
	echo "v 1.5 -2.0" >expect.be &&
	test_cmp_numbers expect.be out
'

test_expect_success 'numpy writer: reflect-info -s reads it' '
	"$PY" write.py >ramp.rfs &&
	reflect-info -s ramp.rfs >info &&
	test_grep "^	python3 write.py$" info &&
	test_grep "^	NCOLS=3$" info &&
	test_grep "^	NROWS=2$" info &&
	test_grep "^	CHANNELS=mask$" info &&
	awk "\$1 == \"mask\" { print \$2, \$3, \$4, \$5, \$6 }" info >stats &&
	echo "0 1.25 0.625 0 0" >expect.stats &&
	test_cmp_numbers expect.stats stats &&
	# 24 bytes of data after a header of a multiple of 4 bytes
	size=$(wc -c <ramp.rfs) &&
	test $(( (size - 24) % 4 )) -eq 0
'

test_expect_success 'numpy writer: frames of any header length feed reflect-project' '
	cat >frames.py <<-\EOF &&
	import sys
	import numpy as np
	sys.path.insert(0, ".")
	from write import write_frame
	g = np.array([[[0, 1, 0, 0, 1, 0, 0, 1, 0],
	               [1, 1, 0, 1, 0, 0, 1, 0, 0],
	               [5, 1, 0, 0, 1, 0, 0, 1, 0]]], np.float32)
	names = "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z".split()
	with open("frames.rfs", "wb") as f:
	    for k in range(4):
	        write_frame(f, g, names, ["PROBE_BOX=-3 0 -2 3 3 2",
	                                  "PROBE_CENTER=0 1 0", "note " + "x" * k])
	        print(f.tell() % 4)
	EOF
	"$PY" frames.py >align &&
	printf "0\n0\n0\n0\n" >expect.align &&
	cmp expect.align align &&
	reflect-info frames.rfs >info &&
	test_grep "^frame 4:" info &&
	test_grep "^	note xxx$" info &&
	reflect-project -fa frames.rfs >out.txt &&
	test $(grep -c "^#?REFLECT1$" out.txt) -eq 4 &&
	grep "^[0-9]" out.txt >data &&
	for k in 1 2 3 4
	do
		cat <<-\EOF || return 1
		0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 2 2
		1 1 0 1 0 0 1 0 0 1 0 0 1 0 0 2 3
		5 1 0 0 1 0 0 1 0 0 1 0 0 1 0 inf inf
		EOF
	done >expect.data &&
	test_cmp_numbers expect.data data 1e-6
'

test_done
