#!/bin/sh
# chainlint FILE...: in the bodies of test_expect_success, every loop's
# last command must end with "|| return 1", as git's chainlint wants: a
# failure inside a loop is otherwise lost to the next iteration, and the
# step passes.  A nested loop's "done || return 1" counts as such a
# command.  Prints FILE:LINE for each loop that breaks the rule and exits
# 1 if any does.
awk '
# "cmd || return 1", "cmd ||" then "return 1", or a block that ends in
# "return 1" or "exit 1" and closes with "}".
function chained(last, prev) {
	return last ~ /\|\|[ \t]*return[ \t]+1$/ ||
	       (last == "return 1" && prev ~ /\|\|$/) ||
	       (last == "}" && prev ~ /(return|exit)[ \t]+1;?$/)
}
function report(line) {
	printf "%s:%d: the loop ending here does not end its last command with \"|| return 1\"\n",
		FILENAME, line
	bad = 1
}
FNR == 1 { body = 0; depth = 0; heredoc = "" }
# A step opens with test_expect_success TITLE followed by a quote that
# ends its line, and closes on a line holding the quote alone.
!body && /^[ \t]*test_expect_success .*[ \t]'\''$/ { body = 1; depth = 0; last = ""; next }
body && /^[ \t]*'\''[ \t]*$/ { body = 0; next }
!body { next }
{
	line = $0
	sub(/[ \t]+$/, "", line)
	stripped = line
	sub(/^[ \t]+/, "", stripped)
	# A here-document is data: the command is the line that opens it.
	if (heredoc != "") {
		if (stripped == heredoc)
			heredoc = ""
		next
	}
	if (match(stripped, /<<-?[\\'\''"]?[A-Za-z_]+/)) {
		heredoc = substr(stripped, RSTART, RLENGTH)
		sub(/^<<-?[\\'\''"]?/, "", heredoc)
	}
	if (stripped == "" || stripped ~ /^#/)
		next
	if (stripped ~ /^(for|while|until)[ \t]/ && stripped !~ /;[ \t]*done/)
		opened[++depth] = FNR
	if (stripped ~ /^done([ \t]|$)/) {
		if (depth > 0 && !chained(last, prev))
			report(FNR)
		if (depth > 0)
			depth--
	}
	prev = last
	last = stripped
}
END { exit bad }
' "$@"
