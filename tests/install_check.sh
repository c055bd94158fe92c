#!/usr/bin/env bash
# install_check.sh BUILD_DIR SOURCE_DIR [PYTHON PYTHON_DIR] - `cmake --install`
# into a temporary prefix, then the installed tree, moved elsewhere, must work
# on its own: bin/clrt prints the version of CMakeLists.txt's project(), finds
# its imaging module under lib*/clrt/ (not the build directory's) and writes a
# PNG; the bash completion and, when built, the man page are installed. With
# PYTHON (the interpreter) and PYTHON_DIR (CLRT_PYTHON_INSTALL_DIR): the Python
# package under PREFIX/PYTHON_DIR imports from there, loads the same module to
# encode a PNG, and PYTHON_DIR under /usr/local is on the interpreter's path.
# Registered with CTest (CMakeLists.txt, "install").
set -euo pipefail
build=$1 src=$2 python=${3:-} python_dir=${4:-}
fail() { echo "install_check: FAIL: $*" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log" 2>&1 || { cat "$tmp/install.log"; fail "cmake --install"; }
# Moved after installing: nothing may point back into the install prefix.
mv "$tmp/prefix" "$tmp/moved"
root=$tmp/moved
clrt=$root/bin/clrt
[ -x "$clrt" ] || fail "no bin/clrt"
mapfile -t modules < <(find "$root" -name clrt_imageio.so)
[ ${#modules[@]} -eq 1 ] || fail "expected one clrt_imageio.so, found: ${modules[*]:-none}"
[[ ${modules[0]} == "$root"/lib*/clrt/clrt_imageio.so ]] || fail "module at ${modules[0]}"

want=$(sed -nE 's/^project\(clrt .*VERSION ([0-9][0-9.]*).*/\1/p' "$src/CMakeLists.txt")
[ -n "$want" ] || fail "no version in CMakeLists.txt"
first=$("$clrt" --version | head -n 1)
[ "$first" = "clrt $want" ] || fail "--version says '$first', CMakeLists.txt says $want"

# A tiny image with the reference engine (no OpenCL device needed), loading
# the installed module, and no other.
export CLRT_CACHE_DIR=$tmp/cache
out=$tmp/out.png
LD_DEBUG=files "$clrt" render "$src/scenes/cgfs-demo.json" --engine reference --width 8 --height 8 -o "$out" \
  2>"$tmp/ld.log" || { tail -n 5 "$tmp/ld.log"; fail "render with the installed clrt"; }
[ "$(head -c 8 "$out" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "out.png is not a PNG"
grep -q "file=${modules[0]} " "$tmp/ld.log" || fail "the installed module was not the one loaded"
if grep -oE "file=[^ ]*clrt_imageio\.so " "$tmp/ld.log" | grep -vqF "file=${modules[0]} "; then
  fail "another module was loaded"
fi
# The same through OpenCL where a device is installed.
if "$clrt" devices >/dev/null 2>&1; then
  rm -f "$out"
  "$clrt" render "$src/scenes/cgfs-demo.json" --width 8 --height 8 -o "$out" || fail "OpenCL render"
  [ -s "$out" ] || fail "OpenCL render wrote nothing"
fi
# $CLRT_IMAGEIO_MODULE still names the module instead.
set +e
CLRT_IMAGEIO_MODULE=$tmp/none.so "$clrt" render "$src/scenes/cgfs-demo.json" --engine reference --width 8 \
  --height 8 -o "$tmp/x.png" 2>"$tmp/err"
status=$?
set -e
[ $status -eq 2 ] && grep -q "$tmp/none.so" "$tmp/err" || fail "CLRT_IMAGEIO_MODULE=missing: status $status, $(cat "$tmp/err")"
CLRT_IMAGEIO_MODULE=${modules[0]} "$clrt" render "$src/scenes/cgfs-demo.json" --engine reference --width 8 \
  --height 8 -o "$tmp/y.png" || fail "CLRT_IMAGEIO_MODULE=installed module"

if [ -n "$python" ]; then
  site=$root/$python_dir
  [ -f "$site/clrt/__init__.py" ] && compgen -G "$site/clrt/_clrt*.so" >/dev/null || fail "no Python package in $site/clrt"
  "$python" -c 'import sys; sys.exit(0 if sys.argv[1] in sys.path else 1)' "/usr/local/$python_dir" ||
    fail "/usr/local/$python_dir is not on $python's sys.path: the default prefix would need PYTHONPATH"
  rm -f "$out"
  PYTHONPATH=$site LD_DEBUG=files "$python" -c '
import os, sys, clrt
assert os.path.realpath(clrt.__file__).startswith(os.path.realpath(sys.argv[3])), clrt.__file__
img = clrt.reference(sys.argv[1], 8, 8)
open(sys.argv[2], "wb").write(img.to_png())' "$src/scenes/cgfs-demo.json" "$out" "$site" 2>"$tmp/py-ld.log" ||
    { grep -v "^ *[0-9]*:" "$tmp/py-ld.log" | tail -n 5; fail "the installed Python package"; }
  [ "$(head -c 8 "$out" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "the Python package's PNG is not a PNG"
  grep -q "file=${modules[0]} " "$tmp/py-ld.log" || fail "the Python package did not load the installed module"
  if grep -oE "file=[^ ]*clrt_imageio\.so " "$tmp/py-ld.log" | grep -vqF "file=${modules[0]} "; then
    fail "the Python package loaded another module"
  fi
fi

completion=$root/share/bash-completion/completions/clrt
[ -f "$completion" ] || fail "no bash completion"
bash -n "$completion" || fail "the completion script does not parse"
if [ -f "$build/clrt.1" ]; then
  [ -f "$root/share/man/man1/clrt.1" ] || fail "clrt.1 built but not installed"
  grep -q '^\.TH CLRT' "$root/share/man/man1/clrt.1" || fail "clrt.1 is not a man page"
else
  echo "install_check: no man page in $build (help2man not found at configure time)"
fi
echo "install_check: the installed tree works (clrt $want, module ${modules[0]#"$root"/}${python:+, Python package $python_dir/clrt})"
