#!/usr/bin/env bash
# Set-up shared by the README's commands, safe to re-run: installs what is missing
# (Debian packages, the Python venv when requirements.txt changed) and builds.
# Nothing is reinstalled when nothing changed.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# dpkg-dev: dpkg-source, for SUNDIALS' source package (scripts/sundials.sh)
APT_PACKAGES=(build-essential cmake ninja-build pkg-config libsundials-dev libcriterion-dev
              dpkg-dev python3 python3-venv zip libtbb12
              liggghts)  # tribo dem's DEM engine (docs/dem.md)
# scripts/build_fmus.sh: Windows binaries (MinGW-w64), checked under Wine
if [ "${TRIBO_SETUP_WINDOWS:-0}" = 1 ]; then
  APT_PACKAGES+=(gcc-mingw-w64-x86-64 wine64)
fi
missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO=sudo
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# Debian's python3 (not whatever python3 is first on PATH), so that a fresh Debian 12
# machine and this one get the same interpreter.
PYTHON=/usr/bin/python3
VENV="$ROOT/.venv"
# the venv is made again when the pinned requirements or the package's metadata change
want=$(cat "$ROOT/requirements.txt" "$ROOT/pyproject.toml" | sha256sum | cut -d' ' -f1)
make_venv() {
  echo "setup: creating the Python venv in .venv"
  rm -rf "$VENV"
  "$PYTHON" -m venv "$VENV"
  # byte-compiled at install (pip's default): an environment with PYTHONDONTWRITEBYTECODE
  # set would otherwise compile every module again in each process that imports it
  "$VENV/bin/pip" install -q --disable-pip-version-check -r "$ROOT/requirements.txt"
  # the Python package tribo (python/tribo), editable: the venv imports the working tree's
  # code; its dependencies are already there, at the pinned versions
  "$VENV/bin/pip" install -q --disable-pip-version-check --no-deps -e "$ROOT"
  echo "$want" > "$VENV/.requirements.sha256"
}
# made while CVODE is fetched and built (pip mostly waits on the network and one core)
venv=""
if [ ! -x "$VENV/bin/python" ] || [ "$(cat "$VENV/.requirements.sha256" 2>/dev/null)" != "$want" ]; then
  make_venv &
  venv=$!
fi

configured() { # configured <dir> <cmake args...>: the build's cache holds every -DNAME=VALUE
  local dir=$1 a kv; shift
  local cache="$ROOT/$dir/CMakeCache.txt"
  [ -f "$ROOT/$dir/build.ninja" ] && [ -f "$cache" ] || return 1
  for a in "$@"; do
    case "$a" in
      -D*=*)
        kv=${a#-D}
        awk -v n="${kv%%=*}" -v v="${kv#*=}" \
          '{ split($0, p, "="); split(p[1], q, ":") }
           q[1] == n && substr($0, index($0, "=") + 1) == v { found = 1 }
           END { exit !found }' "$cache" || return 1 ;;
    esac
  done
}
# CVODE optimised, from Debian's source package of the installed version (scripts/sundials.sh):
# position-independent, since it links into the FMUs' shared libraries
# shellcheck source=sundials.sh
. "$ROOT/scripts/sundials.sh"
sundials_source "$ROOT/build-sundials"
sundials_build "$ROOT/build-sundials/src" "$ROOT/build-sundials/build-native" \
  "$ROOT/build-sundials/native" -DCMAKE_POSITION_INDEPENDENT_CODE=ON
# the builds need the venv: the FMI headers come from its fmpy
if [ -n "$venv" ] && ! wait "$venv"; then
  echo "setup: making the Python venv failed" >&2
  exit 1
fi
build() { # build <dir> <cmake args...>
  local dir=$1; shift
  local args=(-DTRIBO_PYTHON="$VENV/bin/python"
              -DSUNDIALS_DIR="$ROOT/build-sundials/native/lib/cmake/sundials" "$@")
  if ! configured "$dir" "${args[@]}"; then
    cmake -S "$ROOT" -B "$ROOT/$dir" -G Ninja "${args[@]}" >/dev/null
  fi
  cmake --build "$ROOT/$dir"
}
# -Werror: a warning fails the build (CI runs this)
build build -DCMAKE_BUILD_TYPE=Release -DTRIBO_WERROR=ON
if [ "${TRIBO_SETUP_SANITIZE:-0}" = 1 ]; then
  # with the FMUs: the fuzz suite drives them under the sanitizers too
  build build-sanitize -DCMAKE_BUILD_TYPE=Debug -DTRIBO_SANITIZE=ON -DTRIBO_BUILD_FMU=ON -DTRIBO_WERROR=ON
fi
