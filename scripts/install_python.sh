#!/usr/bin/env bash
# Installs the Python package evas (make test, after the tests): the `python`
# component of BUILD into PREFIX (default /usr/local, where Debian's python3
# looks), then makes it visible to the `python3` first on PATH when that is
# another interpreter of the same version (e.g. pyenv's), with a .pth file,
# and checks `python3 -c "import evas"`.
#
#   scripts/install_python.sh BUILD [PREFIX]
set -euo pipefail
build="$1"
prefix="${2:-/usr/local}"
SUDO=""
[ "$(id -u)" = 0 ] || SUDO=sudo
$SUDO cmake --install "$build" --component python --prefix "$prefix" >/dev/null
ver="$(/usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
dir="$prefix/lib/python$ver/dist-packages"
/usr/bin/python3 -c "import sys; sys.path.insert(0, '$dir'); import evas" ||
  { echo "install_python.sh: evas does not import from $dir" >&2; exit 1; }
py="$(command -v python3 || true)"
if [ -n "$py" ] && [ "$(readlink -f "$py")" != "$(readlink -f /usr/bin/python3)" ]; then
  pyver="$("$py" -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
  if [ "$pyver" = "$ver" ] && ! "$py" -c "import evas" 2>/dev/null; then
    site="$("$py" -c 'import site; print(site.getsitepackages()[0])')"
    echo "$dir" | $SUDO tee "$site/evas.pth" >/dev/null
    echo "install_python.sh: $py finds evas through $site/evas.pth"
  fi
fi
python3 -c "import evas; print('python3 -c \"import evas\": ok,', evas.__file__)"
