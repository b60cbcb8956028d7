#!/usr/bin/env bash
# Set-up shared by the README's commands, safe to re-run: installs what is missing
# (Debian packages, the Python venv when requirements.txt changed) and builds.
# Nothing is reinstalled when nothing changed.
set -eEuo pipefail  # -E: the ERR trap below in functions too
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# what the installs and builds print goes to this log, progress lines to the terminal; a
# failure shows the log's end
mkdir -p "$ROOT/build"
export SETUP_LOG="$ROOT/build/setup.log"
: > "$SETUP_LOG"
failed() {
  echo "setup: failed; the end of $SETUP_LOG:" >&2
  tail -n 30 "$SETUP_LOG" >&2
}
trap 'failed' ERR
# shellcheck source=apt.sh
. "$ROOT/scripts/apt.sh"

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
  echo "setup: installing ${missing[*]} (log: build/setup.log)"
  apt_run update -qq
  DEBIAN_FRONTEND=noninteractive apt_run install -y -qq "${missing[@]}"
fi

# Debian's python3 (not whatever python3 is first on PATH), so that a fresh Debian 12
# machine and this one get the same interpreter.
PYTHON=/usr/bin/python3
VENV="$ROOT/.venv"
# the venv is made again when the pinned requirements or the package's metadata change
want=$(cat "$ROOT/requirements.txt" "$ROOT/pyproject.toml" | sha256sum | cut -d' ' -f1)
pip_install() {
  "$VENV/bin/pip" install -q --disable-pip-version-check "$@"
}
# The venv in two parts, each beside other work (pip mostly waits on the network and one
# core): first what the builds need, while CVODE is fetched and built (fmpy, whose FMI
# headers the FMUs compile against; Markdown, which renders their documentation), then the
# rest while the C code is built. Byte-compiled at install (pip's default): with
# PYTHONDONTWRITEBYTECODE set, every process would otherwise compile the modules it imports.
venv_for_builds=""
venv_rest=""
if [ ! -x "$VENV/bin/python" ] || [ "$(cat "$VENV/.requirements.sha256" 2>/dev/null)" != "$want" ]; then
  echo "setup: creating the Python venv in .venv"
  rm -rf "$VENV"
  "$PYTHON" -m venv "$VENV"
  pip_install -c "$ROOT/requirements.txt" FMPy Markdown &
  venv_for_builds=$!
fi
venv_waited() { # venv_waited <pid> <what>: waits for a part of the venv; its failure ends set-up
  if [ -n "$1" ] && ! wait "$1"; then
    echo "setup: installing $2 into the Python venv failed" >&2
    exit 1
  fi
}
rest_of_venv() {
  pip_install -r "$ROOT/requirements.txt"
  # the Python package tribo (python/tribo), editable: the venv imports the working tree's
  # code; its dependencies are already there, at the pinned versions
  pip_install --no-deps -e "$ROOT"
  echo "$want" > "$VENV/.requirements.sha256"
}

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
venv_waited "$venv_for_builds" "fmpy and Markdown"
if [ -n "$venv_for_builds" ]; then
  rest_of_venv &
  venv_rest=$!
fi
build() { # build <dir> <cmake args...>
  local dir=$1; shift
  local args=(-DTRIBO_PYTHON="$VENV/bin/python"
              -DSUNDIALS_DIR="$ROOT/build-sundials/native/lib/cmake/sundials" "$@")
  if ! configured "$dir" "${args[@]}"; then
    cmake -S "$ROOT" -B "$ROOT/$dir" -G Ninja "${args[@]}" >>"$SETUP_LOG" 2>&1
  fi
  # ninja's lines (one per file) into the log, a line here
  echo "setup: building $dir (log: build/setup.log)"
  cmake --build "$ROOT/$dir" >>"$SETUP_LOG" 2>&1
}
# -Werror: a warning fails the build (CI runs this)
build build -DCMAKE_BUILD_TYPE=Release -DTRIBO_WERROR=ON
if [ "${TRIBO_SETUP_SANITIZE:-0}" = 1 ]; then
  # with the FMUs: the fuzz suite drives them under the sanitizers too
  build build-sanitize -DCMAKE_BUILD_TYPE=Debug -DTRIBO_SANITIZE=ON -DTRIBO_BUILD_FMU=ON -DTRIBO_WERROR=ON
fi
venv_waited "$venv_rest" "the pinned requirements and the package"
trap - ERR
