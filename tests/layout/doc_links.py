#!/usr/bin/env python3
"""Checks that every relative link of the documentation resolves.

  python3 tests/layout/doc_links.py [CHECKOUT]

Reads README.md, config/scenes/README.md and every docs/**/*.md of CHECKOUT (default: this
checkout). For each Markdown link or image whose target is not a URL, the file it names must
exist; a #fragment must be the anchor of a heading in the Markdown file it names, as GitHub makes
anchors (lower case, punctuation dropped, spaces as hyphens, -1, -2 for repeats). Links inside code
blocks and code spans are not links.

Prints one line per broken link and exits 1 if there is any, else 0 (doc_links_test).
"""
import glob
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
FENCE = re.compile(r"^```.*?^```", re.S | re.M)


def without_code(text):
    return re.sub(r"`[^`\n]*`", "", FENCE.sub("", text))


def anchor(heading):
    text = heading.strip().lower().replace("`", "")
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors(path):
    found, seen = set(), {}
    for m in re.finditer(r"^#{1,6}\s+(.*)$", FENCE.sub("", open(path, encoding="utf-8").read()), re.M):
        base = anchor(m.group(1))
        n = seen.get(base, 0)
        found.add(base if n == 0 else "%s-%d" % (base, n))
        seen[base] = n + 1
    return found


def broken_links(root):
    files = [os.path.join(root, "README.md"), os.path.join(root, "config", "scenes", "README.md")]
    files += sorted(glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True))
    for path in files:
        if not os.path.exists(path):
            continue
        for m in LINK.finditer(without_code(open(path, encoding="utf-8").read())):
            target = m.group(1)
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):
                continue  # a URL
            name, _, fragment = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(path), name)) if name else path
            where = os.path.relpath(path, root)
            if not os.path.exists(dest):
                yield "%s: %s: no such file" % (where, target)
                continue
            if fragment and dest.endswith(".md") and fragment not in anchors(dest):
                yield "%s: %s: no heading with that anchor" % (where, target)


def main(argv):
    root = os.path.abspath(argv[0]) if argv else ROOT
    broken = list(broken_links(root))
    for line in broken:
        print(line)
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
