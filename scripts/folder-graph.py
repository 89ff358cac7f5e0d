#!/usr/bin/env python3
"""The folder graph of the C++ sources: which folder includes which (doc/architecture.md, Layout).

Prints the folders floor by floor (a folder stands above every folder it includes) and exits
with 1 when two folders include each other or the includes run in a circle, naming the
includes that do it. A folder is a stage of generator/ (generator/model -> "model"), render/,
or an application of app/ (app/cli -> "app/cli"); an include names its folder first
("section/cross_section.h", "render/...", "app/edit/...").

It then compares those floors with the layout table of doc/architecture.md (the first ```
block after "## Layout": a line "floor N  FOLDER... | what they hold" opens floor N, a line
"  FOLDER... | ..." with no floor adds to the floor above it) and exits with 1 as well, naming
every difference: a folder on another floor in the doc than in the code, a folder of the code
the doc leaves out, a folder the doc names that the code does not have, or a line of the
table it cannot read.

Usage: scripts/folder-graph.py [REPO]   (default: the repository this script is in)
"""
import collections
import os
import re
import sys

import doc_blocks

INCLUDE = re.compile(r'\s*#\s*include\s+"([^"]+)"')
DOC = os.path.join('doc', 'architecture.md')
# One line of the layout table: "floor 11  io | ..." or "          render | ...".
TABLE_LINE = re.compile(r'^(?:floor\s+(\d+)\s+|\s+)(\S.*?)\s*\|')


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


def source_files(repo):
    """(relative path, absolute path) of every .h and .cpp of a folder (see folder_of_file)."""
    for top in ('generator', 'render', 'app'):
        for root, dirs, files in os.walk(os.path.join(repo, top)):
            dirs.sort()
            for name in sorted(files):
                if not name.endswith(('.h', '.cpp')):
                    continue
                path = os.path.join(root, name)
                rel = os.path.relpath(path, repo)
                if rel.count('/') < 2 and top != 'render':
                    continue  # generator/CMakeLists-level files belong to no stage
                yield rel, path


def include_edges(repo):
    """The folders that hold sources, and {(from, to): [file -> include, ...]} between them."""
    folders = set()
    edges = collections.defaultdict(list)
    for rel, path in source_files(repo):
        src = folder_of_file(rel)
        folders.add(src)
        with open(path, encoding='utf-8', errors='replace') as f:
            for line in f:
                m = INCLUDE.match(line)
                if not m or '/' not in m.group(1):
                    continue
                dst = folder_of_include(m.group(1))
                if dst != src:
                    edges[(src, dst)].append(rel + ' -> ' + m.group(1))
    return folders, edges


def two_way_problems(edges):
    """Lines naming every pair of folders that include each other, with the includes."""
    lines = []
    for (a, b), includes in sorted(edges.items()):
        if a < b and (b, a) in edges:
            lines.append(f'two-way: {a} and {b} include each other')
            lines += ['    ' + line for line in includes + edges[(b, a)]]
    return lines


def code_floors(folders, edges):
    """(floors, circle): floors[0] the folders that include no other, each next floor those
    that include only folders below it; circle the folders left over, which include each other
    in a circle (empty when there is none)."""
    uses = collections.defaultdict(set)
    for a, b in edges:
        uses[a].add(b)
    floors, left = [], set(folders) | set(x for e in edges for x in e)
    while left:
        floor = sorted(f for f in left if not (uses[f] & left))
        if not floor:
            break
        floors.append(floor)
        left -= set(floor)
    return floors, sorted(left)


def doc_floors(doc_text):
    """({folder: floor}, problems) from the layout table of doc/architecture.md."""
    block = doc_blocks.block_after(doc_text, '## Layout')
    if block is None:
        return {}, [f'{DOC}: no ``` table after "## Layout"']
    floor_of, problems, floor = {}, [], None
    for number, line in block:
        if not line.strip():
            continue
        where = f'{DOC}:{number}'
        m = TABLE_LINE.match(line)
        if not m:
            problems.append(f'{where}: not a line of the layout table '
                            f'("floor N  FOLDER | ..." or "  FOLDER | ..."): {line.strip()}')
            continue
        if m.group(1) is not None:
            floor = int(m.group(1))
        elif floor is None:
            problems.append(f'{where}: the table starts without "floor N": {line.strip()}')
            continue
        for folder in m.group(2).split():
            folder = folder.rstrip('/')
            if folder in floor_of:
                problems.append(f'{where}: {folder} is named twice (floors {floor_of[folder]} '
                                f'and {floor})')
            else:
                floor_of[folder] = floor
    return floor_of, problems


def layout_differences(floors, doc_floor_of):
    """Lines naming every difference between the code's floors and the doc's table."""
    code_floor_of = {f: i + 1 for i, floor in enumerate(floors) for f in floor}
    lines = []
    for folder in sorted(set(code_floor_of) | set(doc_floor_of)):
        code, doc = code_floor_of.get(folder), doc_floor_of.get(folder)
        if doc is None:
            lines.append(f'{DOC}, Layout: {folder} is missing (on floor {code} in the code)')
        elif code is None:
            lines.append(f'{DOC}, Layout: {folder} (floor {doc}) is not a folder of the code')
        elif code != doc:
            lines.append(f'{DOC}, Layout: {folder} is on floor {doc} in the doc but on floor '
                         f'{code} in the code')
    return lines


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))
    folders, edges = include_edges(repo)
    problems = two_way_problems(edges)
    floors, circle = code_floors(folders, edges)
    if circle:
        problems.append('circle: ' + ', '.join(circle) + ' include each other in a circle')
    for line in problems:
        print(line)
    for i in reversed(range(len(floors))):
        print(f'floor {i + 1:2d}  ' + '  '.join(floors[i]))
    if problems:
        return 1  # the floors are not all known: comparing them with the doc would mislead
    with open(os.path.join(repo, DOC), encoding='utf-8') as f:
        doc_floor_of, doc_problems = doc_floors(f.read())
    doc_problems += layout_differences(floors, doc_floor_of)
    for line in doc_problems:
        print(line)
    return 1 if doc_problems else 0


if __name__ == '__main__':
    sys.exit(main())
