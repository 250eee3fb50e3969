#!/usr/bin/env bash
# Sourced by scripts/fuzz.sh and scripts/sanitize.sh: installs clang with the
# libFuzzer and sanitizer runtimes (Debian 12: clang, libclang-rt-14-dev),
# python3 and gdb when missing, and points the sanitizers at llvm-symbolizer.
need=""
command -v clang++ >/dev/null 2>&1 || need="$need clang"
command -v python3 >/dev/null 2>&1 || need="$need python3"
command -v gdb >/dev/null 2>&1 || need="$need gdb"  # fuzz.sh: stacks of out-of-memory inputs
ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1 ||
  need="$need libclang-rt-14-dev"
if [ -n "$need" ]; then
  echo "installing:$need"
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $need
fi
symbolizer="$(command -v llvm-symbolizer || ls /usr/lib/llvm-*/bin/llvm-symbolizer 2>/dev/null | tail -1 || true)"
[ -n "$symbolizer" ] && export ASAN_SYMBOLIZER_PATH="$symbolizer"
true
