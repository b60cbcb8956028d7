"""scripts/setup.sh's apt-get (scripts/apt.sh): where another apt-get or dpkg holds the
package lock it waits for it, bounded, saying so in one line (it failed at once, rc 100, on
a machine where another job installs packages). apt-get is a stand-in on PATH here that is
refused the lock a given number of times."""

import os
import subprocess

import pytest

from tribo_fmu import ROOT

LOCKED = ("E: Could not get lock /var/lib/dpkg/lock-frontend. It is held by process 4242 "
          "(apt-get)")


def apt_run(tmp_path, refusals: int, wait: float, error: str = LOCKED):
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    calls = tmp_path / "calls"
    (bin_dir / "apt-get").write_text(
        "#!/bin/sh\n"
        f"echo x >> {calls}\n"
        f"if [ $(wc -l < {calls}) -le {refusals} ]; then echo '{error}' >&2; exit 100; fi\n"
        "echo 'Reading package lists...'\n")
    (bin_dir / "sudo").write_text('#!/bin/sh\nexec "$@"\n')
    for f in bin_dir.iterdir():
        f.chmod(0o755)
    env = dict(os.environ, PATH=f"{bin_dir}:{os.environ['PATH']}", APT_LOCK_WAIT=str(wait),
               APT_LOCK_POLL="0.05", SETUP_LOG=str(tmp_path / "setup.log"))
    done = subprocess.run(["bash", "-c", f". {ROOT}/scripts/apt.sh; apt_run update -qq"],
                          env=env, capture_output=True, text=True, timeout=60)
    return done, len(calls.read_text().splitlines())


def test_a_held_lock_is_waited_for_in_one_line(tmp_path):
    done, calls = apt_run(tmp_path, refusals=3, wait=30)
    assert done.returncode == 0, done.stderr
    assert calls == 4
    assert done.stdout.splitlines() == [
        "setup: another apt-get or dpkg holds the package lock; waiting for it (up to 30 s)"]
    assert done.stderr == ""
    assert "Reading package lists" in (tmp_path / "setup.log").read_text()  # not the terminal


@pytest.mark.parametrize("error, wait", [(LOCKED, 0), ("E: Unable to locate package nope", 30)])
def test_a_lock_held_too_long_or_another_error_fails_saying_apts_error(tmp_path, error, wait):
    done, calls = apt_run(tmp_path, refusals=100, wait=wait, error=error)
    assert done.returncode == 1 and error in done.stderr
    assert calls == 1


def sundials_source(tmp_path, apt_fails: bool):
    """scripts/sundials.sh's sundials_source with stand-ins for dpkg-query, apt-get and
    dpkg-source that warn as Debian's do without a keyring for the sources' signatures."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    scripts = {
        "dpkg-query": "#!/bin/sh\necho 1.0+dfsg-1\n",
        "apt-get": "#!/bin/sh\necho 'gpgv: Signature made; cannot check signature: No public key' >&2\n"
                   + ("echo 'E: Failed to fetch sundials' >&2; exit 100\n" if apt_fails else "")
                   + 'case " $* " in *" source "*) touch sundials_1.0.dsc ;; esac\n',
        "dpkg-source": "#!/bin/sh\necho 'dpkg-source: warning: cannot verify inline signature' >&2\n"
                       'mkdir -p "$3"\n',
    }
    for name, text in scripts.items():
        (bin_dir / name).write_text(text)
        (bin_dir / name).chmod(0o755)
    env = {k: v for k, v in os.environ.items() if k != "SETUP_LOG"}
    env["PATH"] = f"{bin_dir}:{os.environ['PATH']}"
    return subprocess.run(["bash", "-c", f". {ROOT}/scripts/sundials.sh; set -e; "
                                         f"sundials_source {tmp_path}/sundials"],
                          env=env, capture_output=True, text=True, timeout=60)


def test_the_sources_fetch_says_one_line_and_keeps_the_signature_warnings_in_a_log(tmp_path):
    # the first scripts/main.sh printed gpgv's and dpkg-source's warnings (issue 42)
    done = sundials_source(tmp_path, apt_fails=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout == "sundials: fetching the source package sundials 1.0+dfsg-1\n"
    assert done.stderr == ""
    log = (tmp_path / "sundials" / "fetch.log").read_text()
    assert "gpgv: Signature made" in log and "dpkg-source: warning" in log


def test_a_failed_fetch_shows_the_logs_end(tmp_path):
    done = sundials_source(tmp_path, apt_fails=True)
    assert done.returncode != 0
    assert "sundials: fetching the sources failed" in done.stderr
    assert "E: Failed to fetch sundials" in done.stderr
