"""runtime_layers.py finds an include that runs back up, and the runtime has none."""
import os
import tempfile
import unittest

import runtime_layers

RUNTIME = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "runtime")


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


class RuntimeLayers(unittest.TestCase):
    def test_the_runtime_includes_downwards_only(self):
        self.assertEqual(runtime_layers.violations(RUNTIME), [])

    def test_an_include_of_a_higher_layer_is_found(self):
        with tempfile.TemporaryDirectory() as root:
            for layer in runtime_layers.LAYERS:
                os.makedirs(os.path.join(root, layer, "src"))
            write(os.path.join(root, "scene", "include", "uampc", "runtime", "scene.hpp"), "#pragma once\n")
            write(os.path.join(root, "launch", "src", "helper.hpp"), "#pragma once\n")
            write(os.path.join(root, "dds", "src", "node.cpp"),
                  '#include "uampc/runtime/scene.hpp"\n#include <vector>\n')
            write(os.path.join(root, "launch", "src", "launcher.cpp"),
                  '#include "uampc/runtime/scene.hpp"\n#include "helper.hpp"\n')
            found = runtime_layers.violations(root)
            self.assertEqual(found, ["dds/src/node.cpp:1: includes uampc/runtime/scene.hpp of layer 'scene' "
                                     "from layer 'dds'"])


if __name__ == "__main__":
    unittest.main()
