#!/usr/bin/env bash
# Sourced by the benchmarks that take --before REV: bench_at_revision REV SOURCE OUT compiles
# the benchmark SOURCE (a C file of bench/) against revision REV's core, built in a
# temporary folder under OUT's folder, into the program OUT. Only the core is built (no
# FMUs, no tests), with every folder of that revision's src/ on the include path (its files
# include by name), so that a benchmark written against the C API compiles against any
# revision that has the calls it makes; both link the same CVODE unless
# BENCH_BEFORE_SUNDIALS=debian.
bench_at_revision() {
  local rev=$1 source=$2 out=$3 root work
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  work=$(dirname "$out")/core-$rev
  mkdir -p "$work/src"
  git -C "$root" archive "$rev" | tar -x -C "$work/src"
  # the CVODE this checkout's build links (scripts/setup.sh's, optimised), so that the two
  # differ by their code alone; Debian's (unoptimised) where there is none or where
  # BENCH_BEFORE_SUNDIALS=debian asks for the revision as it was built before setup.sh built
  # its own
  local sundials="$root/build-sundials/native" cmake_args=() libraries=()
  if [ -f "$sundials/lib/libsundials_cvode.a" ] && [ "${BENCH_BEFORE_SUNDIALS:-}" != debian ]; then
    cmake_args=(-DSUNDIALS_DIR="$sundials/lib/cmake/sundials")
    libraries=("$sundials/lib/libsundials_cvode.a" "$sundials/lib/libsundials_nvecserial.a")
  else
    libraries=(-lsundials_cvode -lsundials_nvecserial)
  fi
  cmake -S "$work/src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DTRIBO_BUILD_FMU=OFF -DTRIBO_BUILD_TESTS=OFF "${cmake_args[@]}" >/dev/null
  cmake --build "$work/build" --target tribo_core >/dev/null
  local includes=() folder
  while IFS= read -r folder; do includes+=(-I"$folder"); done < <(find "$work/src/src" -type d)
  cc -O3 -DNDEBUG -std=c11 -D_DEFAULT_SOURCE "${includes[@]}" "$source" \
     "$work/build/libtribo_core.a" "${libraries[@]}" -lm -o "$out"
}
