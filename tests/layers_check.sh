#!/usr/bin/env bash
# CTest Build.LayersAreEnforced: cmake/evas_layers.cmake stops the configuration
# when a layer includes a header of a layer above it (docs/architecture.md).
# A tree of empty layers configures; the same tree with model/ including io/
# fails, naming the file, the include and the rule; so does elements/ including
# solver/ (a layer beside and above it), while solver/ including elements/ is
# allowed.
#   tests/layers_check.sh SOURCE_DIR
set -euo pipefail
src="$(cd "$1" && pwd)"  # absolute: the probe project is configured elsewhere
tmp="$(mktemp -d "${TMPDIR:-/tmp}/evas-layers.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
tree="$tmp/tree"
for layer in model bodies elements dae problems solver integrators post io run plot study; do
  mkdir -p "$tree/$layer"
  echo "int evas_probe_$layer() { return 0; }" > "$tree/$layer/$layer.cpp"
done
cat > "$tmp/CMakeLists.txt" <<CM
cmake_minimum_required(VERSION 3.20)
project(layers_probe LANGUAGES CXX)
set(EVAS_ROOT "$tree")
include("$src/cmake/evas_layers.cmake")
evas_add_layers(probe)
CM
configure() { cmake -S "$tmp" -B "$tmp/build-$1" >"$tmp/$1.log" 2>&1; }
# the log with CMake's line wrapping undone
said() { tr -s ' \n' '  ' <"$tmp/$1.log" | grep -q "$2"; }

echo '#include "elements/element.h"' > "$tree/solver/allowed.h"
configure clean || { echo "a tree without upward includes did not configure:"; cat "$tmp/clean.log"; exit 1; }

echo '#include "io/scene.h"' > "$tree/model/up.h"
if configure up; then echo "model/ including io/ configured"; exit 1; fi
said up "model/up.h: '#include \"io/scene.h\"' runs from the layer 'model' to 'io'" ||
  { echo "the failure does not name the file and the rule:"; cat "$tmp/up.log"; exit 1; }
rm "$tree/model/up.h"

echo '#include "solver/system.h"' > "$tree/elements/side.h"
if configure side; then echo "elements/ including solver/ configured"; exit 1; fi
said side "elements/side.h: .* runs from the layer 'elements' to 'solver', which it may not use (it may use: model;" ||
  { cat "$tmp/side.log"; exit 1; }
echo "layers enforced: an upward include stops the configuration"
