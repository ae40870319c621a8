#!/usr/bin/env python3
"""Checks the relative links of README.md and docs/*.md: every link and image points to a file
of this repository (never outside it), and a link's #anchor names a heading of its Markdown
target (GitHub's heading slugs, or an <a id=...>). Prints each broken link; exit status 1 if there is any.

Usage: python3 docs/tools/check_links.py   (from anywhere)
"""
import glob
import os
import re
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
FENCE = re.compile(r"^(```|~~~)")


def slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def anchors(path):
    out, fenced = set(), False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if FENCE.match(line):
                fenced = not fenced
            elif not fenced and line.startswith("#"):
                out.add(slug(line.lstrip("#")))
            if not fenced:
                out.update(re.findall(r'<a (?:id|name)="([^"]+)"', line))
    return out


def links(path):
    fenced = False
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if not fenced:
                for m in LINK.finditer(line):
                    yield n, m.group(1)


def main():
    files = [os.path.join(ROOT, "README.md")] + sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")))
    bad = 0
    for f in files:
        for n, target in links(f):
            if re.match(r"^[a-z]+:", target):
                continue  # http:, https:, mailto:
            path, _, anchor = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(f), path)) if path else f
            where = f"{os.path.relpath(f, ROOT)}:{n}: {target}"
            if not (dest == ROOT or dest.startswith(ROOT + os.sep)):
                print(f"{where}: points outside the repository")
                bad += 1
            elif not os.path.exists(dest):
                print(f"{where}: no such file")
                bad += 1
            elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
                print(f"{where}: no heading #{anchor}")
                bad += 1
    print(f"{len(files)} files checked, {bad} broken links")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
