#!/usr/bin/env bash
# Installs the build into a temporary prefix (what `make install PREFIX=...` does) and builds a C
# and a C++ program against it: with pkg-config (shared, then static with the private dependencies)
# and with CMake's find_package(Lucent); runs each, and the installed `lucent`. Nothing but
# PKG_CONFIG_PATH / CMAKE_PREFIX_PATH points at the prefix: the programs run as built (rpath).
# Usage: install_test.sh BUILD_DIR SOURCE_DIR CC CXX
set -euo pipefail
build=$1 src=$2 cc=$3 cxx=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" >"$tmp/install.log" || { cat "$tmp/install.log"; exit 1; }
fail() { echo "FAIL: $*"; exit 1; }
for f in bin/lucent include/lucent/lucent.h lib/liblucent.a lib/pkgconfig/lucent.pc \
         lib/cmake/Lucent/LucentConfig.cmake; do
  [ -e "$prefix/$f" ] || fail "$f not installed"
done
so=$(readlink -f "$prefix/lib/liblucent.so")
soname=$(objdump -p "$so" | awk '/SONAME/ {print $2}')
[ -e "$prefix/lib/$soname" ] || fail "soname $soname not installed"
case $so in *.so.[0-9]*.[0-9]*.[0-9]*) ;; *) fail "liblucent.so has no version: $so" ;; esac
"$prefix/bin/lucent" --version | grep -q '^lucent [0-9]' || fail "installed lucent --version"

export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
inc=$src/tests/install
# pkg-config, shared.
"$cc" -std=c11 -Wall -Wextra -Werror "$inc/consumer.c" $(pkg-config --cflags --libs lucent) -lm -o "$tmp/c_shared"
"$cxx" -Wall -Wextra -Werror "$inc/consumer.cpp" $(pkg-config --cflags --libs lucent) -o "$tmp/cpp_shared"
objdump -p "$tmp/c_shared" | grep -q "NEEDED.*$soname" || fail "the pkg-config program does not load $soname"
"$tmp/c_shared" && "$tmp/cpp_shared" || fail "programs built with pkg-config"
# pkg-config --static: the archive and every private dependency.
static_libs=$(pkg-config --static --libs lucent | sed 's/-llucent\b/-l:liblucent.a/')
"$cc" -std=c11 -Wall -Wextra -Werror "$inc/consumer.c" $(pkg-config --cflags lucent) $static_libs -o "$tmp/c_static"
objdump -p "$tmp/c_static" | grep -q "NEEDED.*liblucent" && fail "the static program loads liblucent.so"
"$tmp/c_static" || fail "program built with pkg-config --static"
# CMake.
cmake -S "$inc" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" \
  -DCMAKE_CXX_COMPILER="$cxx" >"$tmp/cm.log" 2>&1 || { cat "$tmp/cm.log"; fail "cmake configure"; }
cmake --build "$tmp/cm" >"$tmp/cmb.log" 2>&1 || { cat "$tmp/cmb.log"; fail "cmake build"; }
"$tmp/cm/consumer_c" && "$tmp/cm/consumer_cpp" || fail "programs built with CMake"
echo "install test: ok ($soname)"
