#!/bin/sh
test_description='reflect-import: passes of other renderers as a G-buffer stream'
. "$srcdir/tests/lib.sh"

# the data lines of an ascii stream's first frame
data () {
	sed -n '/^$/,$p' "$1" | sed 1d
}

# ascii_image FILE CHANNELS ROW...: a 1-row image from ascii rows
ascii_image () {
	out=$1 chans=$2
	shift 2
	{
		printf '#?REFLECT1\nNCOLS=%d\nNROWS=1\nNCOMP=%d\nCHANNELS=%s\nFORMAT=ascii\n\n' \
			$# "$(echo $chans | wc -w)" "$chans"
		for row
		do
			echo "$row"
		done
	} | reflect-export -c all -o "$out"
}

test_expect_success 'Blender passes: names mapped, Z up turned to Y up, V from the camera' '
	ascii_image blender.exr "ViewLayer.Position.X ViewLayer.Position.Y ViewLayer.Position.Z ViewLayer.Normal.X ViewLayer.Normal.Y ViewLayer.Normal.Z ViewLayer.Depth.Z ViewLayer.IndexOB.X Extra" \
		"1 2 3 0 0 1 7 4 0.5" "-1 0 0 1 0 0 2 5 0.25" &&
	reflect-import --preset=blender --camera=1,-5,3 --roughness=0.25 -fa blender.exr >out.txt &&
	test_grep "^CHANNELS=P.X P.Y P.Z N.X N.Y N.Z depth objid roughness Extra V.X V.Y V.Z$" out.txt &&
	data out.txt >got &&
	# P (1,2,3) Z up is (1,3,-2) Y up; N (0,0,1) is (0,1,0); the camera
	# (1,-5,3) is (1,3,5), so V = (0,0,7)/7 for the first pixel; for the
	# second, P = (-1,0,0), V = (2,3,5)/sqrt(38)
	cat >expect <<-\EOF &&
	1 3 -2   0 1 0   7 4 0.25 0.5   0 0 1
	-1 0 0   1 0 0   2 5 0.25 0.25  0.324442842 0.486664263 0.811107106
	EOF
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'Blender: a Tangent AOV becomes T, turned to Y up as a vector' '
	ascii_image tangent.exr "ViewLayer.Position.X ViewLayer.Position.Y ViewLayer.Position.Z ViewLayer.Normal.X ViewLayer.Normal.Y ViewLayer.Normal.Z ViewLayer.Tangent.X ViewLayer.Tangent.Y ViewLayer.Tangent.Z" \
		"1 2 3 0 0 1 0 1 0" &&
	reflect-import --preset=blender --camera=1,-5,3 --roughness=0.25 -fa tangent.exr >t.txt &&
	test_grep "^CHANNELS=P.X P.Y P.Z N.X N.Y N.Z T.X T.Y T.Z " t.txt &&
	# T (0,1,0) Z up is (0,0,-1) Y up
	data t.txt | cut -f7-9 >got &&
	echo "0 0 -1" >expect &&
	test_cmp_numbers expect got 1e-6
'

test_expect_success 'single-layer images mapped by FILE:CHANNEL; duplicate names dropped' '
	ascii_image pos.exr "R G B" "0.5 1 -1" &&
	ascii_image nrm.exr "R G B" "0 0 1" &&
	reflect-import -fa -c P.X=pos.exr:R -c P.Y=pos.exr:G -c P.Z=0:B \
		-c N.X=nrm.exr:R -c N.Y=nrm.exr:G -c N.Z=1:B pos.exr nrm.exr >two.txt &&
	test_grep "^CHANNELS=P.X P.Y P.Z N.X N.Y N.Z$" two.txt &&
	data two.txt >got &&
	echo "0.5 1 -1 0 0 1" >expect &&
	test_cmp_numbers expect got 0
'

test_expect_success 'probe keys from --box and --center' '
	reflect-import -fa --box=-5,0,-5,5,4,5 --center=0,2,0 pos.exr >probe.txt &&
	test_grep "^PROBE_BOX=-5 0 -5 5 4 5$" probe.txt &&
	test_grep "^PROBE_CENTER=0 2 0$" probe.txt
'

test_expect_success 'bad input: each a one-line message and exit 1' '
	test_expect_code 1 reflect-import -c P.X=R pos.exr nrm.exr 2>err &&
	test_one_line_message reflect-import err &&
	test_grep "channel .R. is in several inputs" err &&
	test_expect_code 1 reflect-import -c P.X=nope pos.exr 2>err &&
	test_grep "no input channel .nope. (the input has: R G B)" err &&
	# A failed mapping after a good one used to return success with no
	# importer (a crash).
	test_expect_code 1 reflect-import -c a=R -c b=nosuch pos.exr >out 2>err &&
	test_one_line_message reflect-import err &&
	test_grep "no input channel .nosuch. (the input has: R G B)" err &&
	test ! -s out &&
	test_expect_code 1 reflect-import -c a=R --roughness=nosuch pos.exr 2>err &&
	test_grep "no input channel .nosuch." err &&
	test_expect_code 1 reflect-import -c P.X=3:R pos.exr 2>err &&
	test_grep "no input file .3." err &&
	ascii_image wide.exr "R" "1" "2" &&
	test_expect_code 1 reflect-import pos.exr wide.exr 2>err &&
	test_grep "the passes must have one size" err &&
	test_expect_code 1 reflect-import --roughness=2 pos.exr 2>err &&
	test_grep "roughness 2 is outside" err &&
	test_expect_code 1 reflect-import --camera=0,0,0 pos.exr 2>err &&
	test_grep "V from the camera needs P.X P.Y P.Z" err &&
	test_expect_code 1 reflect-import -c P.X pos.exr 2>err &&
	test_grep "is not OUT=IN" err &&
	test_expect_code 1 reflect-import missing.exr 2>err &&
	test_grep "cannot open .missing.exr." err &&
	test_expect_code 1 reflect-import 2>err &&
	test_grep "^usage: reflect-import" err
'

# The path-traced references beside the source tree, or where
# REFLECT_TRUTH says (./run-tests --sanitize builds a copy elsewhere).
truth="${REFLECT_TRUTH:-$srcdir/../shared/truth}/room-floor.gbuf.exr"
if test -f "$truth"
then
	test_expect_success 'the path-traced G-buffer goes through the pipeline' '
		reflect-import --box=-5,0,-5,5,4,5 --center=0,2,0 "$truth" >gbuf.rfl &&
		reflect-info gbuf.rfl >info &&
		test_grep "NCOLS=320" info && test_grep "NROWS=240" info &&
		grep "CHANNELS=" info | sed "s/.*CHANNELS=//" | tr " " "\n" >names &&
		for c in P.X N.Y V.Z roughness mask objid depth
		do
			grep -x "$c" names || return 1
		done &&
		# every reflective pixel (mask 1) gets a finite hit and a unit
		# lookup direction; the walls (mask 0) carry V = 0 in this file
		reflect-project -fa -h gbuf.rfl >proj.txt &&
		awk "\$2 == 1 { n++; l = \$20 * \$20 + \$21 * \$21 + \$22 * \$22
			if (\$23 == \"inf\" || \$23 < 0 || l < 0.999 || l > 1.001) bad++ }
			END { print n, bad + 0 }" proj.txt >got &&
		echo "34834 0" >expect &&
		test_cmp_numbers expect got 0
	'
else
	test_skip 'the path-traced G-buffer goes through the pipeline' "no $truth"
fi

test_done
