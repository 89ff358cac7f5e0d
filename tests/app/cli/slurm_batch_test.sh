#!/usr/bin/env bash
# A 4-task Slurm array job makes the same batch as a local run, byte for byte: a one-node
# cluster (scripts/slurm-one-node.sh) is started, `cutaway batch --slurm --array 4` submits the
# batch, `cutaway batch merge` checks and merges the shards, and every asset, the manifest, the
# batch index and the contact sheet are compared with an unsharded local run. The daemons are
# stopped and everything removed on any exit.
#   slurm_batch_test.sh CUTAWAY SOURCE_DIR WORK_DIR
set -euo pipefail
cutaway=$1
src=$2
work=$3
batch="$src/tests/data/batches/four-variants.yaml"

rm -rf "$work"
mkdir -p "$work"
cluster="$work/cluster"
cleanup() { "$src/scripts/slurm-one-node.sh" stop "$cluster" || true; }
trap cleanup EXIT
eval "export $("$src/scripts/slurm-one-node.sh" start "$cluster")"

# Both builds cut every object themselves (--no-cache, passed on to the array tasks): the
# comparison is of work done twice, not of a cache read back.
"$cutaway" -q batch "$batch" -o "$work/local" --no-cache
"$cutaway" -q batch merge "$work/local"

job=$("$cutaway" -q batch "$batch" -o "$work/slurm" --slurm --array 4 --no-cache)
grep -q -- '--no-cache' "$work/slurm/batch.sbatch"
[[ "$job" =~ ^[0-9]+$ ]] || { echo "FAIL: no job id from batch --slurm: '$job'"; exit 1; }
grep -q -- '--array=1-4' "$work/slurm/batch.sbatch"
for _ in $(seq 600); do
  [[ -z "$(squeue -h -j "$job" 2>/dev/null)" ]] && break
  sleep 0.5
done
if [[ -n "$(squeue -h -j "$job" 2>/dev/null)" ]]; then
  echo "FAIL: job $job still queued or running after 300 s"; squeue; exit 1
fi
outs=("$work"/slurm/slurm/"${job}"_*.out)
[[ ${#outs[@]} -eq 4 ]] || { echo "FAIL: ${#outs[@]} task logs, not 4"; ls -R "$work/slurm"; exit 1; }
for k in 1 2 3 4; do
  [[ -f "$work/slurm/manifest-$k-of-4.jsonl" ]] || {
    echo "FAIL: task $k wrote no manifest"; cat "${outs[@]}"; exit 1; }
done
"$cutaway" -q batch merge "$work/slurm"

n=0
for f in "$work"/local/*; do
  name=$(basename "$f")
  [[ "$name" == timings*.jsonl ]] && continue
  cmp "$f" "$work/slurm/$name" || { echo "FAIL: $name differs from the local run"; exit 1; }
  n=$((n + 1))
done
[[ $n -ge 14 ]] || { echo "FAIL: only $n files compared"; exit 1; }
echo "PASS: $n files byte-identical between the local run and the 4-task Slurm array job $job"
