#!/usr/bin/env bash
# Packs the Blender add-on (addons/blender/cutaway) into a zip that Blender installs:
# Preferences > Add-ons > Install... (doc/blender.md). The zip's top folder is cutaway/.
#
#   scripts/make-blender-addon.sh OUT.zip
#
# Python's zipfile (no zip program needed); sorted entries with a fixed time stamp, so the same
# sources give the same bytes.
set -euo pipefail
if (($# != 1)); then
  echo "usage: $0 OUT.zip" >&2
  exit 2
fi
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$(dirname "$1")"
python3 - "$root/addons/blender/cutaway" "$1" <<'PY'
import os
import sys
import zipfile

source, out = sys.argv[1], sys.argv[2]
files = sorted(name for name in os.listdir(source) if name.endswith(".py"))
with zipfile.ZipFile(out + ".tmp", "w", zipfile.ZIP_DEFLATED) as archive:
    for name in files:
        entry = zipfile.ZipInfo(f"cutaway/{name}", date_time=(1980, 1, 1, 0, 0, 0))
        entry.compress_type = zipfile.ZIP_DEFLATED
        entry.external_attr = 0o644 << 16
        with open(os.path.join(source, name), "rb") as stream:
            archive.writestr(entry, stream.read())
os.replace(out + ".tmp", out)
print(f"wrote {out} ({len(files)} files)")
PY
