#!/bin/sh
test_description='normal maps perturb N, keep it unit, and a flat map changes nothing'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/scene-lib.sh"

# A 2x1 float PFM whose pixels are (0.5, 0.5, 1): the flat tangent-space
# normal, exactly (8-bit files cannot hold 0.5).
write_flat_pfm () {
	printf 'PF\n2 1\n-1.0\n' >"$1" &&
	printf '\000\000\000\077\000\000\000\077\000\000\200\077' >>"$1" &&
	printf '\000\000\000\077\000\000\000\077\000\000\200\077' >>"$1"
}

scene () {
	cat <<-EOF
	probe box -5 -5 -5 5 5 5
	camera position 0 3 3 target 0 0 0 fov 60
	rect plane y 0 min -4 -4 max 4 4 $1
	sphere center 0 0.5 0 radius 0.5 $1
	box min 1 0 -1 max 1.5 1 -0.5 $1
	rect center -1.5 0.5 -1 normal 1 0 1 size 1 1 $1
	EOF
}

# |N| = 1 everywhere; returns in $perturbed how many pixels have N != Ng.
check_normals () {
	gb_data "$1" | awk '
	{
		l = sqrt($4 * $4 + $5 * $5 + $6 * $6)
		if ((l - 1) ^ 2 > 1e-12) { print NR ": |N| = " l; bad = 1 }
		if (($4 - $7) ^ 2 + ($5 - $8) ^ 2 + ($6 - $9) ^ 2 > 1e-8) n++
	}
	END { print n + 0 > "perturbed"; exit bad }'
}

test_expect_success 'a flat (0.5, 0.5, 1) image map leaves N = Ng' '
	write_flat_pfm flat.pfm &&
	scene "normalmap image flat.pfm strength 3 tiling 2 5" >flat.scene &&
	reflect-gbuffer -x 48 -y 32 -fa flat.scene >flat.txt &&
	check_normals flat.txt &&
	test "$(cat perturbed)" -eq 0 &&
	scene "" >plain.scene &&
	reflect-gbuffer -x 48 -y 32 -fa plain.scene >plain.txt &&
	gb_data flat.txt >a && gb_data plain.txt >b &&
	cmp a b
'

for kind in tiles bumps noise
do
	test_expect_success "procedural $kind: N perturbed, unit, Ng unchanged" '
		scene "normalmap $kind scale 0.25 strength 0.8" >$kind.scene &&
		reflect-gbuffer -x 48 -y 32 -fa $kind.scene >$kind.txt &&
		check_normals $kind.txt &&
		test "$(cat perturbed)" -gt 100 &&
		gb_data $kind.txt | cut -f 1-3,7-9,19,20 >a &&
		gb_data plain.txt | cut -f 1-3,7-9,19,20 >b &&
		cmp a b
	'
done

test_expect_success 'an image map is found next to the scene file' '
	mkdir -p sub &&
	write_flat_pfm sub/map.pfm &&
	echo "probe box -1 -1 -1 1 1 1" >sub/s.scene &&
	echo "sphere center 0 0 0 radius 0.5 normalmap image map.pfm" >>sub/s.scene &&
	reflect-gbuffer -x 2 -y 2 sub/s.scene >/dev/null
'

test_done
