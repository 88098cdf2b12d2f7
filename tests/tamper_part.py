#!/usr/bin/env python3
"""tamper_part.py MODE IN OUT: a damaged copy of an mcml part file (format v2, docs/scale.md), for the merge's
refusals (issue 32 item 9; tests/cli_hostile.sh, tests/hostile_limits.sh). MODE: "max" sets tally 1's first
value to INT64_MAX (two such parts overflow int64 when added), "negative" sets every value of tally 1 to -1,
both with the CRC-32 recomputed so the merge's own checks must find them; "keep-crc" adds 1 to tally 1's second
value and keeps the old CRC-32 (a changed body). The layout read here is the writer's, src/base/dist.c."""
import struct, sys, zlib
mode, src, dst = sys.argv[1:4]
b = bytearray(open(src, "rb").read())
argc = struct.unpack_from("<I", b, 28)[0]  # after the magic (16), order, k and n
at = 32
for _ in range(argc):
    at += 4 + struct.unpack_from("<I", b, at)[0]
at += 4  # the tally count; tally 1 follows: u32 type, u64 count, values
ttype, count = struct.unpack_from("<IQ", b, at)
assert ttype == 0, "tally 1 of an mcml part is I64"
at += 12
if mode == "max":
    struct.pack_into("<q", b, at, 2**63 - 1)
elif mode == "negative":
    for j in range(count):
        struct.pack_into("<q", b, at + 8 * j, -1)
elif mode == "keep-crc":
    struct.pack_into("<q", b, at + 8, struct.unpack_from("<q", b, at + 8)[0] + 1)
if mode != "keep-crc":
    struct.pack_into("<I", b, len(b) - 4, zlib.crc32(bytes(b[:-4])))
open(dst, "wb").write(b)
