#!/usr/bin/env bash
# The FMUs for every platform this project ships, one .fmu per front end and FMI version:
#   build-fmus/tribo_fmi2.fmu, build-fmus/tribo_fmi3.fmu         (dimensionless)
#   build-fmus/tribo_si_fmi2.fmu, build-fmus/tribo_si_fmi3.fmu   (SI units)
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

# ---- sources/: what a C compiler needs to build the FMU anywhere ------------------------------
description_name() { # description_name <prefix> <fmi version>: as fmu/CMakeLists.txt names it
  if [ "$1" = tribo ]; then echo "fmi$2"; else echo "$1_fmi$2"; fi
}
make_sources() { # make_sources <prefix> <fmi version> <folder>
  local prefix=$1 v=$2 dir=$3 sun="$3/sundials" front=front_end_model variables=variables_model
  [ "$prefix" = tribo ] || { front=front_end_si; variables=variables_si; }
  rm -rf "$dir"
  mkdir -p "$dir/tribo/src" "$dir/tribo/fmu" "$sun/include" "$sun/src"
  cp "$ROOT/src"/*.c "$ROOT/src"/*.h "$ROOT/src"/*.def "$dir/tribo/src/"
  for f in "$variables" logging lifecycle step access fmu_state "$front" "fmi$v"; do
    cp "$ROOT/fmu/$f.c" "$dir/tribo/fmu/"
  done
  cp "$ROOT/fmu"/*.h "$ROOT/build/fmu/generated/$(description_name "$prefix" "$v")/instantiation_token.h" \
     "$dir/tribo/fmu/"
  cp "$ROOT/LICENSE" "$dir/tribo/"
  # CVODE: the sources of the objects in the static library the Windows build links (it
  # bundles the dense matrix, linear and nonlinear solvers), their private headers, the
  # public headers and the configured ones
  cp -r "$SUNDIALS_SRC/include/." "$sun/include/"
  cp "$SUNDIALS_WIN/include/sundials/sundials_config.h" "$SUNDIALS_WIN/include/sundials/sundials_export.h" \
     "$sun/include/sundials/"
  # configured for MinGW: make the deprecation attributes portable (empty)
  sed -i 's/__declspec(deprecated(msg))//; s/__attribute__ ((__deprecated__))//' \
     "$sun/include/sundials/sundials_config.h" "$sun/include/sundials/sundials_export.h"
  for obj in $( (ar t "$SUNDIALS_WIN/lib/libsundials_cvode.a"; ar t "$SUNDIALS_WIN/lib/libsundials_nvecserial.a") | sort -u); do
    local c
    c=$(cd "$SUNDIALS_SRC" && find src -name "${obj%.obj}" | head -1)
    mkdir -p "$sun/$(dirname "$c")"
    cp "$SUNDIALS_SRC/$c" "$sun/$c"
    cp "$SUNDIALS_SRC/$(dirname "$c")"/*.h "$sun/$(dirname "$c")/" 2>/dev/null || true
  done
  cp "$SUNDIALS_SRC/LICENSE" "$SUNDIALS_SRC/NOTICE" "$sun/"
  "$PYTHON" "$ROOT/fmu/tools/build_description.py" "$prefix" "$v" "$dir" > "$dir/buildDescription.xml"
}

for prefix in tribo tribo_si; do
  for v in 2 3; do
    if [ "$v" = 2 ]; then linux=linux64 windows=win64; else linux=x86_64-linux windows=x86_64-windows; fi
    id=${prefix}_fmi$v name=$(description_name "$prefix" "$v")
    token=$(sed -n 's/.*"\({[0-9a-f-]*}\)".*/\1/p' "$ROOT/build/fmu/generated/$name/instantiation_token.h")
    grep -q "$token" "$OUT/win64/fmu/lib/$id.dll" ||
      { echo "build_fmus: the Windows binary does not carry the description's token $token" >&2; exit 1; }
    make_sources "$prefix" "$v" "$OUT/sources_$id"
    "$PYTHON" "$ROOT/fmu/tools/pack_fmu.py" --out "$OUT/$id.fmu" \
      --description "$ROOT/build/fmu/$name.xml" --model-doc "$ROOT/docs/model.md" \
      --binary "$linux=$ROOT/build/fmu/lib/$id.so" \
      --binary "$windows=$OUT/win64/fmu/lib/$id.dll" \
      --license license.txt="$ROOT/LICENSE" --license SUNDIALS-LICENSE="$SUNDIALS_SRC/LICENSE" \
      --sources "$OUT/sources_$id" --epoch "$SOURCE_DATE_EPOCH"
    echo "build_fmus: $OUT/$id.fmu"
  done
done
