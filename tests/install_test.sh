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

# Man pages (one per command, made from its --help), bash completion and the examples (issue 35).
commands=$("$prefix/bin/lucent" --help | awk '/^commands:/ {on = 1; next} on && /^$/ {exit} on {print $1}')
[ "$(wc -w <<<"$commands")" -ge 10 ] || fail "lucent --help lists no commands: $commands"
man1=$prefix/share/man/man1
for page in lucent $(sed 's/^/lucent-/' <<<"$commands"); do
  [ -s "$man1/$page.1" ] || fail "no man page $page.1"
  warnings=$(groff -man -Tutf8 -ww -z "$man1/$page.1" 2>&1) || fail "groff cannot read $page.1"
  [ -z "$warnings" ] || fail "groff warns on $page.1: $warnings"
done
grep -q '^lucent mcml FILE.mci' "$man1/lucent-mcml.1" || fail "lucent-mcml.1's synopsis is not mcml's usage"
"$prefix/bin/lucent" mcml --help | grep -q -- '--out-dir DIR' && grep -q -- '\\-\\-out\\-dir DIR' "$man1/lucent-mcml.1" ||
  fail "lucent-mcml.1 lacks the --help text"
completion=$prefix/share/bash-completion/completions/lucent
got=$(bash -c 'source "$1"; COMP_WORDS=(lucent mc); COMP_CWORD=1; _lucent; echo "${COMPREPLY[*]}";
  COMP_WORDS=(lucent trace --sp); COMP_CWORD=2; _lucent; echo "${COMPREPLY[*]}"' _ "$completion") ||
  fail "the bash completion does not load"
[ "$got" = $'mcml\n--spp' ] || fail "bash completion: 'lucent mc' and 'lucent trace --sp' gave: $got"
share=$prefix/share/lucent
for f in README.md scenes/spheres-skin.json scenes/bunny-skin.json examples/materials/jade.json \
         examples/mcml/vanhulst.mci examples/scenes/trace-small.json; do
  [ -s "$share/$f" ] || fail "share/lucent/$f not installed"
done
"$prefix/bin/lucent" materials "$share/examples/materials/two.json" >/dev/null || fail "the installed example material"
(cd "$tmp" && "$prefix/bin/lucent" -q trace "$share/examples/scenes/trace-small.json" --spp 1 \
  --set render.width=8 --set render.height=8 --out "$tmp/ex/ball.png") || fail "the installed example scene"

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
# Python: the package installed beside the library finds it with only PYTHONPATH set; and
# `pip install ./python` works offline (its build backend needs no index).
if command -v python3 >/dev/null 2>&1; then
  site=$prefix/lib/python3/site-packages
  [ -f "$site/lucent/__init__.py" ] || fail "the Python package is not installed"
  got=$(cd "$tmp" && env -u LUCENT_LIBRARY PYTHONPATH="$site" python3 -c \
    "import lucent; print(lucent.library_path); print(lucent.profile('skin1', model='dipole').rd_total)") ||
    fail "python3 -c 'import lucent' with PYTHONPATH=$site"
  case $(head -1 <<<"$got") in "$prefix"/lib/liblucent.so*) ;; *) fail "python loaded $(head -1 <<<"$got")" ;; esac
  # Skin1's dipole Rd, red (Jensen et al. 2001's closed form, as consumer.c computes it): 0.43596
  grep -q "^(0\.4359" <<<"$(tail -1 <<<"$got")" || fail "python: Skin1's dipole rd_total: $got"
  if python3 -m pip --version >/dev/null 2>&1; then
    LUCENT_BUILD_DIR=$build python3 -m pip install --quiet --no-index --no-deps --target "$tmp/pip" "$src/python" \
      >"$tmp/pip.log" 2>&1 || { cat "$tmp/pip.log"; fail "pip install ./python (offline)"; }
    (cd "$tmp" && env -u LUCENT_LIBRARY PYTHONPATH="$tmp/pip" python3 -c \
      "import lucent, sys; sys.exit(not lucent.library_path.startswith('$tmp/pip/lucent/'))") ||
      fail "the pip-installed package does not load its own liblucent.so"
  fi
fi
echo "install test: ok ($soname)"
