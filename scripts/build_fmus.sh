#!/usr/bin/env bash
# The FMUs for every platform this project ships, one .fmu per front end and FMI version:
#   build-fmus/tribo_fmi2.fmu, build-fmus/tribo_fmi3.fmu         (dimensionless)
#   build-fmus/tribo_si_fmi2.fmu, build-fmus/tribo_si_fmi3.fmu   (SI units)
#   build-fmus/tribo_separator_fmi2.fmu, ..._fmi3.fmu            (the free-fall separator)
# each with the Linux x86-64 binary (the native build, build/), the Windows x86-64 binary
# (cross-compiled with Debian's MinGW-w64, CVODE built from Debian's source package of
# SUNDIALS, the same version as the native build links), sources/ (the core, the FMI
# layer and the CVODE sources they need, with buildDescription.xml), and documentation/
# with the licences. Then checks the Windows binaries under Wine against the native ones
# (tests/python/test_platforms.py does it in the test suite). Safe to re-run: only what is
# missing or changed is rebuilt. SOURCE_DATE_EPOCH (default: the last commit's time) dates
# the descriptions and the archives, so the same commit gives the same bytes.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT="$ROOT/build-fmus"
export SOURCE_DATE_EPOCH=${SOURCE_DATE_EPOCH:-$(git -C "$ROOT" log -1 --format=%ct)}

TRIBO_SETUP_WINDOWS=1 "$ROOT/scripts/setup.sh"
# the descriptions carry the source date: configure the native build with it
cmake -S "$ROOT" -B "$ROOT/build" >/dev/null
cmake --build "$ROOT/build"
PYTHON="$ROOT/.venv/bin/python"
mkdir -p "$OUT"

# ---- CVODE for Windows (static), from Debian's source package of SUNDIALS (setup.sh fetched
# it for the native build) ----------------------------------------------------------------
# shellcheck source=sundials.sh
. "$ROOT/scripts/sundials.sh"
SUNDIALS_SRC="$ROOT/build-sundials/src"
SUNDIALS_WIN="$ROOT/build-sundials/win64"
TOOLCHAIN="$ROOT/cmake/mingw-w64-x86_64.cmake"
sundials_source "$ROOT/build-sundials"
sundials_build "$SUNDIALS_SRC" "$ROOT/build-sundials/build-win64" "$SUNDIALS_WIN" \
  -DCMAKE_TOOLCHAIN_FILE="$TOOLCHAIN"

# ---- the FMUs' Windows binaries, with the native build's descriptions and tokens ---------
if [ ! -f "$OUT/win64/build.ninja" ]; then
  cmake -S "$ROOT" -B "$OUT/win64" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$TOOLCHAIN" \
    -DCMAKE_BUILD_TYPE=Release -DTRIBO_WERROR=ON -DTRIBO_PYTHON="$PYTHON" \
    -DTRIBO_HOST_BUILD="$ROOT/build" -DCMAKE_FIND_ROOT_PATH="$SUNDIALS_WIN" >/dev/null
fi
cmake --build "$OUT/win64"

# ---- sources/: what a C compiler needs to build the FMU anywhere, with only sources/ and the
# importer's FMI headers on its include path (fmu/tools/make_sources.py lays it out) -------
description_name() { # description_name <prefix> <fmi version>: as fmu/CMakeLists.txt names it
  if [ "$1" = tribo ]; then echo "fmi$2"; else echo "$1_fmi$2"; fi
}
make_sources() { # make_sources <prefix> <fmi version> <folder>
  # the core's and CVODE's sources of the objects the two binaries link (the linkers' maps;
  # CVODE's static libraries bundle the dense matrix, linear and nonlinear solvers), with
  # SUNDIALS' headers configured for the Windows build
  local id=$1_fmi$2
  "$PYTHON" "$ROOT/fmu/tools/make_sources.py" --prefix "$1" --version "$2" --out "$3" \
    --link-map "$ROOT/build/fmu/lib/$id.map" --link-map "$OUT/win64/fmu/lib/$id.map" \
    --token "$ROOT/build/fmu/generated/$(description_name "$1" "$2")/instantiation_token.h" \
    --sundials "$SUNDIALS_SRC" --sundials-config "$SUNDIALS_WIN/include/sundials" \
    --sundials-library "$SUNDIALS_WIN/lib/libsundials_cvode.a" \
    --sundials-library "$SUNDIALS_WIN/lib/libsundials_nvecserial.a"
}

for prefix in tribo tribo_si tribo_separator; do
  for v in 2 3; do
    if [ "$v" = 2 ]; then linux=linux64 windows=win64; else linux=x86_64-linux windows=x86_64-windows; fi
    id=${prefix}_fmi$v name=$(description_name "$prefix" "$v")
    token=$(sed -n 's/.*"\({[0-9a-f-]*}\)".*/\1/p' "$ROOT/build/fmu/generated/$name/instantiation_token.h")
    grep -q "$token" "$OUT/win64/fmu/lib/$id.dll" ||
      { echo "build_fmus: the Windows binary does not carry the description's token $token" >&2; exit 1; }
    make_sources "$prefix" "$v" "$OUT/sources_$id"
    description="$ROOT/build/fmu/$name.xml"
    if [ "$v" = 2 ]; then
      # FMI 2.0 importers read the files to compile from the description's <SourceFiles>
      "$PYTHON" "$ROOT/fmu/tools/add_source_files.py" "$description" \
        "$OUT/sources_$id/buildDescription.xml" > "$OUT/$id.xml"
      description="$OUT/$id.xml"
    fi
    "$PYTHON" "$ROOT/fmu/tools/pack_fmu.py" --out "$OUT/$id.fmu" \
      --description "$description" --model-doc "$ROOT/docs/model.md" \
      --binary "$linux=$ROOT/build/fmu/lib/$id.so" \
      --binary "$windows=$OUT/win64/fmu/lib/$id.dll" \
      --license license.txt="$ROOT/LICENSE" --license SUNDIALS-LICENSE="$SUNDIALS_SRC/LICENSE" \
      --sources "$OUT/sources_$id" --epoch "$SOURCE_DATE_EPOCH"
    echo "build_fmus: $OUT/$id.fmu"
  done
done
