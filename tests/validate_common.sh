# Sourced by the validation scripts: the project root, the Python with
# numpy/h5py, the work folder $W (build/validate/NAME, or under
# $VALIDATE_WORK), JOBS runs at a time, and a copy of bin/udar in $W (a
# rebuild during the runs must not change them).
#   source tests/validate_common.sh NAME
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
ROOT=$PWD
PYTHON=${PYTHON:-/usr/bin/python3}
W=${VALIDATE_WORK:-$ROOT/build/validate}/$1
JOBS=${JOBS:-2}
mkdir -p "$W" doc/validation
cp bin/udar "$W/udar"
