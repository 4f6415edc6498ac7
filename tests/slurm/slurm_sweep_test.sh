#!/usr/bin/env bash
# End-to-end test of tools/slurm/: starts a real single-node Slurm (munged,
# slurmctld, slurmd) under a temporary directory, runs SPEC as a 2-shard job
# array with tools/slurm/submit_sweep.sh (sbatch --wait), and checks that the
# merged results equal a local `campo sweep SPEC` apart from timing fields.
#
#   tests/slurm/slurm_sweep_test.sh CAMPO SPEC
#
# CAMPO is the campo executable.
# Environment: CAMPO_SLURM_TMP, where to make the temporary directory (/tmp).
# Exit 77 (CTest SKIP_RETURN_CODE) when Slurm or munge is not installed or we
# are not root; the daemons are always stopped and the directory removed.
set -euo pipefail

# Keys removed (at any depth) before comparing: wall-clock timings differ from
# run to run. Glob patterns on the key name.
IGNORED_KEYS=("wall_time_s" "replan_time_ms*" "planner_time_ms*")
SHARDS=2

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"

fail() {
  echo "slurm_sweep_test: FAIL: $*" >&2
  exit 1
}
skip() {
  echo "slurm_sweep_test: SKIP: $*" >&2
  exit 77
}

(($# == 2)) || {
  echo "usage: $0 CAMPO SPEC" >&2
  exit 2
}
[ -x "$1" ] || fail "campo executable not found: $1"
[ -f "$2" ] || fail "spec file not found: $2"
campo="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
spec="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"

for cmd in sbatch slurmctld slurmd munged jq; do
  command -v "$cmd" >/dev/null || skip "'$cmd' not installed (Debian packages: slurm-wlm munge jq)"
done
[ "$(id -u)" -eq 0 ] || skip "needs root to run slurmd"

# A short path: Unix socket paths under it must stay below 108 bytes (and the
# job scripts run from it, so not a noexec mount): CAMPO_SLURM_TMP overrides.
tmp="$(mktemp -d "${CAMPO_SLURM_TMP:-/tmp}/campo-slurm.XXXXXX")"
child=""
cleanup() {
  local rc=$?
  # An interrupted step (see run) goes first, with its children (sbatch --wait).
  [ -z "$child" ] || kill -TERM -- "-$child" 2>/dev/null || true
  "$root/tools/slurm/local_cluster.sh" stop "$tmp/cluster" || true
  if ((rc != 0 && rc != 77)); then
    # Leave the evidence in the test log before removing it.
    for f in "$tmp"/out/logs/*.out "$tmp"/cluster/log/slurm*.log; do
      [ -f "$f" ] || continue
      echo "----- $f (last 20 lines) -----" >&2
      tail -n 20 "$f" >&2 || true
    done
  fi
  rm -rf "$tmp"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM # run the EXIT trap on interruption too

# Runs a long step in the background and waits for it: bash defers traps until
# a foreground command ends, but "wait" returns at once on a signal, so the
# cluster is stopped promptly when the test is interrupted. setsid makes the
# step a process group of its own, so cleanup can stop it with its children.
run() {
  setsid "$@" &
  child=$!
  local rc=0
  wait "$child" || rc=$?
  child=""
  return "$rc"
}

# Settings of an enclosing Slurm (say, CI inside a job: SBATCH_PARTITION,
# SLURM_CONF, ...) would be read by sbatch and steer it away from our cluster.
for v in $(compgen -e); do
  case "$v" in
    SLURM_LOCAL_*) ;; # ours: tools/slurm/local_cluster.sh settings
    SLURM_* | SBATCH_* | SALLOC_* | SRUN_*) unset "$v" ;;
  esac
done

SECONDS=0
echo "slurm_sweep_test: starting a local cluster in $tmp/cluster" >&2
env_line="$("$root/tools/slurm/local_cluster.sh" start "$tmp/cluster")" \
  || fail "could not start the local Slurm cluster (see the messages above)"
eval "$env_line"
[ -n "${SLURM_CONF:-}" ] || fail "local_cluster.sh did not report SLURM_CONF"
sinfo >&2

echo "slurm_sweep_test: [${SECONDS}s] submitting $spec as $SHARDS shards" >&2
# One CPU per task so both shards run at once even on a 2-CPU machine; a time
# limit so a hung task cannot outlive the test.
export CAMPO="$campo"
run "$root/tools/slurm/submit_sweep.sh" "$spec" "$tmp/out" "$SHARDS" \
  --cpus-per-task=1 --time=5 \
  || fail "submit_sweep.sh failed"
[ -f "$tmp/out/merged/results.jsonl" ] || fail "no merged results.jsonl"

echo "slurm_sweep_test: [${SECONDS}s] running the same spec locally" >&2
run "$campo" sweep "$spec" --out "$tmp/local" || fail "local campo sweep failed"

# Canonical form: ignored keys deleted, keys sorted, one line per run in id order.
# The globs as anchored regular expressions (metacharacters escaped, * -> .*).
ignored_res="$(printf '%s\n' "${IGNORED_KEYS[@]}" \
  | sed -e 's/[].[^$+?(){}|\\]/\\&/g' -e 's/\*/.*/g' -e 's/^/^/' -e 's/$/$/' \
  | jq -R . | jq -s -c .)"
normalize() {
  jq -c -S -n --argjson res "$ignored_res" '
    [inputs
       | walk(if type == "object"
              then with_entries(select(.key as $k | any($res[]; . as $re | $k | test($re)) | not))
              else . end)]
    | sort_by(.id) | .[]' "$1"
}
normalize "$tmp/out/merged/results.jsonl" >"$tmp/merged.norm"
normalize "$tmp/local/results.jsonl" >"$tmp/local.norm"

runs="$(wc -l <"$tmp/local.norm")"
((runs > 0)) || fail "the local sweep produced no results"
# Every shard must have contributed, or sharding silently did nothing.
for ((k = 1; k <= SHARDS; k++)); do
  [ -s "$tmp/out/shard-$k/results.jsonl" ] || fail "shard $k wrote no results (spec too small for $SHARDS shards?)"
done
# Lists what differs between two normalized files: missing runs and, per run,
# each differing field with both values (lines are too long for a plain diff).
explain_difference() {
  jq -r -n --slurpfile a "$1" --slurpfile b "$2" '
    ($a | map({key: .id, value: .}) | from_entries) as $A
    | ($b | map({key: .id, value: .}) | from_entries) as $B
    | (($A | keys) - ($B | keys) | .[] | "only in the local run: \(.)"),
      (($B | keys) - ($A | keys) | .[] | "only in the merged results: \(.)"),
      (($A | keys) - (($A | keys) - ($B | keys)) | .[] as $id
       | [$A[$id], $B[$id] | paths(type != "object" and type != "array")] | unique | .[] as $p
       | ($A[$id] | getpath($p)) as $x | ($B[$id] | getpath($p)) as $y
       | select($x != $y)
       | "\($id) \($p | map(tostring) | join("/")): local \($x | tojson), merged \($y | tojson)")'
}
if ! cmp -s "$tmp/local.norm" "$tmp/merged.norm"; then
  explain_difference "$tmp/local.norm" "$tmp/merged.norm" | head -n 40 >&2
  fail "merged Slurm results differ from the local run (ignoring ${IGNORED_KEYS[*]})"
fi
[ "$(jq -r .id "$tmp/merged.norm" | sort | uniq -d)" = "" ] || fail "duplicate ids in merged results"

echo "slurm_sweep_test: PASS: $runs runs, $SHARDS shards merged equal the local run [${SECONDS}s]" >&2
