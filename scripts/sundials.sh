#!/usr/bin/env bash
# Sourced by setup.sh and build_fmus.sh: CVODE from Debian's source package of SUNDIALS, the
# version libsundials-dev installs, built optimised. Debian builds its SUNDIALS libraries
# without optimisation (-O0), and CVODE's steps and vector operations are a large part of a
# run's cost; the same sources compiled with -O2 give every result to the bit (baseline
# x86-64 has no fused multiply-add to contract into; the regression test holds it).
#
#   sundials_source DIR                    Debian's sources of that version in DIR/src
#   sundials_build SRC BUILD PREFIX ARGS   CVODE and the serial vector, static, installed
#                                          into PREFIX (ARGS: more CMake arguments)

sundials_version() {
  dpkg-query -W -f='${source:Version}' libsundials-dev
}

# apt reads a deb-src copy of the system's Debian entries and keeps its lists in DIR/apt,
# so the system's apt configuration is left as it is.
sundials_source() {
  local dir=$1 version apt f
  version=$(sundials_version)
  if [ -f "$dir/src/.version" ] && [ "$(cat "$dir/src/.version")" = "$version" ]; then
    return 0
  fi
  echo "sundials: fetching the source package sundials $version"
  apt="$dir/apt"
  rm -rf "$dir"
  mkdir -p "$apt/parts" "$apt/lists/partial" "$apt/cache/archives/partial" "$dir/package"
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -e "$f" ] && sed 's/^Types:.*/Types: deb-src/' "$f" > "$apt/parts/$(basename "$f")"
  done
  if [ -f /etc/apt/sources.list ]; then
    sed -n 's/^deb /deb-src /p' /etc/apt/sources.list > "$apt/parts/system.list"
  fi
  local options=(-o Dir::Etc::SourceList=/dev/null -o Dir::Etc::SourceParts="$apt/parts"
                 -o Dir::State::Lists="$apt/lists" -o Dir::Cache="$apt/cache"
                 -o APT::Sandbox::User=root)
  # into SETUP_LOG (setup.sh's; else a log of its own): apt's gpgv and dpkg-source's
  # signature warnings (no keyring for Debian's source signatures here; apt checks the
  # sources' hashes); the log's end said where a step fails
  local log=${SETUP_LOG:-$dir/fetch.log}
  { apt-get "${options[@]}" update -qq &&
    (cd "$dir/package" && apt-get "${options[@]}" source --download-only -qq "sundials=$version") &&
    dpkg-source -x "$dir/package"/sundials_*.dsc "$dir/src"; } >>"$log" 2>&1 ||
    { echo "sundials: fetching the sources failed; the end of $log:" >&2; tail -n 20 "$log" >&2
      return 1; }
  echo "$version" > "$dir/src/.version"
}

sundials_build() {
  local src=$1 build=$2 prefix=$3 version
  shift 3
  version=$(cat "$src/.version")
  if [ -f "$prefix/lib/libsundials_cvode.a" ] && [ "$(cat "$prefix/.version" 2>/dev/null)" = "$version" ]; then
    return 0
  fi
  echo "sundials: building CVODE $version into $prefix"
  local log=${SETUP_LOG:-$build.log}
  rm -rf "$build" "$prefix"
  cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_LIBDIR=lib \
    -DBUILD_SHARED_LIBS=OFF -DBUILD_STATIC_LIBS=ON \
    -DBUILD_ARKODE=OFF -DBUILD_CVODES=OFF -DBUILD_IDA=OFF -DBUILD_IDAS=OFF -DBUILD_KINSOL=OFF \
    -DBUILD_CVODE=ON -DEXAMPLES_ENABLE_C=OFF -DEXAMPLES_INSTALL=OFF -DSUNDIALS_INDEX_SIZE=64 \
    -DCMAKE_INSTALL_PREFIX="$prefix" "$@" >>"$log" 2>&1 &&
  cmake --build "$build" >>"$log" 2>&1 ||
    { echo "sundials: building CVODE failed; the end of $log:" >&2; tail -n 20 "$log" >&2
      return 1; }
  cmake --install "$build" > "$build/install.log" 2>&1 || { cat "$build/install.log" >&2; return 1; }
  echo "$version" > "$prefix/.version"
}
