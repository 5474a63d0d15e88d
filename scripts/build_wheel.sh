#!/usr/bin/env bash
# Builds the Linux wheels of geofair into dist/, one per CPython (pybind11 has no stable ABI):
# the default python3 (3.11: Blender 4.2 to 5.0) and pyenv's 3.12 and 3.13 (3.13: Blender 5.1
# and later), where installed.
#
# GEOFAIR_WHEEL=manylinux_2_28 (default): the wheels that are shipped. zig (PyPI `ziglang`)
#   compiles for glibc 2.28 (Blender's own Linux builds, EL8, the VFX Reference Platform) with
#   LLVM's libc++ linked in statically; OpenMesh and SuiteSparse (CHOLMOD, UMFPACK, METIS)
#   are built once per machine from checksummed sources by cmake/deps (into the folder that
#   scripts/deps_folder.py names) and linked statically; the BLAS is PyPI's scipy-openblas32,
#   a dependency of the wheel that the module loads at import. The module needs nothing but
#   glibc; auditwheel repair checks and tags it. The compiler wrappers (build/zig/) run zig
#   through ccache where it is installed.
# GEOFAIR_WHEEL=system: this machine's GCC, SuiteSparse and OpenBLAS (Debian's),
#   copied into geofair.libs/ by auditwheel; the tag follows this machine's glibc
#   (manylinux_2_35 on Debian 12).
#
#   pip wheel .        scikit-build-core over the CMake build (pyproject.toml)
#   auditwheel repair  the manylinux tag, every library beyond the allow-list in geofair.libs/
#   scripts/wheel_licenses.py  adds the bundled libraries' copyright files to the wheel
# Needs what scripts/setup.sh installs. PYTHONS="/path/to/python3.X ..." for another set.
set -euo pipefail
cd "$(dirname "$0")/.."
KIND="${GEOFAIR_WHEEL:-manylinux_2_28}"
if [ -z "${PYTHONS:-}" ]; then
  PYTHONS="python3"
  PYENV_ROOT="${PYENV_ROOT:-$HOME/.pyenv}"
  for minor in 10 12 13; do
    candidate=$(ls -d "$PYENV_ROOT"/versions/3."$minor".*/bin/python3."$minor" 2>/dev/null | sort -V | tail -1 || true)
    if [ -n "$candidate" ]; then PYTHONS="$PYTHONS $candidate"; fi
  done
fi
case "$KIND" in
  manylinux_2_28)
    # CMake takes a compiler as one program: wrappers around the zig binary of the ziglang
    # package (by path: pip's isolated build environment hides this Python's packages).
    python3 -c 'import ziglang' 2>/dev/null || python3 -m pip install --quiet "ziglang==0.17.1"
    zig=$(python3 -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "zig"))')
    zig_dir="$PWD/build/zig"
    mkdir -p "$zig_dir"
    # Debian's own Pythons keep pyconfig.h in /usr/include/x86_64-linux-gnu/python3.X and
    # include it by that relative path; zig reads no include folder of the machine, so those
    # folders alone are linked into one that the wrappers search last.
    multiarch="$zig_dir/multiarch"
    rm -rf "$multiarch"
    mkdir -p "$multiarch/x86_64-linux-gnu"
    for dir in /usr/include/x86_64-linux-gnu/python3*; do
      if [ -d "$dir" ]; then ln -s "$dir" "$multiarch/x86_64-linux-gnu/"; fi
    done
    # zig caches a compilation (keyed on its arguments, the source and every header it reads)
    # only when no depfile is asked for: the wrappers drop CMake's -MD -MT -MF and write an
    # empty depfile (the object's source is in the build rule). Each wheel is built in a fresh
    # folder (below), so no object outlives a change of a header, and the library's sources
    # compile once for all wheels; only the bindings compile per Python. zig's cache keys on
    # absolute paths: ccache in front of it (where installed) keys on the paths under the clone
    # as relative ones (CCACHE_BASEDIR), so another clone on this machine finds the objects.
    launcher=""
    if command -v ccache >/dev/null; then launcher=ccache; fi
    for tool in cc c++; do
      cat > "$zig_dir/$tool" <<WRAPPER
#!/usr/bin/env bash
args=() depfile="" target=""
while [ \$# -gt 0 ]; do
  case "\$1" in
    -MD) ;;
    -MT) target="\$2"; shift ;;
    -MF) depfile="\$2"; shift ;;
    *) args+=("\$1") ;;
  esac
  shift
done
CCACHE_BASEDIR="$PWD" $launcher "$zig" $tool -target x86_64-linux-gnu.2.28 "\${args[@]}" \
  -idirafter "$multiarch" || exit
if [ -n "\$depfile" ]; then echo "\$target:" > "\$depfile"; fi
WRAPPER
      chmod +x "$zig_dir/$tool"
    done
    # The static dependencies, once per machine (scripts/deps_folder.py: keyed on cmake/deps,
    # the target and zig's version; a later run, in any clone, finds them built), under a lock
    # (another clone's setup may build them at the same time).
    deps=$(python3 scripts/deps_folder.py "$KIND" "$zig" "-target x86_64-linux-gnu.2.28")
    (
      flock 9
      if [ ! -e "$deps/complete" ]; then
        rm -rf "$deps"
        cmake -S cmake/deps -B "$deps" -DCMAKE_C_COMPILER="$zig_dir/cc" \
          -DCMAKE_CXX_COMPILER="$zig_dir/c++" -DCMAKE_INSTALL_PREFIX="$deps/prefix" >/dev/null
        # Not through ccache: its preprocessing only costs here, where the folder is the cache.
        CCACHE_DISABLE=1 cmake --build "$deps" -j"$(nproc)" >"$deps/build.log" 2>&1 ||
          { tail -40 "$deps/build.log"; exit 1; }
        touch "$deps/complete"
      fi
    ) 9>"$deps.lock"
    export CMAKE_ARGS="-DCMAKE_C_COMPILER=$zig_dir/cc -DCMAKE_CXX_COMPILER=$zig_dir/c++ \
-DGEOFAIR_DEPS_PREFIX=$deps/prefix"
    plat=(--plat manylinux_2_28_x86_64 --only-plat)
    ;;
  system)
    plat=()
    ;;
  *)
    echo "GEOFAIR_WHEEL=$KIND: expected manylinux_2_28 or system" >&2
    exit 2
    ;;
esac
rm -rf dist/raw
mkdir -p dist/raw
rm -f dist/geofair-*.whl
build_one() {
  local python="$1" tag ignore=()
  tag=$("$python" -c 'import sys; print(f"cp{sys.version_info[0]}{sys.version_info[1]}")')
  echo "== $KIND $tag: $python"
  rm -rf "build/wheel-$KIND-$tag"
  # cp310 only for the legacy add-on of Blender 3.x and 4.0 (Python 3.10;
  # scripts/build_extension.py): not a wheel of the package, which needs Python 3.11.
  if [ "$tag" = cp310 ]; then ignore=(--ignore-requires-python); fi
  "$python" -m pip wheel . --no-deps "${ignore[@]}" -w dist/raw --config-settings=build-dir="build/wheel-$KIND-$tag"
}
# The first wheel compiles the library (with zig, each object once: its cache); the others
# then compile only their bindings, one translation unit each, so zig's run side by side.
read -r -a pythons <<<"$PYTHONS"
build_one "${pythons[0]}"
pids=() logs=()
for python in "${pythons[@]:1}"; do
  if [ "$KIND" != manylinux_2_28 ]; then build_one "$python"; continue; fi
  log=$(mktemp)
  build_one "$python" >"$log" 2>&1 &
  pids+=("$!") logs+=("$log")
done
failed=0
for k in "${!pids[@]}"; do
  wait "${pids[$k]}" || failed=1
  cat "${logs[$k]}"
  rm -f "${logs[$k]}"
done
if [ "$failed" -ne 0 ]; then echo "a wheel failed to build (its log above)" >&2; exit 1; fi
# auditwheel and the licence step run in the default python3 for every wheel.
rm -rf build/legacy-wheels
for raw in dist/raw/geofair-*.whl; do
  out=dist
  case "$raw" in *-cp310-*) out=build/legacy-wheels ;; esac
  python3 -m auditwheel repair "${plat[@]}" -w "$out" "$raw"
done
rm -rf dist/raw
for wheel in dist/geofair-*.whl build/legacy-wheels/geofair-*.whl; do
  [ -e "$wheel" ] || continue  # no cp310 wheel where PYTHONS has no 3.10
  compiled_in=()
  if [ "$KIND" = manylinux_2_28 ]; then
    tag=$(basename "$wheel" | cut -d- -f3)
    zig_lib=$(python3 -c 'import os, ziglang; print(os.path.dirname(ziglang.__file__))')/lib
    sources="$deps"
    suitesparse="$sources/suitesparse-prefix/src/suitesparse"
    compiled_in=("OpenMesh=$sources/openmesh-prefix/src/openmesh/OpenMesh/LICENSE"
      "SuiteSparse=$suitesparse/LICENSE.txt" "CHOLMOD=$suitesparse/CHOLMOD/Doc/License.txt"
      "UMFPACK=$suitesparse/UMFPACK/Doc/License.txt" "AMD=$suitesparse/AMD/Doc/License.txt"
      "COLAMD=$suitesparse/COLAMD/Doc/License.txt" "METIS=$suitesparse/CHOLMOD/SuiteSparse_metis/LICENSE.txt"
      "libcxx=$zig_lib/libcxx/LICENSE.TXT" "libcxxabi=$zig_lib/libcxxabi/LICENSE.TXT"
      "libunwind=$zig_lib/libunwind/LICENSE.TXT")
  fi
  python3 scripts/wheel_licenses.py "$wheel" "${compiled_in[@]}"
  python3 -m auditwheel show "$wheel"
done
