#!/usr/bin/env bash
# Sourced by setup.sh: apt-get that waits for the package lock where another
# apt-get or dpkg holds it (a machine where another job installs packages), saying so in
# one line, up to APT_LOCK_WAIT seconds (default 600), checking every APT_LOCK_POLL (5);
# apt-get's own output goes to SETUP_LOG (default: nowhere), its errors to stderr.
#   apt_run ARGS...   apt-get ARGS (as root, or through sudo)

apt_run() {
  local wait=${APT_LOCK_WAIT:-600} poll=${APT_LOCK_POLL:-5} log=${SETUP_LOG:-/dev/null}
  local sudo="" said="" err start=$SECONDS
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  while :; do
    if err=$($sudo apt-get "$@" 2>&1 >>"$log"); then
      return 0
    fi
    # apt-get update's lists lock and install's dpkg lock are refused at once ("Could not
    # get lock ... It is held by process N (apt-get)"): wait, then try again
    if grep -q "Could not get lock\|Unable to lock\|Unable to acquire the dpkg" <<<"$err" \
        && ((SECONDS - start < wait)); then
      if [ -z "$said" ]; then
        echo "setup: another apt-get or dpkg holds the package lock; waiting for it (up to ${wait} s)"
        said=1
      fi
      sleep "$poll"
      continue
    fi
    printf '%s\n' "$err" >&2
    return 1
  done
}
