#!/usr/bin/env bash
# make test-cpus: the same bytes on another CPU. Makes tests/data/scenes/emulated_cpu.yaml (one
# tomato in halves dropped on a board: meshing, PMVC, physics, glTF and POV-Ray export) natively
# (and the .pov's texture images) and under qemu-user emulating a Nehalem (SSE4.2, no AVX, no FMA: glibc takes its SSE2 math
# routines and Embree its SSE4.2 kernels, and qemu computes the approximate reciprocals its own
# way), and compares the files byte for byte.
#   tests/app/cli/emulated_cpu_test.sh BINARY WORK_DIR
set -euo pipefail
binary=$(realpath "$1")
work=$2
cd "$(dirname "$0")/../.."
command -v qemu-x86_64 >/dev/null || { echo "qemu-x86_64 is missing (apt-get install qemu-user)" >&2; exit 2; }
rm -rf "$work"
mkdir -p "$work/native" "$work/nehalem"
# --no-cache: each CPU cuts and settles every object itself.
args=(scene tests/data/scenes/emulated_cpu.yaml --cube 8 --no-cache)
"$binary" "${args[@]}" -o "$work/native/scene.glb" -o "$work/native/scene.pov" >/dev/null
start=$(date +%s)
qemu-x86_64 -cpu Nehalem "$binary" "${args[@]}" -o "$work/nehalem/scene.glb" \
  -o "$work/nehalem/scene.pov" >/dev/null
echo "emulated Nehalem run: $(($(date +%s) - start)) s"
passed=0 failed=0
# Every file: the scene files and the .pov's texture images beside it.
for f in $(cd "$work/native" && ls); do
  if cmp -s "$work/native/$f" "$work/nehalem/$f"; then
    echo "same bytes: $f"; passed=$((passed + 1))
  else
    echo "DIFFERENT: $f ($work/native/$f, $work/nehalem/$f)"; failed=$((failed + 1))
  fi
done
echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
