#!/usr/bin/env bash
# Formats every C++ file of the checkout in place with clang-format 14 and .clang-format
# (doc/architecture.md, Style): the files and the clang-format of scripts/format-files.sh, so
# that scripts/check-format.sh (the format_check test) finds none to change. Works from any
# folder.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd -P)"
root="$(dirname "$here")"
tool="$(bash "$here/format-files.sh" --tool)"
cd "$root"
bash "$here/format-files.sh" | tr '\n' '\0' |
  xargs -0 -r "$tool" -i --style="file:$root/.clang-format" --fallback-style=none
