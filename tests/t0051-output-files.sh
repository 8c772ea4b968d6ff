#!/bin/sh
test_description='every file a tool writes: whole or not at all, and never a hang'
. "$srcdir/tests/lib.sh"

SQ="'"

# Every file output goes to a temporary file beside its path, synced and
# renamed over it (lib/util/output.c): a failed write leaves the old file
# as it was, and a signal removes the temporary file.  A full disk is a
# 64 KB tmpfs where the system lets us mount one, and /dev/full (through
# a link, which is written in place) everywhere.

test_expect_success 'the inputs' '
	reflect-gbuffer -x 400 -y 300 | reflect-project | reflect-shade --size=8 >frame.rfl &&
	reflect-prefilter --size=8 >small-env.rfl
'

# the old file, which a failed write must leave as it was (its copy
# kept off the small disk)
old () {
	echo "the old $1" >"$1" &&
	cp "$1" "$(basename "$1").want"
}

# kept FILE: the old file is whole and nothing else is in its folder
# besides what was there (no hidden temporary file).
kept () {
	cmp "$(basename "$1").want" "$1" &&
	ls -A "$(dirname "$1")" >listing &&
	if grep "^\." listing >hidden
	then
		cat hidden >&2 &&
		false
	fi
}

mounted=
if mkdir disk && mount -t tmpfs -o size=64k tmpfs disk 2>mount.err
then
	mounted=1
fi

# full TOOL ARGS...: the write fails for want of room within 60 s, with
# status 2 and one line saying so.
full () {
	test_expect_code 2 timeout 60 "$@" >out 2>err </dev/null &&
	test_one_line_message "$1" err &&
	test_grep "No space left on device" err
}

if test -n "$mounted"
then
	test_expect_success 'a full disk: every writer fails, the old file stays' '
		old disk/a.png &&
		full reflect-export -c all -o disk/a.exr frame.rfl &&
		full reflect-export --depth=16 -o disk/a.png frame.rfl &&
		kept disk/a.png &&
		old disk/a.tif &&
		full reflect-export --depth=16 -o disk/a.tif frame.rfl &&
		kept disk/a.tif &&
		old disk/heat.png &&
		reflect-shade --size=8 -m none frame.rfl >other.rfl &&
		test_expect_code 2 timeout 60 reflect-compare -o disk/heat.exr frame.rfl other.rfl >out 2>err &&
		test_one_line_message reflect-compare err &&
		test_grep "^reflect-compare: cannot write ${SQ}disk/heat.exr${SQ}: No space left on device$" err &&
		kept disk/heat.png &&
		old disk/m.exr &&
		full reflect-montage -o disk/m.exr A=frame.rfl B=other.rfl &&
		kept disk/m.exr &&
		old disk/env.rfl &&
		full reflect-prefilter --size=64 -o disk/env.rfl &&
		kept disk/env.rfl &&
		old disk/env.exr &&
		full reflect-prefilter --size=128 -o disk/env.exr &&
		kept disk/env.exr &&
		old disk/env.ktx &&
		full reflect-prefilter --size=64 -o disk/env.ktx &&
		kept disk/env.ktx &&
		old disk/env.ktx2 &&
		full reflect-prefilter --size=64 -o disk/env.ktx2 &&
		kept disk/env.ktx2 &&
		old disk/irr.ktx &&
		full reflect-prefilter --size=64 --ktx-texel=float --irradiance=disk/irr.ktx \
			-o disk/env.ktx &&
		kept disk/irr.ktx &&
		old disk/cube.rfl &&
		full reflect-capture -n 64 -o disk/cube.rfl &&
		kept disk/cube.rfl &&
		old disk/cube.exr &&
		full reflect-capture -n 64 -o disk/cube.exr &&
		kept disk/cube.exr
	'
	test_expect_success 'a file that fits is written whole, and replaces the old one' '
		old disk/small.rfl &&
		reflect-prefilter --size=4 -o disk/small.rfl &&
		# the same command line (which the stream keeps) off the small disk
		mkdir -p roomy/disk &&
		(cd roomy && reflect-prefilter --size=4 -o disk/small.rfl) &&
		cmp roomy/disk/small.rfl disk/small.rfl &&
		ls -A disk >listing &&
		! grep "^\." listing
	'
	test_expect_success 'unmount the full disk' '
		umount disk
	'
else
	test_skip 'a full disk: every writer fails, the old file stays' \
		"no tmpfs ($(head -n 1 mount.err 2>/dev/null))"
	test_skip 'a file that fits is written whole, and replaces the old one' 'no tmpfs'
fi

test_expect_success '/dev/full: an error, not a hang' '
	ln -s /dev/full full.exr &&
	ln -s /dev/full full.png &&
	ln -s /dev/full full.ktx &&
	ln -s /dev/full full.rfl &&
	full reflect-prefilter --size=64 -o full.exr &&
	full reflect-prefilter --size=64 -o full.ktx &&
	full reflect-prefilter --size=64 -o full.rfl &&
	full reflect-capture -n 16 -o full.rfl &&
	full reflect-export -c all -o full.exr frame.rfl &&
	full reflect-export -o full.png frame.rfl &&
	test -h full.exr && test -h full.rfl
'

# killed SIGNAL STATUS: reflect-export stopped by SIGNAL in the middle of an
# image, its input a FIFO that gave half a frame; it dies of the signal
# and leaves neither a hidden file nor the image.  (A shell starts a
# background job with SIGINT ignored, which a tool leaves so: env puts
# it back.)
killed () {
	rm -f in && mkfifo in &&
	{ env --default-signal=INT reflect-export -c all -o k.exr in 2>err & } &&
	pid=$! &&
	exec 3>in &&
	size=$(wc -c <frame.rfl) &&
	head -c $((size / 2)) frame.rfl >&3 &&
	n=0 &&
	while ! ls -A | grep "^\.k\..*\.exr$" >/dev/null && test $n -lt 100
	do
		sleep 0.1 && n=$((n + 1)) || return 1
	done &&
	ls -A | grep "^\.k\." >temp &&
	test -s temp &&
	kill -s $1 $pid &&
	{ wait $pid; got=$?; } &&
	exec 3>&- &&
	echo "status $got" &&
	test $got -eq $2 &&
	ls -A >listing &&
	! grep "^\.k\." listing &&
	! test -e k.exr
}

test_expect_success 'SIGTERM, SIGINT, SIGHUP in the middle of an export leave no file' '
	killed TERM 143 &&
	killed INT 130 &&
	killed HUP 129
'

test_done
