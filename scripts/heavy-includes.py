#!/usr/bin/env python3
"""Where the heavy libraries are included (doc/architecture.md, Layout, Heavy includes).

Reads the table of doc/architecture.md (the first ``` block after "### Heavy includes"; its
first line names the columns, then "LIBRARY | NAME START | FILES", a line with the first two
columns blank adding files to the line above; a file ending in "/" is a folder) and checks it
against every #include of the C++ sources of generator/, render/ and app/ (the tests may
include what they need). Exits with 1, naming each one, when
- a file the table does not allow includes a name that starts with a library's name start
  (<CGAL/...> or "CGAL/..." for "CGAL/"), with the line that does it;
- a file the table allows no longer exists or no longer includes that library (a folder: when
  it is missing or none of its files does);
- a line of the table cannot be read.
Otherwise prints one line per library: which files include it.

Usage: scripts/heavy-includes.py [REPO]   (default: the repository this script is in)
"""
import os
import re
import sys

import doc_blocks

DOC = os.path.join('doc', 'architecture.md')
HEADING = '### Heavy includes'
TOPS = ('generator', 'render', 'app')
SOURCE_ENDINGS = ('.h', '.hpp', '.cpp', '.cc', '.c', '.inl')
INCLUDE = re.compile(r'\s*#\s*include\s*[<"]([^>"]+)[>"]')


class Library:
    """One line of the table: a library, the start of the names it is included by, and the
    files and folders (ending in "/") that may include it."""

    def __init__(self, name, start, line):
        self.name, self.start, self.line = name, start, line
        self.allowed = []

    def allows(self, rel):
        return any(rel == a or (a.endswith('/') and rel.startswith(a)) for a in self.allowed)


def read_table(doc_text):
    """([Library], problems) from the table of doc/architecture.md."""
    block = doc_blocks.block_after(doc_text, HEADING)
    if block is None:
        return [], [f'{DOC}: no ``` table after "{HEADING}"']
    rows = [(n, line) for n, line in block if line.strip()]
    if not rows or not rows[0][1].strip().startswith('library'):
        return [], [f'{DOC}, {HEADING}: the table\'s first line must name its columns '
                    '("library | included as | only in")']
    libraries, problems = [], []
    for number, line in rows[1:]:
        where = f'{DOC}:{number}'
        columns = [c.strip() for c in line.split('|')]
        if len(columns) != 3:
            problems.append(f'{where}: not "LIBRARY | NAME START | FILES": {line.strip()}')
            continue
        name, start, files = columns
        if name or start:
            if not name or not start or len(start.split()) != 1:
                problems.append(f'{where}: a library needs a name and one name start: '
                                f'{line.strip()}')
                continue
            libraries.append(Library(name, start, number))
        elif not libraries:
            problems.append(f'{where}: files before the first library: {line.strip()}')
            continue
        if not files.split():
            problems.append(f'{where}: no files named: {line.strip()}')
        for path in files.split():
            if not path.startswith(tuple(t + '/' for t in TOPS)):
                problems.append(f'{where}: {path} is outside {", ".join(t + "/" for t in TOPS)},'
                                ' which are the files checked')
            libraries[-1].allowed.append(path)
    return libraries, problems


def source_includes(repo):
    """{relative path: [(line number, included name)]} for every source of TOPS."""
    includes = {}
    for top in TOPS:
        for root, dirs, files in os.walk(os.path.join(repo, top)):
            dirs.sort()
            for name in sorted(files):
                if not name.endswith(SOURCE_ENDINGS):
                    continue
                path = os.path.join(root, name)
                found = []
                with open(path, encoding='utf-8', errors='replace') as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if m:
                            found.append((number, m.group(1)))
                includes[os.path.relpath(path, repo).replace(os.sep, '/')] = found
    return includes


def check(libraries, includes, repo):
    """(problems, {library name: files that include it})."""
    problems, users = [], {lib.name: [] for lib in libraries}
    for rel, found in sorted(includes.items()):
        for lib in libraries:
            lines = [(n, inc) for n, inc in found if inc.startswith(lib.start)]
            if not lines:
                continue
            users[lib.name].append(rel)
            if not lib.allows(rel):
                for n, inc in lines:
                    problems.append(f'{rel}:{n}: includes {inc} ({lib.name}), which only '
                                    f'{", ".join(lib.allowed)} may include ({DOC}, Heavy '
                                    'includes)')
    for lib in libraries:
        for allowed in lib.allowed:
            where = f'{DOC}:{lib.line}'
            if allowed.endswith('/'):
                if not os.path.isdir(os.path.join(repo, allowed)):
                    problems.append(f'{where}: {allowed} may include {lib.name}, but there is '
                                    'no such folder')
                elif not any(u.startswith(allowed) for u in users[lib.name]):
                    problems.append(f'{where}: {allowed} may include {lib.name}, but none of '
                                    f'its files includes {lib.start}...')
            elif allowed not in includes:
                problems.append(f'{where}: {allowed} may include {lib.name}, but there is no '
                                'such source file')
            elif allowed not in users[lib.name]:
                problems.append(f'{where}: {allowed} may include {lib.name}, but no longer '
                                f'includes {lib.start}...')
    return problems, users


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))
    with open(os.path.join(repo, DOC), encoding='utf-8') as f:
        libraries, problems = read_table(f.read())
    if not problems:
        found, users = check(libraries, source_includes(repo), repo)
        problems += found
        for lib in libraries:
            print(f'{lib.name} ({lib.start}...): ' + ('  '.join(users[lib.name]) or 'none'))
    for line in problems:
        print(line)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
