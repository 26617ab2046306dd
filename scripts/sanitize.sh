#!/usr/bin/env bash
# Builds the whole test suite (GUI included) with AddressSanitizer and
# UndefinedBehaviorSanitizer into build-asan/ (installing the Debian packages that are
# missing) and runs it with ctest. Any memory error, leak or undefined behaviour fails
# the test it happens in. With gcc, the compiler of the Release build, so that the
# tests' thresholds meet the same arithmetic (under clang 17 of them missed by rounding);
# float-cast-overflow (a NaN converted to int, the fuzzers' first finding) is asked for
# by name, as gcc's -fsanitize=undefined leaves it out. (The fuzzers use clang.)
set -euo pipefail
cd "$(dirname "$0")/.."

source scripts/packages.sh
installMissing "${LAFAIR_LIBRARY_PACKAGES[@]}" g++ \
  libgtest-dev libgmock-dev qt6-base-dev qt6-qpa-plugins fonts-dejavu-core python3 python3-numpy

start=$(date +%s)
# Through the environment, so that the test that builds a consumer of the installed
# package (tests/install) compiles and links it with the same flags.
export CXXFLAGS="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=undefined,float-cast-overflow -fno-omit-frame-pointer"
export LDFLAGS="-fsanitize=address,undefined,float-cast-overflow"
cmake -S . -B build-asan -G Ninja -DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DLAFAIR_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-asan -j2
echo "sanitizer build: $(($(date +%s) - start)) s"

export QT_QPA_PLATFORM=offscreen
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp
status=0
ctest --test-dir build-asan --output-on-failure --timeout 600 -j2 || status=$?  # (--timeout: as scripts/test.sh)
echo "sanitize.sh total: $(($(date +%s) - start)) s"
exit $status
