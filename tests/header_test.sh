#!/usr/bin/env bash
# Compiles every public header on its own, as C11 and as C++, with strict warnings.
# Usage: header_test.sh INCLUDE_DIR CC CXX
set -u
inc=$1 cc=$2 cxx=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
check() { # LABEL COMPILER ARGS...
  local label=$1; shift
  if "$@" -o "$tmp/t.o" 2>"$tmp/err"; then
    pass=$((pass + 1))
  else
    fail=$((fail + 1)); echo "FAIL $label: $name"; cat "$tmp/err"
  fi
}
flags=(-Wall -Wextra -Werror -Wstrict-prototypes -I"$inc" -c)
cxxflags=(-Wall -Wextra -Werror -I"$inc" -c)
for h in "$inc"/lucent/*.h; do
  name=lucent/$(basename "$h")
  printf '#include "%s"\n#include "%s"\nint lucent_header_test_dummy;\n' "$name" "$name" > "$tmp/t.c"
  cp "$tmp/t.c" "$tmp/t.cpp"
  check "C11 ($cc)" "$cc" -std=c11 -pedantic "${flags[@]}" "$tmp/t.c"
  # g++ rejects the C-only -Wstrict-prototypes under -Werror; clang++ accepts it.
  check "C++11 ($cxx)" "$cxx" -std=c++11 -pedantic "${cxxflags[@]}" "$tmp/t.cpp"
  if command -v clang++ >/dev/null 2>&1; then
    check "C++11 (clang++)" clang++ -std=c++11 -pedantic "${flags[@]}" "$tmp/t.cpp"
  fi
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
