#!/usr/bin/env bash
# Runs a campo sweep on a Slurm cluster as a job array of N shards, waits for
# it, and merges the shards into OUT/merged. See tools/slurm/README.md.
#
#   tools/slurm/submit_sweep.sh SPEC OUT N [sbatch options...] [-- campo sweep options...]
#
#   OUT/shard-K/      shard K's campo sweep output (results.jsonl, ...)
#   OUT/logs/         one Slurm log per task (campo-sweep-<job>_<K>.out) and
#                     shard-K.status (the task's exit code)
#   OUT/merged/       `campo merge` of all shards, written only when every
#                     shard succeeded; then `campo table OUT/merged`
#
# sbatch options pass through and override the #SBATCH defaults:
# --partition=..., --cpus-per-task=8, --time=..., --account=...; an --array
# option replaces the default 1-N, e.g. --array=3 reruns shard 3 only (the
# other shards' results are kept and the merge covers all N). Options after
# "--" go to every `campo sweep` (e.g. -- --figures).
#
# Environment: CAMPO, the campo executable (default: build/campo of this
# repository if built, else `campo` on PATH); it must be reachable at the same
# path on the compute nodes.
#
# Exit status: 0 when all shards succeeded and were merged; 1 otherwise.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"

die() {
  echo "submit_sweep: error: $*" >&2
  exit 1
}
if (($# < 3)); then
  echo "usage: $0 SPEC OUT N [sbatch options...] [-- campo sweep options...]" >&2
  exit 2
fi
spec="$1" out="$2" shards="$3"
shift 3
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "N must be a positive integer, got '$shards'"
[ -f "$spec" ] || die "no such spec file: $spec"
command -v sbatch >/dev/null || die "sbatch not found (load the Slurm module or run on a submit host)"

# The campo command line: the one place to change how campo is invoked.
campo="${CAMPO:-}"
if [ -z "$campo" ]; then
  if [ -x "$root/build/campo" ]; then campo="$root/build/campo"; else campo=campo; fi
fi
# Absolute paths: the job may start in another directory or on another node.
if [[ "$campo" == */* ]]; then
  campo="$(cd "$(dirname "$campo")" && pwd)/$(basename "$campo")"
else
  campo="$(command -v "$campo")" || die "'$campo' not found on PATH (set CAMPO=/path/to/campo)"
fi
[ -x "$campo" ] || die "campo executable not found: $campo (set CAMPO=/path/to/campo)"
spec="$(cd "$(dirname "$spec")" && pwd)/$(basename "$spec")"
mkdir -p "$out/logs" # Slurm does not create the directory of --output files
out="$(cd "$out" && pwd)"

# Split the sbatch options from the campo sweep options after "--".
sbatch_opts=() campo_opts=()
while (($#)); do
  if [ "$1" = -- ]; then
    shift
    campo_opts=("$@")
    break
  fi
  sbatch_opts+=("$1")
  shift
done
# The array indices: 1-N unless an --array option says otherwise.
array=(--array="1-$shards") indices_spec="1-$shards" prev=""
for a in "${sbatch_opts[@]}"; do
  case "$prev" in --array | -a) indices_spec="$a" ;; esac
  case "$a" in
    --array=*) array=() indices_spec="${a#--array=}" ;;
    --array | -a) array=() ;;
    -a?*) array=() indices_spec="${a#-a}" ;;
  esac
  prev="$a"
done
# Forget the status of the shards about to run, so one cancelled before it
# starts cannot pass for done with a status file from an earlier submission.
# (Index syntax: 1,3,5-7, 1-9:2, with an optional %limit.)
indices_list="${indices_spec%%\%*}"
for part in ${indices_list//,/ }; do
  if [[ "$part" =~ ^([0-9]+)(-([0-9]+)(:([1-9][0-9]*))?)?$ ]]; then
    lo="${BASH_REMATCH[1]}" hi="${BASH_REMATCH[3]:-${BASH_REMATCH[1]}}" step="${BASH_REMATCH[5]:-1}"
    for ((k = lo; k <= hi && k <= shards; k += step)); do rm -f "$out/logs/shard-$k.status"; done
  else
    die "cannot read the array indices '$indices_spec' (expected e.g. 1-$shards or 2,5)"
  fi
done

export CAMPO="$campo"
echo "submit_sweep: $shards shards of $spec -> $out (campo: $campo)" >&2
# --wait: sbatch returns when every array task has ended, with the highest
# task exit code. The status files are checked as well, since a task killed by
# Slurm (time limit, node failure) may leave no exit code behind.
sbatch_rc=0
sbatch --wait --export=ALL "${array[@]}" \
  --output="$out/logs/%x-%A_%a.out" \
  "${sbatch_opts[@]}" "$here/sweep_array.sbatch" "$spec" "$out" "$shards" "${campo_opts[@]}" \
  || sbatch_rc=$?

failed=() indices=""
for ((k = 1; k <= shards; k++)); do
  st="$(cat "$out/logs/shard-$k.status" 2>/dev/null || echo "no status")"
  if [ "$st" != 0 ]; then
    [[ "$st" =~ ^[0-9]+$ ]] && st="exit code $st" || st="no status file (killed, timed out or never started)"
    failed+=("shard $k: $st")
    indices="${indices:+$indices,}$k"
  fi
done
if ((${#failed[@]})) || ((sbatch_rc)); then
  echo "submit_sweep: sbatch exited with $sbatch_rc" >&2
  for f in "${failed[@]}"; do echo "submit_sweep: failed: $f" >&2; done
  echo "submit_sweep: task logs: $out/logs/" >&2
  [ -z "$indices" ] || echo "submit_sweep: to rerun (completed runs are skipped): $0 $spec $out $shards --array=$indices [the same other options]" >&2
  exit 1
fi

# Merge into a fresh directory, then swap it in, so OUT/merged is never a
# half-written or stale merge.
shard_dirs=()
for ((k = 1; k <= shards; k++)); do
  shard_dirs+=("$out/shard-$k")
done
rm -rf "$out/merged.tmp"
"$campo" merge "${shard_dirs[@]}" --out "$out/merged.tmp" || die "campo merge failed"
rm -rf "$out/merged"
mv "$out/merged.tmp" "$out/merged"
echo "submit_sweep: merged $shards shards into $out/merged" >&2
