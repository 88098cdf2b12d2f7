#!/usr/bin/env bash
# The house style is .clang-format (clang-format 14, Debian 12's). Usage:
#   scripts/format.sh          reformat every tracked C/C++ file in place
#   scripts/format.sh --check  list the files that differ from the style; exit 1 if any do
# Other clang-format versions format a few constructs differently, so the check runs only with 14
# (exit 77: CTest's "skipped").
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null 2>&1 || { echo "format: clang-format not installed"; exit 77; }
version=$(clang-format --version | sed -n 's/.*version \([0-9]*\).*/\1/p')
mapfile -t files < <(git ls-files '*.c' '*.h' '*.cpp' 2>/dev/null || find src include tools tests bench fuzz viewer -name '*.[ch]' -o -name '*.cpp' 2>/dev/null)
if [ "${1:-}" != "--check" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
[ "$version" = 14 ] || { echo "format: clang-format $version is not 14; check skipped"; exit 77; }
bad=0
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "format: $f differs from .clang-format (run scripts/format.sh)"; bad=1
  fi
done
[ $bad = 0 ] && echo "format: ${#files[@]} files follow .clang-format"
exit $bad
