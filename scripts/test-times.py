#!/usr/bin/env python3
"""The slowest tests and the time per tier (CTest label) of the last test run in a build folder.

Reads BUILD/Testing/junit.xml (written by `make test` and `make check`: ctest --output-junit)
for each test's wall time and status, and asks CTest for each test's labels
(ctest --show-only=json-v1). Prints the slowest 20 tests, then per label the number of tests
run, their summed and largest time, and the tests over 60 s (the budget of one test). A
measure, not a check: it exits 0 whatever the times, 1 only when there is no run to read.

Usage: scripts/test-times.py [BUILD]   (default: build)
"""
import collections
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

TEST_BUDGET_S = 60.0


def read_times(build):
    """{test name: (seconds, status)} from the JUnit file of the last run."""
    path = os.path.join(build, 'Testing', 'junit.xml')
    if not os.path.exists(path):
        sys.exit(f'test-times: no {path}: run `make test` or `make check` first')
    times = {}
    for case in ET.parse(path).getroot().iter('testcase'):
        times[case.get('name')] = (float(case.get('time') or 0), case.get('status') or '')
    return times


def read_labels(build):
    """{test name: [label, ...]} as CTest has them."""
    out = subprocess.run(['ctest', '--show-only=json-v1'], cwd=build, check=True,
                         capture_output=True, text=True).stdout
    labels = {}
    for test in json.loads(out).get('tests', []):
        names = [p['value'] for p in test.get('properties', []) if p['name'] == 'LABELS']
        labels[test['name']] = names[0] if names else []
    return labels


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else 'build'
    times = read_times(build)
    labels = read_labels(build)
    print('slowest 20 tests (wall seconds):')
    ranked = sorted(times.items(), key=lambda kv: -kv[1][0])
    for name, (seconds, status) in ranked[:20]:
        tiers = ','.join(labels.get(name, [])) or '-'
        print(f'  {seconds:8.1f}  {name}  [{tiers}]{"" if status == "run" else " " + status}')
    per = collections.defaultdict(list)
    for name, (seconds, _) in times.items():
        for label in labels.get(name, []) or ['(no label)']:
            per[label].append((seconds, name))
    print('per label: tests, summed seconds, largest, tests over '
          f'{TEST_BUDGET_S:.0f} s')
    for label in sorted(per):
        entries = per[label]
        over = sorted(n for s, n in entries if s > TEST_BUDGET_S)
        print(f'  {label:12s} {len(entries):5d} {sum(s for s, _ in entries):9.1f} '
              f'{max(s for s, _ in entries):8.1f}  {len(over)}' +
              (f' ({", ".join(over)})' if over else ''))
    total = sum(s for s, _ in times.values())
    print(f'all: {len(times)} tests, {total:.1f} s summed')


if __name__ == '__main__':
    main()
