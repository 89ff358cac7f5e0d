#!/usr/bin/env bash
# Regenerates the golden images of tests/render/golden_test.cpp (tests/golden/*.png) with the
# same code path the test compares: it builds the test executable, then runs the Golden.* tests
# with CUTAWAY_UPDATE_GOLDEN=1, which makes them write their renders as the references instead
# of comparing. Review the new pictures (git diff shows which changed) before committing them.
# See doc/golden-images.md.
#   usage: scripts/update-golden.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"

if [[ ! -f "$build_dir/build.ninja" && ! -f "$build_dir/Makefile" ]]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build_dir" --target cutaway_tests
CUTAWAY_UPDATE_GOLDEN=1 "$build_dir/cutaway_tests" --gtest_filter='Golden.*'
git status --short tests/golden
