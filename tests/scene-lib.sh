# Helpers for the scene and G-buffer tests, on top of tests/lib.sh.

# gb_pixel FILE X Y CHANNEL...: the named channels of pixel (X, Y) of the
# first frame of an ascii stream (-fa), on one line.
gb_pixel () {
	gb_file=$1 gb_x=$2 gb_y=$3
	shift 3
	awk -v x="$gb_x" -v y="$gb_y" -v want="$*" '
	!body && /^NCOLS=/ { ncols = substr($0, 7) }
	!body && /^CHANNELS=/ {
		n = split(substr($0, 10), ch, " ")
		for (i = 1; i <= n; i++) idx[ch[i]] = i
	}
	!body && /^$/ { body = 1; next }
	body {
		if (row++ != y * ncols + x) next
		m = split(want, w, " ")
		for (i = 1; i <= m; i++) {
			if (!(w[i] in idx)) { print "no channel " w[i] > "/dev/stderr"; exit 1 }
			printf "%s%s", (i > 1 ? " " : ""), $(idx[w[i]])
		}
		printf "\n"
		exit
	}' "$gb_file"
}

# gb_frame_pixels FILE CHANNEL...: for every frame of an ascii stream of
# 1x1 frames, the named channels of its pixel, a line per frame.
gb_frame_pixels () {
	gb_file=$1
	shift
	awk -v want="$*" '
	/^#\?REFLECT/ { body = 0; delete idx; next }
	!body && /^CHANNELS=/ {
		n = split(substr($0, 10), ch, " ")
		for (i = 1; i <= n; i++) idx[ch[i]] = i
	}
	!body && /^$/ { body = 1; next }
	body {
		m = split(want, w, " ")
		for (i = 1; i <= m; i++)
			printf "%s%s", (i > 1 ? " " : ""), $(idx[w[i]])
		printf "\n"
	}' "$gb_file"
}

# gb_data FILE: the data lines of an ascii stream (all frames).
gb_data () {
	awk '/^#\?REFLECT/ { body = 0; next } !body && /^$/ { body = 1; next } body' "$1"
}

# bad_scene 'MESSAGE' < scene: reflect-gbuffer refuses the scene with
# status 1 and one line on stderr, "reflect-gbuffer: bad.scene:MESSAGE",
# and writes nothing.
bad_scene () {
	cat >bad.scene &&
	test_expect_code 1 reflect-gbuffer bad.scene >out 2>err &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "^reflect-gbuffer: bad.scene:$1" err &&
	test ! -s out
}

# write_wall_image FILE: a 2x2 float image, texels (1 2 3) (4 5 6) on the
# top row and (7 8 9) (10 11 12) below, for a wall to show.
write_wall_image () {
	cat >wall-image.txt <<-\EOF_IMG &&
	#?REFLECT1
	NCOLS=2
	NROWS=2
	NCOMP=3
	CHANNELS=R G B
	FORMAT=ascii

	1 2 3
	4 5 6
	7 8 9
	10 11 12
	EOF_IMG
	reflect-export -o "$1" wall-image.txt
}
