#!/usr/bin/env bash
# CTest Install.OutsideProject: `cmake --install` of this build into a temporary
# prefix; the two examples built there as outside projects with find_package(evas)
# (examples/radau_plugin: an integrator plug-in, examples/compare_integrators: a
# program linking evas::evas); the installed evas runs the demo scene with the
# plug-in, and the outside program finds it agrees with IDA.
#
#   tests/install_check.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src="$1"
build="$2"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/evas-install.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log"
for ex in radau_plugin compare_integrators; do
  cmake -S "$src/examples/$ex" -B "$tmp/$ex" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
    -DCMAKE_BUILD_TYPE=Release >"$tmp/$ex.log" || { cat "$tmp/$ex.log"; exit 1; }
  cmake --build "$tmp/$ex" -j2 >>"$tmp/$ex.log" || { cat "$tmp/$ex.log"; exit 1; }
done
plugin="$tmp/radau_plugin/libevas_radau.so"
# the demo scene (generated bodies only), shortened to 0.02 s
sed 's/^time: .*/time: {start: 0, end: 0.02}/' "$src/scenes/demo.yaml" >"$tmp/demo.yaml"
"$tmp/prefix/bin/evas" run "$tmp/demo.yaml" --plugin "$plugin" --integrator radau-iia \
  --set step=1e-5 --out "$tmp/out" -q
grep -q '"status": "completed"' "$tmp/out/summary.json"
out="$("$tmp/compare_integrators/evas_compare" "$tmp/demo.yaml" ida radau-iia "$plugin" step=1e-5)"
echo "$out"
d="$(echo "$out" | sed -n 's/.*max relative difference //p')"
# Radau IIA (order 3) at h = 1e-5 s against IDA at rtol 1e-10: measured 7e-5
awk -v d="$d" 'BEGIN { exit !(d != "" && d < 1e-4) }'
