#!/bin/sh
# doc/farm/sweep.sh OUT SCENE...: the fidelity table (bench/fidelity,
# doc/fidelity.md) for the scenes given, "default" for the embedded one,
# every mode of $MODES shaded and scored against the scene's truth, the
# jobs spread by GNU parallel over the machines of $SSHLOGINFILE or else
# of $SSHLOGIN (by default ":", this machine alone).  First a job a scene
# makes its G-buffer, its probe (reflect-capture --hide-reflective) and
# its truth (reflect-trace at $TRUTH_SAMPLES samples); then a job a scene
# and mode shades and scores.  Inputs go out with --basefile and
# --transferfile, the G-buffers and truths come back with --return, the
# scores on the jobs' stdout (reflect-compare's status 3, pictures
# beyond its thresholds, is a score like any other here).  Writes OUT, a table in markdown: relative
# RMSE of R G B over the eroded mask.  $SIZE (WxH) is the frame's size,
# $PROBE_SIZE the probe's faces' (reflect-capture -n; its own by default).
# Every machine needs reflect's tools on its PATH.
set -e
test $# -ge 2 || {
	echo "usage: sweep.sh OUT SCENE..." >&2
	exit 2
}
out=$1
shift
modes=${MODES:-none approx hdrp godot footprint raytraced:samples=64 raytraced:samples=1024}
size=${SIZE:-320x180}
truth=${TRUTH_SAMPLES:-4096}
w=${size%x*} h=${size#*x}
probe=${PROBE_SIZE:+-n $PROBE_SIZE}
work=$out.work
rm -rf "$work"
mkdir -p "$work"
names=
base=
for s in "$@"
do
	if test "$s" = default
	then
		n=default
	else
		n=$(basename "$s" .scene)
		cp "$s" "$work/$n.scene"
		base="$base --basefile $n.scene"
	fi
	names="$names $n"
done
if test -n "${SSHLOGINFILE:-}"
then
	set -- --sshloginfile "$SSHLOGINFILE"
else
	set -- -S "${SSHLOGIN:-:}"
fi
cd "$work"
# $base and $names are lists of words: split on purpose.
# shellcheck disable=SC2086
parallel --will-cite "$@" --halt now,fail=1 $base \
	--return '{}.g.rfl' --return '{}.env.rfl' --return '{}.truth.rfl' --cleanup \
	's=default; test {} = default || s={}.scene;' \
	"reflect-gbuffer -q -x $w -y $h -c P,N,Ng,V,roughness,mask,objid,depth,emission \$s |" \
	'reflect-project >{}.g.rfl &&' \
	"reflect-capture --hide-reflective $probe \$s | reflect-prefilter -q -o {}.env.rfl - &&" \
	"reflect-trace -q -x $w -y $h --samples=$truth \$s >{}.truth.rfl" \
	::: $names
# shellcheck disable=SC2086
parallel --will-cite "$@" --halt now,fail=1 --keep-order --tag \
	--transferfile '{1}.g.rfl' --transferfile '{1}.env.rfl' \
	--transferfile '{1}.truth.rfl' --cleanup \
	'reflect-shade -q -m {2} --final --env={1}.env.rfl {1}.g.rfl >{1}.{#}.rfl &&' \
	'reflect-compare -f a --mask --erode=1 {1}.{#}.rfl {1}.truth.rfl >{1}.{#}.txt;' \
	"r=\$?; test \$r = 0 || test \$r = 3 &&" \
	"awk '{ print \$2 }' {1}.{#}.txt && rm -f {1}.{#}.rfl {1}.{#}.txt" \
	::: $names ::: $modes >rows
cd - >/dev/null
{
	printf '| scene |'
	for m in $modes
	do
		printf ' %s |' "$m"
	done
	echo
	printf '|---|'
	for m in $modes
	do
		printf '%s' '---|'
	done
	echo
	for n in $names
	do
		printf '| %s |' "$n"
		awk -v n="$n" '$1 == n { printf " %.4f |", $3 }' "$work/rows"
		echo
	done
} >"$out"
rm -rf "$work"
