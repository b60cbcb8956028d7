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

# ---- SUNDIALS' sources: Debian's source package, through a private sources list ---------
# apt reads a deb-src copy of the system's Debian entries and keeps its lists in
# $OUT/apt, so the system's apt configuration is left as it is.
version=$(dpkg-query -W -f='${source:Version}' libsundials-dev)
SUNDIALS_SRC="$OUT/sundials/src"
if [ ! -f "$SUNDIALS_SRC/.version" ] || [ "$(cat "$SUNDIALS_SRC/.version")" != "$version" ]; then
  echo "build_fmus: fetching the source package sundials $version"
  APT="$OUT/apt"
  rm -rf "$APT" "$OUT/sundials"
  mkdir -p "$APT/parts" "$APT/lists/partial" "$APT/cache/archives/partial" "$OUT/sundials"
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -e "$f" ] && sed 's/^Types:.*/Types: deb-src/' "$f" > "$APT/parts/$(basename "$f")"
  done
  if [ -f /etc/apt/sources.list ]; then
    sed -n 's/^deb /deb-src /p' /etc/apt/sources.list > "$APT/parts/system.list"
  fi
  apt_options=(-o Dir::Etc::SourceList=/dev/null -o Dir::Etc::SourceParts="$APT/parts"
               -o Dir::State::Lists="$APT/lists" -o Dir::Cache="$APT/cache"
               -o APT::Sandbox::User=root)
  apt-get "${apt_options[@]}" update -qq
  (cd "$OUT/sundials" && apt-get "${apt_options[@]}" source --download-only -qq "sundials=$version")
  dpkg-source -x "$OUT/sundials"/sundials_*.dsc "$SUNDIALS_SRC" >/dev/null
  echo "$version" > "$SUNDIALS_SRC/.version"
fi

# ---- CVODE for Windows (static) ------------------------------------------------------------
TOOLCHAIN="$ROOT/cmake/mingw-w64-x86_64.cmake"
SUNDIALS_WIN="$OUT/sundials/win64"
if [ ! -f "$SUNDIALS_WIN/lib/libsundials_cvode.a" ]; then
  echo "build_fmus: building CVODE for Windows"
  cmake -S "$SUNDIALS_SRC" -B "$OUT/sundials/build-win64" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$TOOLCHAIN" \
    -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=OFF -DBUILD_STATIC_LIBS=ON \
    -DBUILD_ARKODE=OFF -DBUILD_CVODES=OFF -DBUILD_IDA=OFF -DBUILD_IDAS=OFF -DBUILD_KINSOL=OFF \
    -DBUILD_CVODE=ON -DEXAMPLES_ENABLE_C=OFF -DEXAMPLES_INSTALL=OFF -DSUNDIALS_INDEX_SIZE=64 \
    -DCMAKE_INSTALL_PREFIX="$SUNDIALS_WIN" >/dev/null
  cmake --build "$OUT/sundials/build-win64" >/dev/null
  cmake --install "$OUT/sundials/build-win64" >/dev/null
fi

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
  # CVODE: the sources of the objects in the static libraries the Windows build links (they
  # bundle the dense matrix, linear and nonlinear solvers), with the headers configured there
  "$PYTHON" "$ROOT/fmu/tools/make_sources.py" --prefix "$1" --version "$2" --out "$3" \
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
