#!/usr/bin/env bash
# check_layers.sh SOURCE_DIR - the layering rule of host/, checked on every
# include: a file in host/<layer>/ includes headers of its own layer and of
# the layers before it only, in this order (the one place it is written):
#   util < scene < image < reference < cl < render < eval < dist < app
# and only app/ includes CLI11. Prints each violation; exit 1 if any.
set -euo pipefail
root=${1:-.}
layers=(util scene image reference cl render eval dist app)
rank() {
  local i
  for i in "${!layers[@]}"; do [[ ${layers[$i]} == "$1" ]] && { echo "$i"; return; }; done
  echo -1
}
bad=0
for dir in "$root"/host/*/; do
  layer=$(basename "$dir")
  own=$(rank "$layer")
  if ((own < 0)); then
    echo "host/$layer: not a known layer (add it to tests/check_layers.sh and CMakeLists.txt)"
    bad=1
    continue
  fi
  for file in "$dir"*; do
    while IFS= read -r line; do
      number=${line%%:*}
      target=$(sed -E 's/^[0-9]+:#include "([a-z_]+)\/.*/\1/' <<<"$line")
      [[ $target == "$line" ]] && continue  # "file.h" without a folder: kernels/ or bench/
      want=$(rank "$target")
      if ((want < 0 || want > own)); then
        echo "host/$layer/$(basename "$file"):$number includes $target/ (a later layer)"
        bad=1
      fi
    done < <(grep -nE '^#include "' "$file" || true)
    if [[ $layer != app ]] && grep -qE '^#include <CLI/' "$file"; then
      echo "host/$layer/$(basename "$file"): includes CLI11 (only app/ may)"
      bad=1
    fi
  done
done
((bad == 0)) && echo "layers: every include of host/ goes to its own or an earlier layer"
exit $bad
