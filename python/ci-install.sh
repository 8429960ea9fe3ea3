#!/usr/bin/env bash
# CI: the documented install of the Python package, end to end, offline and with Debian's packages only
# (python/README.md, "Install"): a venv with --system-site-packages, `pip install --no-build-isolation
# --no-deps ./python` (setup.py builds the extension with the project's CMake, from scratch in a temporary
# build directory), then the package's API tests run against the INSTALLED package from outside the source
# tree, and a check that it is complete (extension, pure-Python modules, stubs, py.typed).
#
#   python/ci-install.sh                   # .ci/run calls it
#   KEEP=1 python/ci-install.sh            # keep the temporary directory
#   RAYKERNEL_CMAKE_BUILD_DIR=build python/ci-install.sh   # reuse a configured build (faster; skips the scratch build)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
python=${RAYKERNEL_PYTHON:-/usr/bin/python3}
start=$(date +%s)
work=$(mktemp -d "${TMPDIR:-/tmp}/raykernel-python.XXXXXX")
cleanup() { if [ "${KEEP:-0}" = 1 ] || [ "${ok:-0}" != 1 ]; then echo "ci-install: kept $work"; else rm -rf "$work"; fi; }
trap cleanup EXIT
step() { printf '\n-- python ci-install: %s (%ds)\n' "$*" "$(( $(date +%s) - start ))"; }
fail() { printf 'python ci-install: FAIL: %s\n' "$*" >&2; exit 1; }

step "venv with Debian's site packages ($python)"
"$python" -m venv --system-site-packages "$work/venv"
venv_python=$work/venv/bin/python

step "pip install --no-build-isolation --no-deps ./python"
export RAYKERNEL_CMAKE_BUILD_DIR=${RAYKERNEL_CMAKE_BUILD_DIR:-$work/cmake-build}
export RAYKERNEL_BUILD_JOBS=${RAYKERNEL_BUILD_JOBS:-2}
# pip builds in the source tree (python/build, python/*.egg-info: ignored by git); -v shows the CMake build.
if ! "$venv_python" -m pip install -v --no-build-isolation --no-deps ./python > "$work/pip.log" 2>&1; then
  tail -40 "$work/pip.log"
  fail "pip install failed (log: $work/pip.log)"
fi
grep -E "^Successfully installed raykernel-" "$work/pip.log"

step "the installed package is complete"
cd "$work"  # nothing of the source tree on sys.path from here
site=$("$venv_python" -c 'import raykernel, os; print(os.path.dirname(raykernel.__file__))')
case "$site" in "$work/venv/"*) ;; *) fail "raykernel imported from $site, not from the venv" ;; esac
for f in __init__.py __main__.py _types.py _raykernel.pyi py.typed testing/__init__.py testing/reference.py \
         testing/exact.py testing/hypothesis.py dask.py; do
  [ -f "$site/$f" ] || fail "$f not installed"
done
ls "$site"/_raykernel*.so > /dev/null || fail "the extension is not installed"
"$venv_python" - <<'PY'
import raykernel as rk
from raykernel.testing.hypothesis import hard_queries  # needs Hypothesis from Debian, through the venv
x = rk.intersect(((0, 0, 0), (10, 0, 0)), ((1, 0, 0), (1, 0, 0)))
assert x == (rk.Relation.HIT, 0.1), x
y = rk.intersect(((0.5, 0, -1), (0, 0, 3)), ((0, 0, 0), (1, 0, 0), (0, 1, 0)))
assert (y.relation, y.location, y.barycentric) == ("hit", "edge-ab", (0.5, 0.5, 0.0)), y
print(f"raykernel {rk.__version__} from {rk.__file__}: {x}")
PY

step "the console script and python -m raykernel (the C++ tool compiled into the extension)"
[ -x "$work/venv/bin/raykernel" ] || fail "the raykernel console script is not installed"
got=$(echo '0 0 0 1 0 0 5 0 0 1 0 0' | "$work/venv/bin/raykernel" classify --exact-t) || fail "raykernel classify failed"
[ "$got" = "hit 5 5/1" ] || fail "raykernel classify printed '$got'"
got=$("$venv_python" -m raykernel --version) || fail "python -m raykernel --version failed"
[ "$got" = "raykernel $("$venv_python" -c 'import raykernel; print(raykernel.__version__)')" ] || fail "python -m raykernel --version printed '$got'"
echo "raykernel console script: $got"

step "the API tests against the installed package"
PYTHONDONTWRITEBYTECODE=1 "$venv_python" -m pytest -p no:cacheprovider -q \
  "$root/python/tests/test_scalar.py" "$root/python/tests/test_nearest.py" "$root/python/tests/test_arrays.py" \
  "$root/python/tests/test_stubs.py" "$root/python/tests/test_testing.py" "$root/python/tests/test_triangles.py" \
  "$root/python/tests/test_spheres.py" "$root/python/tests/test_mesh.py" "$root/python/tests/test_dask.py" \
  "$root/python/tests/test_console.py"

ok=1
step "done"
