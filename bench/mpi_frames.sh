#!/usr/bin/env bash
# mpi_frames.sh - many frames under mpirun, written (docs/developer/distributed.md,
# "Many frames"): `clrt render` of FRAMES copies of the demo at 640x480 to
# f_####.png, with `mpirun -np K` for each K given, ROUNDS times, the K
# alternating within each round. Prints each run's frames/s (FRAMES over the
# command's own total, which includes loading the scenes and each rank's
# program-cache load), then per K the mean ± sd and N.
#
#   bash bench/mpi_frames.sh [CLRT] [ROUNDS] [FRAMES] [K...]
#
# CLRT: the clrt binary (default build/clrt); ROUNDS: 5; FRAMES: 60; K: 1 2 3.
# A benchmark: nothing checks the times, and a busy machine moves them
# (check `uptime`).
set -euo pipefail
CLRT=${1:-build/clrt}
ROUNDS=${2:-5}
FRAMES=${3:-60}
shift $(($# >= 3 ? 3 : $#))
RANKS=("$@")
[ ${#RANKS[@]} -gt 0 ] || RANKS=(1 2 3)
[ -x "$CLRT" ] || { echo "mpi_frames.sh: no executable $CLRT" >&2; exit 2; }
ROOT_FLAG=()
[ "$(id -u)" = 0 ] && ROOT_FLAG=(--allow-run-as-root)
export CLRT_CACHE_DIR=${CLRT_CACHE_DIR:-/tmp/clrt-mpi-frames-cache}
HERE=$(cd "$(dirname "$0")/.." && pwd)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
SCENES=()
for ((i = 0; i < FRAMES; i++)); do SCENES+=("$HERE/scenes/cgfs-demo.json"); done
# One unmeasured run first: the program cache and the page cache.
"$CLRT" render "${SCENES[@]:0:2}" -o "$OUT/w_#.png" --width 640 --height 480 --aspect image -q >/dev/null

declare -A ALL
for ((round = 1; round <= ROUNDS; round++)); do
  for k in "${RANKS[@]}"; do
    rm -f "$OUT"/f_*.png
    total_ms=$(mpirun -q "${ROOT_FLAG[@]}" --oversubscribe -np "$k" "$CLRT" render "${SCENES[@]}" \
                 -o "$OUT/f_####.png" --width 640 --height 480 --aspect image |
               awk '/ frames, / { for (i = 1; i <= NF; i++) if ($i == "ms") { print $(i - 1); exit } }')
    written=$(find "$OUT" -name 'f_*.png' | wc -l)
    [ "$written" = "$FRAMES" ] || { echo "mpi_frames.sh: $written of $FRAMES frames written" >&2; exit 1; }
    fps=$(awk -v n="$FRAMES" -v ms="$total_ms" 'BEGIN { printf "%.2f", n / (ms / 1000) }')
    echo "round $round  -np $k  $total_ms ms  $fps frames/s"
    ALL[$k]+="$fps "
  done
done
for k in "${RANKS[@]}"; do
  echo "${ALL[$k]}" | awk -v k="$k" '{ for (i = 1; i <= NF; i++) { s += $i; q += $i * $i } m = s / NF;
    sd = NF > 1 ? sqrt((q - NF * m * m) / (NF - 1)) : 0; printf "-np %s: %.2f ± %.2f frames/s (N = %d)\n", k, m, sd, NF }'
done
