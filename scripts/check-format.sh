#!/usr/bin/env bash
# The format_check test: every C++ file as clang-format 14 and .clang-format leave it, and
# ESLint's verdict on the editor's page scripts (app/edit/web/, eslint.config.mjs). Lists each
# file that scripts/format.sh would change with a diff of its first offending lines, prints what
# ESLint finds, and exits 1 when either finds anything (0 when clean). Reads only: nothing is
# written into the tree. Works from any folder. Needs clang-format 14 and ESLint in
# node_modules/ (bash scripts/install-deps.sh --test installs both).
#   usage: scripts/check-format.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd -P)"
root="$(dirname "$here")"
cd "$root"

# The C++ files (scripts/format-files.sh): one clang-format run names those it would change, and
# each of them gets the start of its diff.
check_cpp() {
  local tool report f files unformatted
  tool="$(bash "$here/format-files.sh" --tool)" || return 1
  local style=(--style="file:$root/.clang-format" --fallback-style=none)
  mapfile -t files < <(bash "$here/format-files.sh")
  if ((${#files[@]} == 0)); then
    echo "check-format: no C++ files found" >&2
    return 1
  fi
  if ! report="$("$tool" --dry-run "${style[@]}" "${files[@]}" 2>&1)"; then
    printf '%s\n' "$report" >&2
    echo "check-format: $tool failed" >&2
    return 1
  fi
  mapfile -t unformatted < <(
    sed -n 's/^\(.*\):[0-9]*:[0-9]*: warning: code should be clang-formatted.*/\1/p' <<<"$report" |
      awk '!seen[$0]++')
  if ((${#unformatted[@]} == 0)); then
    echo "check-format: ${#files[@]} C++ files formatted"
    return 0
  fi
  echo "check-format: ${#unformatted[@]} of ${#files[@]} C++ files are not formatted" \
       "(bash scripts/format.sh formats them):"
  for f in "${unformatted[@]}"; do
    echo "--- $f"
    "$tool" "${style[@]}" "$f" | diff -u --label "$f" --label "$f (formatted)" "$f" - |
      sed -n '3,20p' || true
  done
  return 1
}

# The editor's page scripts, with ESLint from node_modules/ (eslint.config.mjs).
check_web() {
  local eslint="$root/node_modules/.bin/eslint"
  if [[ ! -x "$eslint" ]]; then
    echo "check-format: ESLint is not in node_modules/ (bash scripts/install-deps.sh --test" \
         "installs it)" >&2
    return 1
  fi
  "$eslint" --max-warnings 0 app/edit/web || return 1
  echo "check-format: ESLint finds nothing in app/edit/web/"
}

failed=0
check_cpp || failed=1
check_web || failed=1
exit "$failed"
