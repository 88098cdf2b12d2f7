#!/usr/bin/env python3
"""No room of the library reaches up to a room above it (docs/architecture.md, "Layers").

Reads the library's object files with `nm`: every symbol an object of room A uses and an object of
room B defines must have B at or below A in ROOMS. The only crossing allowed is listed in ALLOWED,
with its reason. A room that is not in ROOMS fails the test, so a new room takes its place in the
order on purpose. Usage: layers_test.py OBJECT_DIR (the build's CMakeFiles/lucent_objects.dir).
"""
import os
import subprocess
import sys

# Lowest first (docs/architecture.md).
ROOMS = ["base", "image", "material", "profile", "kernel", "mesh", "cdrf", "scene", "bake", "engine",
         "gl", "trace", "report", "eval"]

# (room of the user, symbol): why it may reach up.
ALLOWED = {
    # The registry of settings groups (src/scene/settings.c) lists the groups that gl and trace
    # declare beside the code that reads them: the scene file's "render" object is their schema, and
    # the scene loader reads it. The settings engine itself (src/base/settings.c) knows no group.
    ("scene", "gl_ssss_settings"): "settings registry",
    ("scene", "gl_translucency_settings"): "settings registry",
    ("scene", "gl_cdrf_settings"): "settings registry",
    ("scene", "gl_points_settings"): "settings registry",
    ("scene", "gl_tsd_settings"): "settings registry",
    ("scene", "gl_burley_settings"): "settings registry",
    ("scene", "tr_trace_settings"): "settings registry",
    ("scene", "lucent_render_method_name"): "settings registry: the method setting's names",
    ("scene", "lucent_render_method_parse"): "settings registry: ssss:svd3 sets the kernel too",
}


def symbols(path):
    out = subprocess.run(["nm", "-g", path], capture_output=True, text=True, check=True).stdout
    defined, used = set(), set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[1] in "TDBRCVW":
            defined.add(parts[2])
        elif len(parts) == 2 and parts[0] == "U":
            used.add(parts[1])
    return defined, used


def main():
    top = os.path.join(sys.argv[1], "src")
    owner, uses = {}, []
    for dirpath, _, files in os.walk(top):
        for f in sorted(files):
            if not f.endswith(".o"):
                continue
            path = os.path.join(dirpath, f)
            room = os.path.relpath(path, top).split(os.sep)[0]
            if room not in ROOMS:
                print(f"FAIL: src/{room}/ is not in the rooms' order (tests/layers_test.py ROOMS)")
                return 1
            defined, used = symbols(path)
            for s in defined:
                owner[s] = room
            uses.append((room, path, used))
    bad = 0
    for room, path, used in uses:
        for s in sorted(used):
            up = owner.get(s)
            if up is None or ROOMS.index(up) <= ROOMS.index(room) or (room, s) in ALLOWED:
                continue
            print(f"FAIL: {room} reaches up to {up}: {os.path.relpath(path, top)} uses {s}")
            bad += 1
    print(f"{len(uses)} objects in {len(ROOMS)} rooms; {bad} upward references")
    return 1 if bad or not uses else 0


if __name__ == "__main__":
    sys.exit(main())
