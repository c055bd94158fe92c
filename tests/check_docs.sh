#!/usr/bin/env bash
# check_docs.sh SOURCE_DIR CLRT - what the documentation promises, checked
# (the CTest test `docs`; docs/developer/documentation.md says how to write
# for it):
#  1. README.md is a front page: at most 200 lines, and its only ```sh
#     blocks are the two commands .ci/run takes from it.
#  2. Every relative link in README.md and docs/**/*.md names a file that
#     exists, and a #fragment names a heading of the page it points to
#     (GitHub's anchors: lower case, punctuation dropped, spaces as hyphens;
#     headings are written in ASCII letters so that this stays simple),
#     and README.md links every page of docs/ (its map).
#  3. No page cites the issue tracker by number: a page says what is true.
#  4. Every ```console block runs. Its lines that start with "$ " are
#     commands (one line each), run in order by bash in a scratch folder per
#     page, with `clrt` (the binary given) on PATH and the repository's
#     scenes/ beside them; the lines under a command are what it must print
#     (stdout and stderr together). In those lines "..." stands for any text,
#     and a line that is "..." alone for any number of lines. A command must
#     exit with status 0: show a failure as `cmd || echo "exit status $?"`.
#     A block opened as ```console full-build needs what a lean build
#     (CLRT_LEAN=ON) leaves out and is skipped there.
# Prints every failure; exit 1 if any.
set -euo pipefail
src=$(cd "${1:?usage: check_docs.sh SOURCE_DIR CLRT}" && pwd)
clrt=$(cd "$(dirname "${2:?usage: check_docs.sh SOURCE_DIR CLRT}")" && pwd)/$(basename "$2")
export LC_ALL=C
cd "$src"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bad=0
fail() {
  echo "$*"
  bad=1
}

pages=(README.md)
while IFS= read -r page; do pages+=("$page"); done < <(find docs -name '*.md' | sort)

# ---- 1. the front page --------------------------------------------------------
lines=$(wc -l <README.md)
((lines <= 200)) || fail "README.md: $lines lines, more than 200 (the guide belongs in docs/)"
sh_blocks=$(grep -c '^```sh$' README.md || true)
[[ $sh_blocks == 2 ]] || fail "README.md: $sh_blocks \`\`\`sh blocks; .ci/run takes the first two as the README's commands, and there must be no others"

# ---- 2. links ------------------------------------------------------------------
# GitHub's anchor of every heading of PAGE, one a line.
anchors() {
  awk '
    /^ *(```|~~~)/ { fenced = !fenced; next }
    !fenced && /^#+ / {
      s = $0
      sub(/^#+ +/, "", s)
      sub(/ +#* *$/, "", s)
      s = tolower(s)
      gsub(/[^a-z0-9 _-]/, "", s)
      gsub(/ /, "-", s)
      if (s in seen) { seen[s]++; s = s "-" seen[s] } else seen[s] = 0
      print s
    }' "$1"
}
# The links of PAGE: "LINE<TAB>TARGET", one a line (inline code and fenced
# blocks hold no links).
links() {
  awk '
    /^ *(```|~~~)/ { fenced = !fenced; next }
    fenced { next }
    {
      line = $0
      gsub(/`[^`]*`/, "", line)
      while (match(line, /\]\([^)]*\)/)) {
        target = substr(line, RSTART + 2, RLENGTH - 3)
        sub(/ .*/, "", target)  # a title: (path "title")
        print NR "\t" target
        line = substr(line, RSTART + RLENGTH)
      }
    }' "$1"
}
for page in "${pages[@]}"; do
  dir=$(dirname "$page")
  while IFS=$'\t' read -r line target; do
    case $target in
      http://* | https://* | mailto:*) continue ;;
    esac
    path=${target%%#*}
    fragment=""
    [[ $target == *#* ]] && fragment=${target#*#}
    if [[ -z $path ]]; then
      file=$page
    else
      file=$dir/$path
      if [[ ! -e $file ]]; then
        fail "$page:$line: link to $target: no such file"
        continue
      fi
    fi
    if [[ -n $fragment ]]; then
      if [[ $file != *.md ]]; then
        fail "$page:$line: link to $target: a fragment of a file that is not a page"
      elif ! anchors "$file" | grep -qxF -- "$fragment"; then
        fail "$page:$line: link to $target: no heading with that anchor in $file"
      fi
    fi
  done < <(links "$page")
done

# The README's map names every page.
for page in "${pages[@]:1}"; do
  grep -qF "]($page" README.md || fail "README.md: the map of the documentation does not link $page"
done

# ---- 3. no issue numbers -------------------------------------------------------
if grep -nE '[Ii]ssue #?[0-9]' "${pages[@]}"; then
  fail "the lines above cite the issue tracker by number: say what is true instead"
fi

# ---- 4. console blocks ---------------------------------------------------------
lean=0
"$clrt" --version | grep -q 'CLRT_LEAN=ON' && lean=1
mkdir "$work/bin"
ln -s "$clrt" "$work/bin/clrt"
export PATH="$work/bin:$PATH" CLRT_PROGRESS=never
# Does the output in file $2 match the expected lines in file $1?
matches() {
  awk -v expected="$1" -v actual="$2" '
    function line_matches(pattern, text,    n, parts, i, at) {
      n = split(pattern, parts, /\.\.\./)
      if (n == 1) return pattern == text
      if (substr(text, 1, length(parts[1])) != parts[1]) return 0
      text = substr(text, length(parts[1]) + 1)
      for (i = 2; i < n; i++) {
        at = index(text, parts[i])
        if (at == 0) return 0
        text = substr(text, at + length(parts[i]))
      }
      return length(text) >= length(parts[n]) && substr(text, length(text) - length(parts[n]) + 1) == parts[n]
    }
    function match_from(i, j,    k) {
      if (i > m) return j > n
      if (e[i] == "...") {
        for (k = j; k <= n + 1; k++) if (match_from(i + 1, k)) return 1
        return 0
      }
      return j <= n && line_matches(e[i], a[j]) && match_from(i + 1, j + 1)
    }
    BEGIN {
      while ((getline l < expected) > 0) e[++m] = l
      while ((getline l < actual) > 0) a[++n] = l
      exit !match_from(1, 1)
    }'
}
commands=0
skipped=0
for page in "${pages[@]}"; do
  grep -q '^```console' "$page" || continue
  run=$work/run/$page
  rm -rf "$run"
  mkdir -p "$run/expected"
  ln -s "$src/scenes" "$run/scenes"
  # One file per command: N.cmd (the command), N.expected (its output), N.full (a full-build block).
  awk -v out="$run/expected" '
    /^```console/ { inside = 1; full = ($0 ~ /full-build/); next }
    inside && /^```/ { inside = 0; next }
    !inside { next }
    /^\$ / {
      if (k) close(file ".expected")
      file = out "/" (++k)
      printf "%s\n", substr($0, 3) > (file ".cmd")
      close(file ".cmd")
      printf "%d\n", NR > (file ".line")
      close(file ".line")
      printf "" > (file ".expected")
      if (full) { printf "" > (file ".full"); close(file ".full") }
      next
    }
    k { print >> (file ".expected") }
  ' "$page"
  for cmd in "$run"/expected/*.cmd; do
    n=${cmd%.cmd}
    line=$(cat "$n.line")
    if ((lean)) && [[ -e $n.full ]]; then
      skipped=$((skipped + 1))
      continue
    fi
    commands=$((commands + 1))
    status=0
    (cd "$run" && timeout 120 bash -c "$(cat "$cmd")") >"$n.out" 2>&1 || status=$?
    if ((status != 0)); then
      fail "$page:$line: \$ $(cat "$cmd"): exit status $status; it printed:"
      sed 's/^/    /' "$n.out"
    elif ! matches "$n.expected" "$n.out"; then
      fail "$page:$line: \$ $(cat "$cmd"): the output is not the one shown. Shown:"
      sed 's/^/    /' "$n.expected"
      echo "  printed:"
      sed 's/^/    /' "$n.out"
    fi
  done
done

echo "docs: ${#pages[@]} pages, $commands commands run$( ((skipped)) && echo ", $skipped skipped (lean build)")"
exit $bad
