#!/usr/bin/env python3
"""Brume.CoreLayers: the core's four libraries stay layered.

Reads the libraries' files, lowest first, as Modules/Core/CMakeLists.txt
declares them (one line each: NAME FILE...), and fails when a file of
Modules/Core/brume belongs to no library or to two, or includes a header
of a library above its own.

    CheckLayers.py LAYERS_FILE CORE_DIR
"""
import os
import re
import sys


def main(layers_file, core_dir):
    layer_of = {}
    names = []
    with open(layers_file, encoding="utf-8") as lines:
        for line in lines:
            words = line.split()
            if not words:
                continue
            names.append(words[0])
            for path in words[1:]:
                name = os.path.basename(path)
                if name in layer_of:
                    print(f"{name} is in {names[layer_of[name]]} and {words[0]}")
                    return 1
                layer_of[name] = len(names) - 1
    failures = 0
    include = re.compile(r'^\s*#\s*include\s+"(?:brume/)?([A-Za-z0-9_]+\.h)"')
    files = sorted(f for f in os.listdir(os.path.join(core_dir, "brume"))
                   if f.endswith((".h", ".cxx")))
    for name in files:
        if name not in layer_of:
            print(f"brume/{name} belongs to none of the core's libraries "
                  "(add it to one in Modules/Core/CMakeLists.txt)")
            failures += 1
            continue
        with open(os.path.join(core_dir, "brume", name), encoding="utf-8") as source:
            for number, text in enumerate(source, 1):
                match = include.match(text)
                if not match or match.group(1) not in layer_of:
                    continue
                if layer_of[match.group(1)] > layer_of[name]:
                    print(f"brume/{name}:{number} ({names[layer_of[name]]}) includes "
                          f"{match.group(1)} of {names[layer_of[match.group(1)]]}, a library above it")
                    failures += 1
    if failures == 0:
        print(f"{len(files)} files in {len(names)} libraries, "
              f"{' < '.join(names)}: every include at or below its own")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
