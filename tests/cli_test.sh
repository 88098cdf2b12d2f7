#!/usr/bin/env bash
# Tests of the `lucent` command as a user meets it: exit codes, messages that name the
# file and the field, outputs that are complete or absent. Each tests/cli_*.sh adds cases.
# Usage: cli_test.sh path/to/lucent path/to/tests/fixtures
set -u
LUCENT=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") # absolute: some cases cd elsewhere
FIXTURES=$(cd "$2" && pwd)
TESTS=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/lucent-cli-XXXXXX")
chmod 755 "$TMP"
passed=0 failed=0
# Commands that open a GL context. Under the sanitizers CMake names Mesa's driver to preload
# (see tests/CMakeLists.txt) so LeakSanitizer does not report the blocks of a dlclosed driver.
GLRUN=("$LUCENT")
if [ -n "${LUCENT_GL_PRELOAD:-}" ]; then
  GLRUN=(env "LD_PRELOAD=$LUCENT_GL_PRELOAD" "ASAN_OPTIONS=${ASAN_OPTIONS:-}:verify_asan_link_order=0" "$LUCENT")
fi

_report() { # OK? DESCRIPTION [DETAIL]
  if [ "$1" = 1 ]; then
    passed=$((passed + 1)); echo "ok   $2"
  else
    failed=$((failed + 1)); echo "FAIL $2"; [ -n "${3:-}" ] && printf '%s\n' "$3" | sed 's/^/     /'
  fi
}

# expect_fail CODE SUBSTRING -- command args...: exits CODE and stderr contains SUBSTRING.
expect_fail() {
  local code=$1 sub=$2; shift 3
  local out rc
  out=$("$@" 2>&1 >/dev/null); rc=$?
  if [ "$rc" = "$code" ] && [[ "$out" == *"$sub"* ]]; then
    _report 1 "fails $code '$sub': ${*#$LUCENT }"
  else
    _report 0 "fails $code '$sub': ${*#$LUCENT }" "exit $rc, stderr: $out"
  fi
}

# expect_ok -- command args...: exits 0. Its stdout is kept in $OUT.
expect_ok() {
  shift
  local rc err
  OUT=$("$@" 2>"$TMP/.stderr"); rc=$?
  err=$(cat "$TMP/.stderr")
  if [ "$rc" = 0 ]; then _report 1 "runs: ${*#$LUCENT }"; else _report 0 "runs: ${*#$LUCENT }" "exit $rc: $err"; fi
}

# expect_true DESCRIPTION -- command args...: the command (a check) succeeds.
expect_true() {
  local what=$1; shift 2
  if "$@" >/dev/null 2>&1; then _report 1 "$what"; else _report 0 "$what"; fi
}

# expect_no_file PATH...: nothing (not even a temporary) was left at PATH or beside it.
expect_no_file() {
  local p
  for p in "$@"; do
    if ls "$p" "$p".tmp* >/dev/null 2>&1; then _report 0 "no output left at $p"; else _report 1 "no output left at $p"; fi
  done
}

# as_nobody command args...: runs the command as an unprivileged user when we are root
# (root ignores directory permissions, so read-only directories need another user).
as_nobody() {
  if [ "$(id -u)" = 0 ] && command -v setpriv >/dev/null 2>&1; then
    setpriv --reuid=65534 --regid=65534 --clear-groups "$@"
  else
    "$@"
  fi
}

# ---- the command itself ---- (mpi_test.sh cuts its harness at this line)
expect_ok -- "${GLRUN[@]}" --version # it opens a GL context to name the renderer
expect_true "--version prints the version" -- grep -q "^lucent [0-9]\+\.[0-9]\+\.[0-9]\+$" <<<"$OUT"
expect_ok -- "$LUCENT" --help
for cmd in $(awk '/^commands:/{f=1;next} f&&/^$/{exit} f{print $1}' <<<"$OUT"); do
  expect_ok -- "$LUCENT" "$cmd" --help
  expect_true "'$cmd --help' shows usage" -- grep -qi "usage" <<<"$OUT"
done
expect_fail 2 "unknown command 'frobnicate'" -- "$LUCENT" frobnicate
expect_fail 2 "usage" -- "$LUCENT"
expect_fail 2 "--threads needs a positive whole number" -- "$LUCENT" materials --threads zero

for snippet in "$TESTS"/cli_*.sh; do
  [ "$snippet" = "$TESTS/cli_test.sh" ] && continue
  # shellcheck source=/dev/null
  . "$snippet"
done

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && rm -rf "$TMP"
[ "$failed" -eq 0 ]
