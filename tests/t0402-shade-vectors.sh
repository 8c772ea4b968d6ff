#!/bin/sh
test_description='the worked test vectors of spec section 15, through reflect-project | reflect-shade'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# Box (-3,0,-2)-(3,3,2), capture point (0,1.5,0), camera (-2,1.6,-1.5),
# floor normal (0,1,0); godot with power 4, 6 steps, the linear mapping:
# the table's mips are pr' * 6.  P, smoothness, then the table's N.V, d,
# |R'| and the mips of none, approx (clamp), hdrp and godot.
cat >table <<\EOF
1 0 0.5    0.75 0.4056 2.6297 3.5424 1.5000 0.6574 1.2101 0.9129
1 0 0.5    0.5  0.4056 2.6297 3.5424 3.0000 1.3149 2.6135 2.5306
1 0 0.5    0.2  0.4056 2.6297 3.5424 4.8000 2.1038 4.5527 4.8000
2.5 0 1.5  0.75 0.2837 0.6267 3.7562 1.5000 0.1567 0.5627 0.4090
2.5 0 1.5  0.5  0.2837 0.6267 3.7562 3.0000 0.3133 1.7503 1.5439
0 0 0      0.5  0.5391 3.9576 3.3930 3.0000 1.9788 3.0000 3.0000
EOF

test_expect_success 'the G-buffer of the table, projected' '
	awk "{
		vx = -2 - \$1; vy = 1.6 - \$2; vz = -1.5 - \$3
		n = sqrt(vx * vx + vy * vy + vz * vz)
		printf \"%s %s %s 0 1 0 %.9g %.9g %.9g %s\n\", \$1, \$2, \$3, vx / n,
			vy / n, vz / n, 1 - \$4
	}" table |
	stream gb.txt 6 1 "P.X P.Y P.Z N.X N.Y N.Z V.X V.Y V.Z roughness" \
		"PROBE_BOX=-3 0 -2 3 3 2" "PROBE_CENTER=0 1.5 0" &&
	reflect-project gb.txt >proj.rfl &&
	level_chain chain.rfl 64 7 linear
'

test_expect_success 'N.V, d and |R'"'"'| are the table'"'"'s' '
	reflect-project -fa gb.txt >proj.txt &&
	column proj.txt V.Y hit.dist probe.dist >got &&
	awk "{ print \$5, \$6, \$7 }" table >want &&
	cmp_numbers want got 1e-4
'

test_expect_success 'R and the lookup vector of P = (1,0,0.5) are the listed ones' '
	column proj.txt R.X R.Y R.Z D.X D.Y D.Z probe.dist | sed -n 1p >got &&
	awk "{ print \$1, \$2, \$3, \$4 * \$7, \$5 * \$7, \$6 * \$7 }" got >rp &&
	echo "0.7605 0.4056 0.5070 3.0 -0.4333 1.8333" >want &&
	cmp_numbers want rp 1e-4
'

col=8
for m in none approx hdrp godot
do
	test_expect_success "$m: the table's mips (roughness.eff x 6, and the lod sampled)" '
		reflect-shade -fa -m $m --mapping=linear --env=chain.rfl proj.rfl >out.txt &&
		column out.txt roughness.eff spec.R >got &&
		awk "{ print \$1 * 6, \$2 }" got >mips &&
		awk -v c=$col "{ print \$c, \$c }" table >want &&
		cmp_numbers want mips 1.5e-4
	'
	col=$((col + 1))
done

test_expect_success 'the same with an environment prefiltered on the fly, --mapping=linear' '
	reflect-shade -fa -m hdrp --mapping=linear --steps=6 --samples=4 --size=64 \
		proj.rfl >out.txt 2>err &&
	test_grep "^ENV_MAPPING=linear$" out.txt &&
	test_grep "^ENV_STEPS=6$" out.txt &&
	column out.txt roughness.eff >got &&
	awk "{ print \$1 * 6 }" got >mips &&
	awk "{ print \$10 }" table >want &&
	cmp_numbers want mips 1.5e-4
'

test_expect_success 'HDRP is unchanged where d >= |R'"'"'| (the last row)' '
	reflect-shade -fa -m hdrp --env=chain.rfl proj.rfl >out.txt &&
	column out.txt roughness.eff roughness | sed -n 6p >last &&
	awk "{ exit !(\$1 == \$2) }" last
'

test_done
