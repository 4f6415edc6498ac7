#!/usr/bin/env bash
# Runs every peer benchmark built in BUILD_DIR (default build/), each pinned to
# one core, and prints docs/PERFORMANCE.md's peers table: the machine, the date
# and the git revision, then one row per comparison as the programs print them.
#   bench/peers/table.sh [BUILD_DIR]
set -euo pipefail
build="${1:-build}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
core="$(( $(nproc) - 1 ))"
echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores," \
  "$(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo); $(date -u +%Y-%m-%d);" \
  "git $(git -C "$root" rev-parse --short=12 HEAD 2>/dev/null || echo unknown); each program pinned to core $core."
echo
echo "| comparison | campo | peer | campo / peer | |"
echo "| --- | --- | --- | ---: | --- |"
for peer in campo_peer_quadrotor campo_peer_lidar campo_peer_astar campo_peer_dubins; do
  if [ -x "$build/$peer" ]; then taskset -c "$core" "$build/$peer"; else echo "| $peer | not built | | | |"; fi
done
if [ -x "$build/campo_peer_rrt_star" ]; then
  echo
  taskset -c "$core" "$build/campo_peer_rrt_star"
fi
