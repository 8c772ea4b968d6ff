# Helpers for the reflect-shade tests, on top of tests/lib.sh.

# level_chain FILE FACE LEVELS MAPPING [FACE0]: writes a prefiltered
# chain whose level k holds the value k in every texel and channel, so
# that a sample's value is its lod (trilinear filtering of constants).
# With FACE0 set, level 0 holds FACE0 + f on face f instead, so that a
# lod-0 lookup tells the face it landed on.  STEPS is LEVELS - 1.
level_chain () {
	awk -v n="$2" -v levels="$3" -v mapping="$4" -v face0="${5:-}" 'BEGIN {
		for (k = 0; k < levels; k++) {
			printf "#?REFLECT1\nENVMAP=CUBE\nLEVEL=%d\nLEVELS=%d\n", k, levels
			printf "PREFILTER=ggx\nMAPPING=%s\nSTEPS=%d\n", mapping, levels - 1
			printf "NCOLS=%d\nNROWS=%d\nNCOMP=3\nCHANNELS=R G B\nFORMAT=ascii\n\n",
				n, 6 * n
			for (f = 0; f < 6; f++) {
				v = (k == 0 && face0 != "") ? face0 + f : k
				for (j = 0; j < n * n; j++)
					print v, v, v
			}
			n = n / 2
		}
	}' >"$1"
}

# stream FILE NCOLS NROWS "CHANNELS" [KEY=VALUE...] <data: an ascii
# stream of one frame; the data (one pixel a line) comes from stdin.
stream () {
	st_file=$1 st_cols=$2 st_rows=$3 st_channels=$4
	shift 4
	{
		echo "#?REFLECT1"
		for kv
		do
			echo "$kv"
		done
		echo "NCOLS=$st_cols"
		echo "NROWS=$st_rows"
		echo "NCOMP=$(echo $st_channels | wc -w)"
		echo "CHANNELS=$st_channels"
		echo "FORMAT=ascii"
		echo
		cat
	} >"$st_file"
}

# column FILE CHANNEL...: the named channels of every pixel of every
# frame of an ascii stream, one pixel a line.
column () {
	col_file=$1
	shift
	awk -v want="$*" '
	/^#\?REFLECT/ { body = 0; next }
	!body && /^CHANNELS=/ {
		for (k in idx) delete idx[k]
		n = split(substr($0, 10), ch, " ")
		for (i = 1; i <= n; i++) idx[ch[i]] = i
	}
	!body && /^$/ { body = 1; next }
	body {
		m = split(want, w, " ")
		for (i = 1; i <= m; i++) {
			if (!(w[i] in idx)) {
				print "no channel " w[i] > "/dev/stderr"
				exit 1
			}
			printf "%s%s", (i > 1 ? " " : ""), $(idx[w[i]])
		}
		printf "\n"
	}' "$col_file"
}

# Lod of perceptual roughness r for a mapping and steps, recomputed here
# (awk function text, to paste into programs).
AWK_LOD='
function clamp01(x) { return x > 0 ? (x < 1 ? x : 1) : 0 }
function lod(mapping, steps, r) {
	r = clamp01(r)
	if (mapping == "linear") return r * steps
	return r * (1.7 - 0.7 * r) * steps
}'

# cmp_numbers EXPECTED ACTUAL [TOL]: like test_cmp_numbers, but numbers
# in exponent notation (1e-06) count as numbers: only inf and nan must
# match as words.
cmp_numbers () {
	awk -v tol="${3:-1e-5}" -v ef="$1" -v af="$2" '
	function bad(msg) { print ef ":" NR ": " msg > "/dev/stderr"; err = 1 }
	function word(s) { return s ~ /^[-+]?(inf|nan)/ }
	{
		if ((getline line < af) <= 0) { bad("missing in " af); exit 1 }
		n = split($0, e); m = split(line, a)
		if (n != m) { bad(n " fields expected, " m " found: " line); next }
		for (i = 1; i <= n; i++) {
			if (word(e[i]) || word(a[i])) {
				if (e[i] != a[i]) bad("field " i ": " e[i] " != " a[i])
				continue
			}
			d = e[i] - a[i]; if (d < 0) d = -d
			if (d > tol) bad("field " i ": " e[i] " != " a[i] " (tolerance " tol ")")
		}
	}
	END {
		if ((getline line < af) > 0) { print af ": more lines than " ef > "/dev/stderr"; err = 1 }
		exit err
	}' "$1"
}

# truth_setup DIR SCENE: a path-traced reference of DIR (../shared/truth)
# as the tests score against it: its G-buffer imported and projected
# (SCENE.g.rfl), its probe prefiltered (SCENE.env.rfl) and its render
# (SCENE.ref.rfl), made once in the current directory.
truth_setup () {
	test -f "$2.g.rfl" || {
		reflect-import --box=-5,0,-5,5,4,5 --center=0,2,0 "$1/$2.gbuf.exr" |
			reflect-project >"$2.g.rfl" &&
		reflect-prefilter -o "$2.env.rfl" "$1/$2.probe.cube.exr" 2>/dev/null &&
		reflect-import "$1/$2.ref.exr" >"$2.ref.rfl"
	}
}
