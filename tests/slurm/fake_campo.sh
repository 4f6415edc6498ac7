#!/usr/bin/env bash
# Stand-in for `campo sweep` / `campo merge`, to exercise the Slurm plumbing
# (tools/slurm/, tests/slurm/slurm_sweep_test.sh) without the simulator:
#   fake_campo.sh sweep SPEC --out DIR [--jobs N] [--shard K/N]
#   fake_campo.sh merge DIR... --out DIR
# A sweep has (#scenes x #axis values... x seeds.count) runs named run-<i>;
# shard K of N takes runs with i % N == K-1. Runs already in results.jsonl are
# skipped. Metrics are deterministic; wall_time_s and the replan_time_ms_*
# timing fields are not (so the comparison must ignore them).
# FAKE_CAMPO_FAIL_SHARD=K makes shard K exit 1 after writing nothing.
set -euo pipefail

die() {
  echo "fake_campo: $*" >&2
  exit 2
}

cmd="${1:-}"
shift || true
case "$cmd" in
  sweep)
    spec="" out="" shard="1/1"
    while (($#)); do
      case "$1" in
        --out) out="$2"; shift 2 ;;
        --jobs) shift 2 ;;
        --figures) shift ;;
        --shard) shard="$2"; shift 2 ;;
        -*) die "unknown option $1" ;;
        *) spec="$1"; shift ;;
      esac
    done
    [ -n "$spec" ] && [ -n "$out" ] || die "usage: sweep SPEC --out DIR [--jobs N] [--shard K/N]"
    [ -f "$spec" ] || die "no such spec: $spec"
    k="${shard%/*}" n="${shard#*/}"
    [[ "$k" =~ ^[0-9]+$ && "$n" =~ ^[0-9]+$ ]] && ((k >= 1 && k <= n)) || die "bad --shard $shard"
    if [ "${FAKE_CAMPO_FAIL_SHARD:-}" = "$k" ]; then
      echo "fake_campo: shard $k failing on purpose" >&2
      exit 1
    fi
    runs="$(jq '(.scenes | length) * ([.axes[]?.values | length] | reduce .[] as $v (1; . * $v)) * (.seeds.count // 1)' "$spec")"
    mkdir -p "$out"
    cp "$spec" "$out/sweep.json"
    touch "$out/results.jsonl"
    for ((i = 0; i < runs; i++)); do
      ((i % n == k - 1)) || continue
      id="run-$i"
      grep -q "\"id\":\"$id\"" "$out/results.jsonl" && continue # resume
      sleep 0.2                                                  # "simulate"
      jq -cn --arg id "$id" --argjson i "$i" --argjson w "$((RANDOM % 100))" \
        '{id: $id, status: "reached",
          metrics: {path_m: ($i * 1.5), steps: ($i + 10),
                    timing: {replan_time_ms_mean: ($w / 7), replan_time_ms_max: $w}},
          wall_time_s: ($w / 10)}' >>"$out/results.jsonl"
      echo "[$((i + 1))/$runs] $id: reached" >&2
    done
    ;;
  merge)
    dirs=() out=""
    while (($#)); do
      case "$1" in
        --out) out="$2"; shift 2 ;;
        -*) die "unknown option $1" ;;
        *) dirs+=("$1"); shift ;;
      esac
    done
    [ -n "$out" ] && ((${#dirs[@]})) || die "usage: merge DIR... --out DIR"
    mkdir -p "$out"
    files=()
    for d in "${dirs[@]}"; do
      [ -f "$d/results.jsonl" ] || die "no results.jsonl in $d"
      files+=("$d/results.jsonl")
    done
    # First occurrence of each id wins, in the order given.
    jq -c -n '[inputs] | reduce .[] as $r ({}; if has($r.id) then . else .[$r.id] = $r end) | .[]' \
      "${files[@]}" >"$out/results.jsonl"
    ;;
  *) die "usage: fake_campo.sh sweep|merge ..." ;;
esac
