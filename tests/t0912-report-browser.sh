#!/bin/sh
test_description='reflect-report'"'"'s page in real browsers: headless Chromium and Firefox run its self-test and take screenshots'
. "$srcdir/tests/lib.sh"
. "$srcdir/tests/shade-lib.sh"

# Debian's package is chromium (scripts/setup.sh installs it with the
# optional tools); other systems name it otherwise.
browser=
for b in chromium chromium-browser google-chrome
do
	if command -v $b >/dev/null 2>&1
	then
		browser=$b
		break
	fi
done
firefox=
for b in firefox firefox-esr
do
	if command -v $b >/dev/null 2>&1
	then
		firefox=$b
		break
	fi
done

# chrome ARGS...: headless, its profile the test's own, console messages
# on stderr (as INFO:CONSOLE lines)
chrome () {
	"$browser" --headless --disable-gpu --no-sandbox --no-first-run \
		--user-data-dir="$TRASH/profile" --enable-logging=stderr --v=0 \
		--virtual-time-budget=10000 "$@"
}

# selftest PAGE: the page's verdict on itself, as its DOM holds it;
# stderr (the console) in console.log
selftest () {
	chrome --dump-dom "file://$TRASH/$1#selftest" >dom 2>chrome.log &&
	sed -n 's|.*<pre id="selftest">\([^<]*\)</pre>.*|\1|p' dom >verdict &&
	{ grep "CONSOLE" chrome.log || :; } >console.log &&
	test -s verdict
}

picture () {
	awk -v w=$2 -v h=$3 'BEGIN {
		for (y = 0; y < h; y++)
			for (x = 0; x < w; x++) {
				hh = ((x * 7919 + y * 104729) % 1000) / 1000
				'"$4"'
				print r, g, b
			}
	}' | stream "$1" $2 $3 "R G B"
}

test_expect_success 'set up a page of three modes, linear, and one of display pictures' '
	picture truth.rfl 48 32 "r = 0.2 + x / 20; g = 0.1 + y / 30; b = 0.3 + hh" &&
	picture bright.rfl 48 32 "r = 0.45 + x / 20; g = 0.35 + y / 30; b = 0.55 + hh" &&
	picture noisy.rfl 48 32 "r = 0.2 + x / 20 + 0.2 * hh; g = 0.1 + y / 30; b = 0.3 + hh / 2" &&
	picture flat.rfl 48 32 "r = 0.9; g = 0.6; b = 0.8" &&
	# a name that HTML and JSON must both escape: the self-test finds it
	# in the table as the script knows it
	reflect-report -o page.html --caption="<flat & \"mean\">=the mean" --time=noisy=3 \
		truth.rfl bright=bright.rfl noisy=noisy.rfl "<flat & \"mean\">=flat.rfl" &&
	reflect-export -o truth.png truth.rfl &&
	reflect-export -o noisy.png noisy.rfl &&
	reflect-report -o ldr.html truth.png noisy=noisy.png
'

if test -n "$browser"
then
	test_expect_success 'the page passes its self-test: pictures decoded, keys, slider, table, zoom' '
		selftest page.html &&
		cat verdict &&
		test_grep "^selftest: pass, [0-9]* checks$" verdict &&
		# the count and 46 pictures (32 stored, 3 maps, 11 in the
		# viewer), 4 of the table, the rest for keys, wipe, zoom, pan,
		# exposure, sort: none left out
		test $(sed "s/.* \([0-9]*\) checks/\1/" verdict) -ge 60 &&
		test_line_count 0 console.log
	'

	test_expect_success 'display pictures, one exposure, one mode: the self-test passes' '
		selftest ldr.html &&
		cat verdict &&
		test_grep "^selftest: pass, [0-9]* checks$" verdict &&
		test_line_count 0 console.log
	'

	test_expect_success 'fewer exposures (--stops), the first the highest or the only: the self-test passes' '
		reflect-report -o low.html --stops=-2,0 truth.rfl bright=bright.rfl noisy=noisy.rfl &&
		selftest low.html &&
		cat verdict &&
		test_grep "^selftest: pass, [0-9]* checks$" verdict &&
		test_line_count 0 console.log &&
		reflect-report -o one.html --stops=1,1 truth.rfl noisy=noisy.rfl &&
		selftest one.html &&
		cat verdict &&
		test_grep "^selftest: pass, [0-9]* checks$" verdict &&
		test_line_count 0 console.log &&
		# one exposure of linear pictures is still named as one
		test_grep "<span id=\"exposure-value\">+1 stop</span>" dom &&
		selftest ldr.html &&
		test_grep "<span id=\"exposure-value\">display pictures</span>" dom
	'

	test_expect_success 'the self-test sees a picture that does not decode' '
		sed "s|\(<img id=\"shot-2-4\" [^>]*src=\"data:image/png;base64,\)[^\"]*|\1AAAA|" \
			page.html >broken.html &&
		! cmp page.html broken.html &&
		selftest broken.html &&
		test_grep "^selftest: FAIL .*image shot-2-4 is not decoded" verdict
	'

	test_expect_success 'the self-test sees keys that show nothing new' '
		sed "s|st.a = +k;|st.a = st.a;|" page.html >broken.html &&
		! cmp page.html broken.html &&
		selftest broken.html &&
		test_grep "^selftest: FAIL .*key 1 does not show mode 1" verdict
	'

	test_expect_success 'the self-test sees a wipe that does not wipe' '
		sed "s|st.wipe = +this.value;|st.wipe = 100;|" page.html >broken.html &&
		! cmp page.html broken.html &&
		selftest broken.html &&
		test_grep "^selftest: FAIL .*the slider does not move the wipe" verdict
	'

	test_expect_success 'the self-test and the console see an error in the page' '
		sed "s|</body>|<script>noSuchFunction();</script></body>|" page.html >broken.html &&
		selftest broken.html &&
		test_grep "^selftest: FAIL .*noSuchFunction" verdict &&
		test_grep "noSuchFunction" console.log
	'

	test_expect_success 'a screenshot of the page is no blank' '
		chrome --screenshot="$TRASH/shot.png" --window-size=1000,900 "file://$TRASH/page.html" \
			>/dev/null 2>&1 &&
		reflect-info -s shot.png >info &&
		test_grep "^	NCOLS=1000$" info &&
		test_grep "^	NROWS=900$" info &&
		# every channel from black (the views) to white (the table), and
		# the pictures colour
		for c in R G B
		do
			grep "^	$c " info | awk "{ exit !(\$2 < 0.05 && \$3 > 0.95) }" || return 1
		done
	'

else
	test_skip 'the page passes its self-test in Chromium' 'no chromium (apt-get install chromium)'
fi

# Firefox headless takes screenshots but hands back no page: the page
# opened as #selftest-colour turns pure green for a pass, red for a
# failure.
if test -n "$firefox"
then
	# firefox_verdict PAGE: the colour of the page, as "R G B" of its
	# screenshot's smallest and largest values
	firefox_verdict () {
		rm -f ff.png &&
		mkdir -p "$TRASH/ffprofile" &&
		"$firefox" --headless --no-remote --profile "$TRASH/ffprofile" \
			--screenshot "$TRASH/ff.png" --window-size=400,300 \
			"file://$TRASH/$1#selftest-colour" >firefox.log 2>&1 &&
		reflect-info -s ff.png >info &&
		grep "^	[RGB] " info | awk "{ print \$1, \$2, \$3 }" >verdict
	}

	test_expect_success 'Firefox: the page passes its self-test (green)' '
		firefox_verdict page.html &&
		printf "%s\n" "R 0 0" "G 1 1" "B 0 0" >green &&
		diff -u green verdict &&
		firefox_verdict ldr.html &&
		diff -u green verdict
	'

	test_expect_success 'Firefox: a page whose keys are dead fails it (red)' '
		sed "s|st.a = +k;|st.a = st.a;|" page.html >broken.html &&
		firefox_verdict broken.html &&
		printf "%s\n" "R 1 1" "G 0 0" "B 0 0" >red &&
		diff -u red verdict
	'
else
	test_skip 'the page passes its self-test in Firefox' 'no firefox (apt-get install firefox-esr)'
fi

test_done
