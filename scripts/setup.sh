# Sourced by ./demo and ./run-tests: installs what the build needs and
# builds, doing only the steps that are not done yet.
# Needs: $top (the source tree).

setup_say () {
	printf '%s\n' "$*" >&2
}

# Debian packages the build and the tests need.
setup_packages="autoconf automake libtool pkg-config make gcc g++ \
libopenimageio-dev libopenexr-dev libpng-dev libzstd-dev libembree-dev \
libassimp-dev"
# Used by some tests when present (they skip otherwise).
setup_optional_packages="python3-numpy valgrind clang strace parallel chromium firefox-esr"

setup_missing () {
	missing=""
	command -v autoreconf >/dev/null 2>&1 || missing="$missing autoconf"
	command -v automake >/dev/null 2>&1 || missing="$missing automake"
	command -v libtoolize >/dev/null 2>&1 || missing="$missing libtool"
	command -v pkg-config >/dev/null 2>&1 || missing="$missing pkg-config"
	command -v make >/dev/null 2>&1 || missing="$missing make"
	command -v gcc >/dev/null 2>&1 || missing="$missing gcc"
	command -v g++ >/dev/null 2>&1 || missing="$missing g++"
	if command -v pkg-config >/dev/null 2>&1
	then
		pkg-config --exists OpenImageIO || missing="$missing libopenimageio-dev"
		pkg-config --exists 'OpenEXR >= 3.1' || missing="$missing libopenexr-dev"
		pkg-config --exists libpng || missing="$missing libpng-dev"
		pkg-config --exists libzstd || missing="$missing libzstd-dev"
		pkg-config --exists 'assimp >= 5.2' || missing="$missing libassimp-dev"
	else
		missing="$missing libopenimageio-dev libopenexr-dev libpng-dev libzstd-dev libassimp-dev"
	fi
	# Embree 3 ships no pkg-config file: its header, through the
	# preprocessor that will build against it.
	echo '#include <embree3/rtcore.h>' | ${CC:-cc} -E - >/dev/null 2>&1 ||
		missing="$missing libembree-dev"
	echo $missing
}

setup_optional_missing () {
	missing=""
	/usr/bin/python3 -c 'import numpy' >/dev/null 2>&1 || missing="$missing python3-numpy"
	command -v valgrind >/dev/null 2>&1 || missing="$missing valgrind"
	command -v clang >/dev/null 2>&1 || missing="$missing clang"
	# libFuzzer's runtime, for make fuzz
	command -v clang >/dev/null 2>&1 &&
		test -f "$(clang -print-file-name=libclang_rt.fuzzer-x86_64.a)" ||
		missing="$missing libclang-rt-14-dev"
	command -v strace >/dev/null 2>&1 || missing="$missing strace"
	# GNU parallel, for the farm recipes (doc/farm.md); moreutils has
	# another program of that name
	parallel --version 2>/dev/null | grep -q 'GNU parallel' ||
		missing="$missing parallel"
	# reflect-report's page, tested in a real browser
	command -v chromium >/dev/null 2>&1 || missing="$missing chromium"
	command -v firefox >/dev/null 2>&1 || missing="$missing firefox-esr"
	echo $missing
}

setup_install () {
	need=$(setup_missing)
	want="$need"
	test "${1:-}" = with-optional && want="$want $(setup_optional_missing)"
	want=$(echo $want)
	test -n "$want" || return 0
	if test "$(id -u)" -eq 0 && command -v apt-get >/dev/null 2>&1
	then
		setup_say "setup: installing $want"
		export DEBIAN_FRONTEND=noninteractive
		apt-get update -qq >/dev/null 2>&1 || apt-get update || return 1
		apt-get install -y -qq $want >/dev/null || apt-get install -y $want || {
			test -n "$need" && return 1
			setup_say "setup: optional packages could not be installed; tests that need them skip"
		}
		return 0
	fi
	test -n "$need" || return 0
	setup_say "setup: missing build dependencies: $need"
	setup_say "setup: install them with: sudo apt-get install $need"
	return 1
}

setup_build () {
	cd "$top" || return 1
	if ! test -x configure || test configure.ac -nt configure || test Makefile.am -nt configure
	then
		setup_say "setup: autoreconf"
		autoreconf -fi >autoreconf.log 2>&1 || {
			cat autoreconf.log >&2
			return 1
		}
	fi
	if ! test -f config.status || test configure -nt config.status
	then
		setup_say "setup: configure"
		./configure ${REFLECT_CONFIGURE_FLAGS:-} >configure.log 2>&1 || {
			tail -20 configure.log >&2
			return 1
		}
	fi
	setup_say "setup: make"
	make -j"$(nproc 2>/dev/null || echo 2)" >make.log 2>&1 || {
		tail -40 make.log >&2
		return 1
	}
}
