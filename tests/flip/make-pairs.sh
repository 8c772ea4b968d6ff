#!/bin/sh
# Writes tests/flip's picture pairs (run from the build tree's top, with
# reflect-export on PATH or in bin/): NAME-ref and NAME-test, each a
# reference (B) and a test (A) picture, made by awk as ascii streams and
# written by reflect-export.  LDR pairs are 8-bit PNG (the values as
# display sRGB, not encoded again), HDR pairs half OpenEXR.  The noise
# is Park-Miller's generator, exact in awk's doubles, so the files come
# out the same everywhere.
#	sh tests/flip/make-pairs.sh OUTDIR
set -e
out=${1:-.}
PATH="$(pwd)/bin:$PATH"

# picture NAME W H KIND VARIANT: an ascii stream of R G B
picture () {
	awk -v w="$2" -v h="$3" -v kind="$4" -v var="$5" '
	function rnd() { seed = (seed * 16807) % 2147483647; return seed / 2147483647 }
	function clamp(v) { return v < 0 ? 0 : v > 1 ? 1 : v }
	BEGIN {
		seed = 12345 + 7 * var
		print "#?REFLECT1"
		print "NCOLS=" w; print "NROWS=" h; print "NCOMP=3"
		print "CHANNELS=R G B"; print "FORMAT=ascii"; print ""
		for (y = 0; y < h; y++) for (x = 0; x < w; x++) {
			u = x / (w - 1); v = y / (h - 1); n = rnd() - 0.5
			if (kind == "gradient") {
				r = u; g = v; b = 1 - u * v
				if (var) { r += 0.08 * n; g += 0.05 * n; b -= 0.06 * n }
				r = clamp(r); g = clamp(g); b = clamp(b)
			} else if (kind == "edges") {
				# a checker of 8-pixel squares and a thin diagonal
				s = (int(x / 8) + int(y / 8)) % 2
				xx = var ? x + 1 : x
				s = (int(xx / 8) + int(y / 8)) % 2
				r = g = b = s ? 0.85 : 0.15
				if (int(x) == int(y * w / h)) { r = 1; g = 0.2; b = 0.1 }
				if (var && x > w / 2 && y > h / 2) b = 0.6
			} else if (kind == "patches") {
				# four colour patches and a grey ramp
				p = int(u * 3.999) + 4 * int(v * 1.999)
				r = (p % 2) ? 0.9 : 0.2; g = (int(p / 2) % 2) ? 0.8 : 0.1
				b = (int(p / 4) % 2) ? 0.7 : 0.3
				if (var) { t = r; r = 0.9 * r + 0.1 * g; g = 0.9 * g + 0.1 * b; b = 0.9 * b + 0.1 * t }
				if (var && x % 16 == 0) { r = clamp(r + 0.3); g = clamp(g + 0.3); b = clamp(b + 0.3) }
			} else if (kind == "sky") {
				# HDR: a sky from 0.05 to 4 with a sun of 60, over a
				# dark ground
				r = g = b = 0
				if (v < 0.6) { l = 0.05 + 4 * (0.6 - v); r = 0.6 * l; g = 0.8 * l; b = l }
				else { r = 0.02 + 0.03 * u; g = 0.015; b = 0.01 }
				d = (u - 0.7) ^ 2 + (v - 0.2) ^ 2
				if (d < 0.004) { r = 60; g = 55; b = 40 }
				if (var) { f = 1 + 0.3 * n; r *= f; g *= f; b *= f }
			} else if (kind == "glossy") {
				# HDR: a highlight over a ramp, with colour; the test
				# softer and a little brighter
				d = (u - 0.4) ^ 2 + (v - 0.5) ^ 2
				k = var ? 80 : 200
				l = 0.1 + 3 * u + 500 * exp(-k * d)
				r = 0.9 * l; g = 0.7 * l; b = 0.5 * l + 0.02
				if (var) { r *= 1.1; g *= 1.05 }
			}
			printf "%.9g %.9g %.9g\n", r, g, b
		}
	}' >"$out/$1.txt"
}

pair () {
	picture "$1-ref" "$2" "$3" "$4" 0
	picture "$1-test" "$2" "$3" "$4" 1
	for s in ref test
	do
		if test "$5" = ldr
		then
			reflect-export --srgb=off --tone=none --depth=8 -o "$out/$1-$s.png" "$out/$1-$s.txt"
		else
			reflect-export --depth=half -o "$out/$1-$s.exr" "$out/$1-$s.txt"
		fi
		rm -f "$out/$1-$s.txt"
	done
}

pair gradient 64 64 gradient ldr
pair edges 96 64 edges ldr
pair patches 128 96 patches ldr
pair sky 64 64 sky hdr
pair glossy 128 96 glossy hdr
