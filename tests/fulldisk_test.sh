#!/usr/bin/env bash
# A full disk (issue 17 item 6): a command whose disk fills part-way through its outputs fails (exit 1,
# "No space left on device"), leaves every previous output byte for byte and no temporary, never a mix of
# new and old; once there is room it writes them all. The disk is a small tmpfs: mounting one needs root
# (CAP_SYS_ADMIN); without it the test is skipped (exit 77).
#   tests/fulldisk_test.sh LUCENT FIXTURES
set -u
LUCENT=$1
FIXTURES=$2
fails=0
TMP=$(mktemp -d)
MNT="$TMP/disk"
mkdir -p "$MNT"
if ! mount -t tmpfs -o size=2m lucent-fulldisk "$MNT" 2>/dev/null; then
  echo "skip: cannot mount a tmpfs here (needs root)"
  rm -rf "$TMP"
  exit 77
fi
trap 'umount "$MNT"; rm -rf "$TMP"' EXIT
check() { # check DESCRIPTION COMMAND...
  local d=$1
  shift
  if "$@" >/dev/null 2>&1; then echo "ok   $d"; else echo "FAIL $d"; fails=$((fails + 1)); fi
}
# full_disk NAME FREE_KIB FIRST_COMMAND -- SECOND_COMMAND: FIRST writes the previous outputs into $MNT/NAME;
# then the disk is filled up to FREE_KIB (room for the first new output, not for all) and SECOND must fail
# leaving them as they were; then, with room, SECOND must succeed.
full_disk() {
  local name=$1 free=$2
  shift 2
  local first=() second=()
  while [ "$1" != -- ]; do first+=("$1"); shift; done
  shift
  second=("$@")
  check "$name: the first run writes its outputs" "${first[@]}"
  mkdir -p "$TMP/$name.before" && cp "$MNT/$name"/* "$TMP/$name.before/"
  dd if=/dev/zero of="$MNT/fill" bs=4096 2>/dev/null
  truncate -s -"${free}K" "$MNT/fill"
  local out rc
  out=$("${second[@]}" 2>&1)
  rc=$?
  check "$name on a full disk: exit 1 (got $rc)" test $rc -eq 1
  check "$name on a full disk: the message says so ($out)" grep -q "No space left on device" <<<"$out"
  check "$name on a full disk: the previous outputs, all of them, and nothing else" diff -r "$MNT/$name" "$TMP/$name.before"
  check "$name on a full disk: no 'wrote' line (they come once the outputs have landed)" bash -c "! grep -q '^wrote' <<<\"\$1\"" _ "$out"
  rm -f "$MNT/fill"
  check "$name with room: the outputs are written" "${second[@]}"
  check "$name with room: it says what it wrote" bash -c "\"\$@\" | grep -q '^wrote '" _ "${second[@]}"
  check "$name with room: every output is new" bash -c "for f in '$TMP/$name.before'/*; do ! cmp -s \"\$f\" '$MNT/$name'/\$(basename \"\$f\") || exit 1; done"
}
# trace writes its PNG (861 bytes, one page), EXR, variance EXR (3 KB each) and sidecar: 8 KiB of room holds two.
full_disk trace 8 "$LUCENT" trace "$FIXTURES/scenes/trace-small.json" --spp 2 --seed 1 --out "$MNT/trace/t.png" \
  --exr "$MNT/trace/t.exr" --variance "$MNT/trace/v.exr" -- \
  "$LUCENT" trace "$FIXTURES/scenes/trace-small.json" --spp 3 --seed 2 --out "$MNT/trace/t.png" \
  --exr "$MNT/trace/t.exr" --variance "$MNT/trace/v.exr"
# profile writes JSON (86 KB), CSV (53 KB), SVG (44 KB): 100 KiB of room holds the JSON only.
full_disk profile 100 "$LUCENT" profile marble --model dipole --out "$MNT/profile/p" -- \
  "$LUCENT" profile marble --model better-dipole --out "$MNT/profile/p"
[ $fails -eq 0 ] && echo "all passed" || echo "$fails failed"
[ $fails -eq 0 ]
