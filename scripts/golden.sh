#!/bin/sh
# scripts/golden.sh BUILD SRC OUT: every tool's output on the example
# scenes (stdout, stderr and exit status of each run, some 340 files in
# OUT, about 1.5 min), to compare with cmp before and after a change that
# must not change them, such as a move between files:
#
#   scripts/golden.sh . . /tmp/before   (change, make)
#   scripts/golden.sh . . /tmp/after && diff -r /tmp/before /tmp/after
#
# Small sizes, fixed seeds, one thread and four.
set -u
build=$(cd "$1" && pwd); src=$(cd "$2" && pwd); out=$3
mkdir -p "$out" && out=$(cd "$out" && pwd)
PATH=$build/bin:$PATH REFLECT_PLUGIN_PATH=$build/plugins/.libs REFLECT_PLUGIN_SYSTEM_PATH=
XDG_CACHE_HOME=$out/cache
export PATH REFLECT_PLUGIN_PATH REFLECT_PLUGIN_SYSTEM_PATH XDG_CACHE_HOME
cd "$out" || exit 1
ex=$src/doc/examples
run () { name=$1; shift; sh -c "$*" >"$name" 2>"$name.err"; echo "$? $name" >>status; }
: >status
run room.rfl "reflect-prefilter -s 8 --levels=5"
run room16.cap "reflect-capture -n 16 --edge-samples=2 --object-samples=2 --bounce-size=8 $ex/room-floor.scene"
run two.cap "reflect-capture -p all -n 16 --edge-samples=2 --object-samples=2 --bounce-size=8 -o two%d.rfl $ex/two-rooms.scene; cat two1.rfl two2.rfl"
for s in default room-floor room-spheres two-rooms
do
	f=; test $s = default || f=$ex/$s.scene
	run $s.gbuf "reflect-gbuffer -x 64 -y 36 $f"
	run $s.gbuf-ss "reflect-gbuffer -x 32 -y 18 --supersample=2 $f"
	run $s.trace "reflect-trace -x 32 -y 18 --samples=8 --seed=3 $f"
	for p in box infinite bevel
	do
		run $s.$p "reflect-project -m $p <$s.gbuf"
	done
	for m in none approx hdrp godot raytraced footprint
	do
		for j in 1 4
		do
			run $s.box.$m.j$j "reflect-shade -j $j -m $m --env=room.rfl <$s.box"
		done
		run $s.bevel.$m "reflect-shade -m $m --env=room.rfl <$s.bevel"
		run $s.box.$m.noenv "reflect-shade -m $m <$s.box"
	done
	run $s.cap.approx "reflect-shade -m approx --env=room16.cap --samples=8 --no-cache <$s.box"
	for o in occlusion-box horizon
	do
		run $s.occ.$o "reflect-occlude -m $o <$s.box.approx.j1"
	done
	for a in mean ema
	do
		run $s.acc.$a "cat $s.box.raytraced.j1 $s.box.raytraced.j4 | reflect-accumulate -m $a"
	done
	for fl in atrous quad
	do
		run $s.filt.$fl "reflect-filter -m $fl <$s.box.raytraced.j1"
	done
	run $s.png "reflect-export -c spec -o $s.png <$s.box.approx.j1; cat $s.png"
	run $s.exr "reflect-export -c spec -o $s.exr <$s.box.approx.j1; cat $s.exr"
	run $s.cmp "reflect-compare $s.box.approx.j1 $s.box.hdrp.j1; true"
done
for m in approx raytraced
do
	run two.final.$m "reflect-project <two-rooms.gbuf | reflect-shade -m $m --samples=8 --no-cache --final"
	run two.noblend.$m "reflect-project <two-rooms.gbuf | reflect-shade -m $m --samples=8 --no-cache --final --blend=off --fallback=none"
done
run montage.png "reflect-montage -o m.png a=default.png b=room-floor.png; cat m.png"
ls | wc -l
