#!/bin/bash
# `cmake --install` into a fresh prefix: the command runs from <prefix>/bin,
# and Debian's python3 imports the module from the directory it searches for
# that prefix's packages (<prefix>/lib/python3.X/dist-packages, as
# /usr/local/lib/python3.X/dist-packages for the default prefix), from a
# directory that is not the build's.
#   install_check.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1
work=$2
rm -rf "$work"
mkdir -p "$work/elsewhere"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
cd "$work/elsewhere"
"$prefix/bin/sizemesh" --version
site=$(/usr/bin/python3 -c 'import sys; print("lib/python%d.%d/dist-packages" % sys.version_info[:2])')
PYTHONPATH="$prefix/$site" /usr/bin/python3 - "$prefix" <<'PY'
import os, sys
import sizemesh
prefix = os.path.realpath(sys.argv[1])
where = os.path.realpath(sizemesh.__file__)
assert where.startswith(prefix + os.sep), where
print("module", sizemesh.__version__, "from", where)
PY
