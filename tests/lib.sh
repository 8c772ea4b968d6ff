# Test library for the shell tests, in the manner of git's t/test-lib.sh:
# every step of a test runs inside test_expect_success, output is TAP.
#
#	test_description='what this file tests'
#	. "$srcdir/tests/lib.sh"
#	test_expect_success 'title' '
#		command && command
#	'
#	test_done

test_count=0
test_failed=0
: "${srcdir:=$(cd "$(dirname "$0")/.." && pwd)}"
: "${builddir:=$srcdir}"
test_name=$(basename "$0" .sh)
TRASH="$builddir/tests/trash-$test_name"
rm -rf "$TRASH" && mkdir -p "$TRASH" || {
	echo "Bail out! cannot make $TRASH"
	exit 1
}
cd "$TRASH" || exit 1
# reflect-shade's cache of prefiltered environments: the test's own,
# never the user's, empty at the start of every test
XDG_CACHE_HOME="$TRASH/.cache"
export XDG_CACHE_HOME
# the user plugin directory ($XDG_DATA_HOME/reflect/plugins): the test's
# own, never the user's
XDG_DATA_HOME="$TRASH/.local/share"
export XDG_DATA_HOME
test_log="$TRASH/.log"

# Seconds a step may take before it is killed and fails: a hang must
# fail its test, never stall the suite.  Steps under valgrind are the
# slowest (some 40 s here); TEST_TIMEOUT overrides.
: "${TEST_TIMEOUT:=300}"

# kill_tree PID: stops PID, kills what it started, then PID itself.
kill_tree () {
	kill -STOP "$1" 2>/dev/null || return 0
	for child in $(ps -o pid= --ppid "$1" 2>/dev/null)
	do
		kill_tree "$child"
	done
	kill -KILL "$1" 2>/dev/null
}

# Runs a step's body in the background with a watchdog that, when the
# step outlives TEST_TIMEOUT, kills it and every command it started (a
# hung tool in a pipeline included).  Returns the body's status, 124 on
# a timeout (as timeout(1) does).
test_run_step () {
	rm -f "$test_log.timeout"
	(eval "$1") >"$test_log" 2>&1 </dev/null &
	step=$!
	(
		trap 'kill $nap 2>/dev/null; exit 0' TERM
		sleep "$TEST_TIMEOUT" &
		nap=$!
		wait $nap
		echo timeout >"$test_log.timeout"
		kill_tree $step
	) >/dev/null 2>&1 &
	watchdog=$!
	wait $step 2>/dev/null
	status=$?
	kill -TERM $watchdog 2>/dev/null
	wait $watchdog 2>/dev/null
	if test -f "$test_log.timeout"
	then
		rm -f "$test_log.timeout"
		echo "timed out after $TEST_TIMEOUT s (TEST_TIMEOUT)" >>"$test_log"
		return 124
	fi
	return $status
}

# Whether every command of a body chains on to the next with &&, as git's
# test-lib.sh checks it: after "(exit 117) &&" a whole chain is skipped
# and the body ends with status 117, but a command that does not chain
# on starts a list of its own, which runs, and the body ends with that
# list's status.  The body's own run would then lose the status of
# every command before the break: the step could pass with a failure in
# it.  (The commands after a break run here, as they would in the step.)
test_chain_intact () {
	test_run_step "(exit 117) && $1
"
	test $? -eq 117
}

# Runs the body in a subshell with set -e semantics left to &&-chains,
# once its chain is found whole; its output goes to the log, shown only
# on failure.
test_expect_success () {
	test_count=$((test_count + 1))
	if ! test_chain_intact "$2"
	then
		test_failed=$((test_failed + 1))
		echo "not ok $test_count - $1"
		echo "# broken &&-chain: a command of this step does not end with &&, so a failure before it would be lost:"
		printf '%s\n' "$2" | sed -e 's/^/#  /'
	elif test_run_step "$2"
	then
		echo "ok $test_count - $1"
	else
		test_failed=$((test_failed + 1))
		echo "not ok $test_count - $1"
		sed -e 's/^/# /' "$test_log"
	fi
}

# Skips a test with a reason (TAP "# SKIP").
test_skip () {
	test_count=$((test_count + 1))
	echo "ok $test_count - $1 # SKIP $2"
}

# test_expect_code STATUS command...: the command exits with that status
# (git's name; a status of 128 or more is a signal's).
test_expect_code () {
	want=$1
	shift
	"$@"
	got=$?
	if test "$got" -ne "$want"
	then
		echo "expected exit status $want, got $got: $*" >&2
		return 1
	fi
	return 0
}

# test_grep PATTERN FILE: the file holds a line matching the (basic) regex.
test_grep () {
	if ! grep -e "$1" "$2" >/dev/null
	then
		echo "no line matches '$1' in $2:" >&2
		cat "$2" >&2
		return 1
	fi
}

# test_line_count N FILE
test_line_count () {
	n=$(wc -l <"$2")
	if test "$n" -ne "$1"
	then
		echo "expected $1 lines in $2, found $n" >&2
		return 1
	fi
}

# A one-line message on stderr, prefixed with the tool's name.
test_one_line_message () {
	test_line_count 1 "$2" && test_grep "^$1: " "$2"
}

test_done () {
	echo "1..$test_count"
	cd "$builddir" || exit 1
	if test "$test_failed" -eq 0
	then
		rm -rf "$TRASH"
		exit 0
	fi
	exit 1
}

# test_cmp_numbers EXPECTED ACTUAL [TOL]: the files hold the same numbers,
# field by field, within an absolute tolerance (default 1e-5); fields that
# are not numbers ("inf", "nan", words) must match exactly.
test_cmp_numbers () {
	awk -v tol="${3:-1e-5}" -v ef="$1" -v af="$2" '
	BEGIN { num = "^[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?$" }
	function bad(msg) { print ef ":" NR ": " msg > "/dev/stderr"; err = 1 }
	{
		if ((getline line < af) <= 0) { bad("missing in " af); exit 1 }
		n = split($0, e); m = split(line, a)
		if (n != m) { bad(n " fields expected, " m " found: " line); next }
		for (i = 1; i <= n; i++) {
			if (e[i] !~ num || a[i] !~ num) {
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

# usage_options TOOL: every option of the tool's usage line, one a line:
# -x letters (split when bundled, as in [-lvV]) and --long names.
usage_options () {
	"$1" --no-such-option 2>&1 >/dev/null |
	sed -n 's/^usage: //p' |
	awk '{
		for (i = 1; i <= NF; i++) {
			w = $i
			gsub(/[][]/, "", w)
			if (w ~ /^--[a-z]/) {
				sub(/[^a-z-].*$/, "", w)
				print w
			} else if (w ~ /^-[A-Za-z]/) {
				for (j = 2; j <= length(w); j++)
					if (substr(w, j, 1) ~ /[A-Za-z]/)
						print "-" substr(w, j, 1)
					else
						break
			}
		}
	}' |
	sort -u
}
