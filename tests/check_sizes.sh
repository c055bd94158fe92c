#!/usr/bin/env bash
# check_sizes.sh SOURCE_DIR - the size rules of the style guide, checked
# (the CTest test `sizes`; docs/developer/architecture.md states them):
#  1. No file under host/ or kernels/ is over 600 lines.
#  2. No function in host/ is over 100 lines, counted from its signature to
#     its closing brace (tests/function_lengths.py: brace matching with
#     comments, literals and preprocessor lines removed; a file whose braces
#     do not match is reported, not skipped).
# Prints each file and function over its limit; exit 1 if any.
set -euo pipefail
src=$(cd "${1:?usage: check_sizes.sh SOURCE_DIR}" && pwd)
cd "$src"
bad=0
while IFS= read -r -d '' file; do
  lines=$(wc -l <"$file")
  if ((lines > 600)); then
    echo "$file: $lines lines (at most 600: split it into files of one concept each)"
    bad=1
  fi
done < <(find host kernels -type f -print0 | sort -z)
mapfile -d '' sources < <(find host -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \) -print0 | sort -z)
python3 tests/function_lengths.py 100 "${sources[@]}" || bad=1
exit "$bad"
