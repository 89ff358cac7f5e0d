#!/usr/bin/env bash
# What scripts/format.sh formats and scripts/check-format.sh checks, in one place:
#   scripts/format-files.sh           the C++ files .clang-format governs, one per line, relative
#                                     to the repository root: every .h and .cpp of the checkout
#                                     (tracked, or new and not ignored by git)
#   scripts/format-files.sh --tool    the clang-format to run them through: $CLANG_FORMAT when
#                                     set, else clang-format-14, else clang-format; it must be
#                                     version 14 (other major versions format differently)
# Without git (a source archive), the .h and .cpp files under app/, generator/, render/ and tests/.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd -P)"
cd "$root"

if [[ "${1:-}" == "--tool" ]]; then
  tool="${CLANG_FORMAT:-}"
  if [[ -z "$tool" ]]; then
    for candidate in clang-format-14 clang-format; do
      if command -v "$candidate" >/dev/null; then tool="$candidate"; break; fi
    done
  fi
  if [[ -z "$tool" ]] || ! command -v "$tool" >/dev/null; then
    echo "${tool:-clang-format 14} not found (Debian 12: the clang-format package;" \
         "bash scripts/install-deps.sh --test installs it)" >&2
    exit 1
  fi
  version="$("$tool" --version 2>&1 || true)"
  version="${version%%$'\n'*}"
  if [[ ! "$version" =~ version\ ([0-9]+)\. || "${BASH_REMATCH[1]}" != 14 ]]; then
    echo "$tool is not clang-format 14 (\"$version\"): other major versions format differently;" \
         "install clang-format-14 or set CLANG_FORMAT to it" >&2
    exit 1
  fi
  command -v "$tool"
  exit 0
fi

if [[ "$(git rev-parse --show-toplevel 2>/dev/null || true)" == "$root" ]]; then
  # Files deleted but not yet removed from git are left out.
  git ls-files --cached --others --exclude-standard -- '*.h' '*.cpp' | LC_ALL=C sort -u |
    while IFS= read -r f; do [[ ! -f "$f" ]] || printf '%s\n' "$f"; done
else
  find app generator render tests -type f \( -name '*.h' -o -name '*.cpp' \) | LC_ALL=C sort
fi
