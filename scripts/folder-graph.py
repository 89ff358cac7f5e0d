#!/usr/bin/env python3
"""The folder graph of the C++ sources: which folder includes which (doc/architecture.md, Layout).

Prints the folders floor by floor (a folder stands above every folder it includes) and exits
with 1 when two folders include each other or the includes run in a circle, naming the
includes that do it. A folder is a stage of generator/ (generator/model -> "model"), render/,
or an application of app/ (app/cli -> "app/cli"); an include names its folder first
("section/cross_section.h", "render/...", "app/edit/...").

Usage: scripts/folder-graph.py [REPO]   (default: the repository this script is in)
"""
import collections
import os
import re
import sys

INCLUDE = re.compile(r'\s*#\s*include\s+"([^"]+)"')


def folder_of_file(rel):
    parts = rel.split('/')
    if parts[0] == 'generator':
        return parts[1]
    if parts[0] == 'app':
        return 'app/' + parts[1]
    return parts[0]


def folder_of_include(inc):
    parts = inc.split('/')
    return 'app/' + parts[1] if parts[0] == 'app' else parts[0]


def include_edges(repo):
    """{(from, to): [file -> include, ...]} over every .h and .cpp of generator/, render/, app/."""
    edges = collections.defaultdict(list)
    for top in ('generator', 'render', 'app'):
        for root, _, files in os.walk(os.path.join(repo, top)):
            for name in sorted(files):
                if not name.endswith(('.h', '.cpp')):
                    continue
                path = os.path.join(root, name)
                rel = os.path.relpath(path, repo)
                if rel.count('/') < 2 and top != 'render':
                    continue  # generator/CMakeLists-level files belong to no stage
                src = folder_of_file(rel)
                with open(path, encoding='utf-8', errors='replace') as f:
                    for line in f:
                        m = INCLUDE.match(line)
                        if not m or '/' not in m.group(1):
                            continue
                        dst = folder_of_include(m.group(1))
                        if dst != src:
                            edges[(src, dst)].append(rel + ' -> ' + m.group(1))
    return edges


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))
    edges = include_edges(repo)
    uses = collections.defaultdict(set)
    for a, b in edges:
        uses[a].add(b)
    failed = False
    for (a, b), lines in sorted(edges.items()):
        if a < b and (b, a) in edges:
            failed = True
            print(f'two-way: {a} and {b} include each other')
            for line in lines + edges[(b, a)]:
                print('    ' + line)
    folders = set(x for e in edges for x in e)
    floors, left = [], set(folders)
    while left:
        floor = sorted(f for f in left if not (uses[f] & left))
        if not floor:
            failed = True
            print('circle: ' + ', '.join(sorted(left)) + ' include each other in a circle')
            break
        floors.append(floor)
        left -= set(floor)
    for i in reversed(range(len(floors))):
        print(f'floor {i + 1:2d}  ' + '  '.join(floors[i]))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
