#!/bin/sh
test_description='a binary stream or image is not written to a terminal'
. "$srcdir/tests/lib.sh"

# As gzip and zstd refuse to write compressed data to a terminal: floats
# would garble it.  -fa (text) is written.  ontty runs a command with its
# standard output on a pseudo-terminal and prints its exit status and the
# number of bytes that reached the terminal.

PY=
for p in "${PYTHON3:-}" /usr/bin/python3 python3
do
	test -n "$p" && command -v "$p" >/dev/null 2>&1 && { PY=$p; break; }
done

cat >ontty.py <<'PYEOF'
import os, pty, select, subprocess, sys
master, slave = pty.openpty()
p = subprocess.Popen(sys.argv[1:], stdin=subprocess.DEVNULL, stdout=slave,
                     stderr=open("err", "wb"))
os.close(slave)
n = 0
while True:
    r, _, _ = select.select([master], [], [], 0.2)
    if r:
        try:
            data = os.read(master, 65536)
        except OSError:
            break
        if not data:
            break
        n += len(data)
    elif p.poll() is not None:
        break
p.wait(timeout=20)
print(p.returncode, n)
PYEOF

# refused_on_tty TOOL ARGS...: status 1, one line, nothing on the terminal.
refused_on_tty () {
	timeout 30 $PY ontty.py "$@" >result &&
	echo "1 0" >expect &&
	test_cmp_numbers expect result &&
	test_one_line_message "$1" err &&
	test_grep "is not written to a terminal: send standard output to a file or a pipe" err
}

if test -z "$PY"
then
	test_skip 'binary streams and images refused on a terminal' 'no python3'
	test_done
fi

test_expect_success 'the inputs' '
	reflect-gbuffer -x 4 -y 3 >g.rfl &&
	reflect-prefilter --size=4 >env.rfl
'

test_expect_success 'a binary stream to a terminal is refused, by every tool that writes one' '
	refused_on_tty reflect-gbuffer -x 4 -y 3 &&
	test_grep "(-fa writes text)" err &&
	refused_on_tty reflect-gbuffer -x 4 -y 3 -h &&
	refused_on_tty reflect-trace -x 4 -y 3 --samples=1 &&
	refused_on_tty reflect-project g.rfl &&
	reflect-project g.rfl >p.rfl &&
	refused_on_tty reflect-shade --env=env.rfl p.rfl &&
	reflect-shade --env=env.rfl p.rfl >s.rfl &&
	refused_on_tty reflect-occlude s.rfl &&
	refused_on_tty reflect-accumulate s.rfl &&
	refused_on_tty reflect-filter s.rfl &&
	refused_on_tty reflect-capture -n 4 &&
	refused_on_tty reflect-prefilter --size=4 &&
	reflect-export -c all -o g.exr g.rfl &&
	refused_on_tty reflect-import g.exr
'

test_expect_success 'an image to a terminal is refused' '
	refused_on_tty reflect-export -c albedo.R,albedo.G,albedo.B -o - g.rfl &&
	refused_on_tty reflect-export -c all -o exr:- g.rfl
'

test_expect_success 'text (-fa) goes to a terminal, and so do the tools that write text' '
	timeout 30 $PY ontty.py reflect-gbuffer -x 2 -y 2 -fa -c mask >result &&
	read status bytes <result &&
	test "$status" -eq 0 && test "$bytes" -gt 10 &&
	timeout 30 $PY ontty.py reflect-info g.rfl >result &&
	read status bytes <result &&
	test "$status" -eq 0 && test "$bytes" -gt 10 &&
	timeout 30 $PY ontty.py reflect-export -o x.png -c albedo.R,albedo.G,albedo.B g.rfl >result &&
	read status bytes <result &&
	test "$status" -eq 0 && test -s x.png &&
	timeout 30 $PY ontty.py reflect-compare g.rfl g.rfl -c mask >result &&
	read status bytes <result &&
	test "$status" -eq 0 && test "$bytes" -gt 10 &&
	timeout 30 $PY ontty.py reflect-prefilter --size=4 -o e.ktx >result &&
	read status bytes <result &&
	test "$status" -eq 0 && test -s e.ktx
'

test_expect_success 'a pipe or a file is written as before' '
	reflect-gbuffer -x 4 -y 3 | cmp - g.rfl
'

test_done
