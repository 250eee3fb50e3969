#!/usr/bin/env bash
# Installs the Python package evas (make test, after the tests): the `python`
# component of BUILD into PREFIX (default /usr/local, where Debian's python3
# looks), then makes it visible to the `python3` first on PATH when that is
# another interpreter of the same version (e.g. pyenv's), with a .pth file,
# and checks each interpreter by calling evas (a model of scenes/demo.yaml and
# one force evaluation, not only the import). Debian's python3 must pass; the
# other interpreter's failure (e.g. no NumPy) is printed with the command that
# installs what it lacks (evas names it), and does not fail the install.
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
demo="$(cd "$(dirname "$0")/.." && pwd)/scenes/demo.yaml"
# import evas and use it: a model, its initial state, one force evaluation
call="import evas, sys; m = evas.Model(sys.argv[1]); q, v = m.initial_state(); m.force(0.0, q, v)"
/usr/bin/python3 -c "import sys; sys.path.insert(0, '$dir'); $call" "$demo" ||
  { echo "install_python.sh: evas does not work from $dir with /usr/bin/python3" >&2; exit 1; }
echo "install_python.sh: /usr/bin/python3: evas imported and called: ok"
py="$(command -v python3 || true)"
if [ -n "$py" ] && [ "$(readlink -f "$py")" != "$(readlink -f /usr/bin/python3)" ]; then
  pyver="$("$py" -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
  # evas not found at all (not: found but lacking NumPy, which evas reports itself)
  if [ "$pyver" = "$ver" ] &&
    ! "$py" -c "import importlib.util as u, sys; sys.exit(u.find_spec('evas') is None)" 2>/dev/null; then
    site="$("$py" -c 'import site; print(site.getsitepackages()[0])')"
    echo "$dir" | $SUDO tee "$site/evas.pth" >/dev/null
    echo "install_python.sh: $py finds evas through $site/evas.pth"
  fi
fi
if [ -n "$py" ] && [ "$(readlink -f "$py")" != "$(readlink -f /usr/bin/python3)" ]; then
  if why="$("$py" -c "$call" "$demo" 2>&1)"; then
    echo "install_python.sh: $py: evas imported and called: ok"
  else
    echo "install_python.sh: $py (first on PATH) cannot use evas: $(echo "$why" | tail -1)"
  fi
fi
