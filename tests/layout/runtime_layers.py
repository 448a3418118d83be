#!/usr/bin/env python3
"""The runtime's layers include downwards only.

runtime/ is five layers, lowest first: types, component, dds, scene, launch (runtime/CMakeLists.txt
says what each holds). Each is a folder with include/uampc/runtime/ and src/. A file of one layer may
include the headers of its own layer and of lower ones, never of a higher one: then each layer can
be read, tested and changed knowing only what lies below it.

  python3 tests/layout/runtime_layers.py [RUNTIME_DIR]   prints each include that runs back up; exit 1 if any
"""
import os
import re
import sys

LAYERS = ["types", "component", "dds", "scene", "launch"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def headers_by_layer(runtime_dir):
    """{header include name: layer}: 'uampc/runtime/x.hpp' for public headers, 'x.hpp' for private ones."""
    owner = {}
    for layer in LAYERS:
        public = os.path.join(runtime_dir, layer, "include", "uampc", "runtime")
        private = os.path.join(runtime_dir, layer, "src")
        for folder, prefix in ((public, "uampc/runtime/"), (private, "")):
            if os.path.isdir(folder):
                for name in os.listdir(folder):
                    if name.endswith(".hpp"):
                        owner[prefix + name] = layer
    return owner


def violations(runtime_dir):
    """Lines 'file:line: includes X of layer L from layer M', one per include that runs back up."""
    owner = headers_by_layer(runtime_dir)
    found = []
    for layer in LAYERS:
        for root, _, files in os.walk(os.path.join(runtime_dir, layer)):
            for name in sorted(files):
                if not name.endswith((".cpp", ".hpp")):
                    continue
                path = os.path.join(root, name)
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for match in INCLUDE.finditer(text):
                    target = match.group(1)
                    target_layer = owner.get(target)
                    if target_layer and LAYERS.index(target_layer) > LAYERS.index(layer):
                        line = text.count("\n", 0, match.start()) + 1
                        found.append(f"{os.path.relpath(path, runtime_dir)}:{line}: includes {target} of layer "
                                     f"'{target_layer}' from layer '{layer}'")
    return found


def main(argv):
    runtime_dir = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..", "runtime")
    for layer in LAYERS:
        if not os.path.isdir(os.path.join(runtime_dir, layer)):
            print(f"runtime_layers: {runtime_dir} has no layer folder '{layer}'", file=sys.stderr)
            return 2
    found = violations(runtime_dir)
    for v in found:
        print(v)
    if found:
        print(f"runtime_layers: {len(found)} include(s) run back up a layer", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
