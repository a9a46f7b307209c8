#!/usr/bin/env bash
# The README's second command: installs what the tests need that cargo does not fetch, then runs
# every test (unit, integration, browser, doc) with the release profile of the README's first
# command, reusing its build (Cargo.toml names the features the test-only dependencies would
# otherwise switch on in shared crates).
#
# Installed when missing, from Debian's archive (sudo when not root):
#   chromium          the browser tests (tests/browser.rs) open the pictures and the HTML report
#   linuxcnc-uspace   its rs274, LinuxCNC's own interpreter, which the conformance test
#                     (tests/linuxcnc.rs) runs side by side with threadcheck; where the package
#                     cannot be installed (a -dev dependency older than the machine's library),
#                     unpacked into target/linuxcnc instead: tests/install-rs274.sh
#   nodejs, npm       run tests/page/page.mjs, which drives `threadcheck serve`'s page in
#                     Chromium through playwright-core (from the npm registry, pinned by
#                     tests/page/package-lock.json; it uses the system Chromium, downloads none)
set -euo pipefail
cd "$(dirname "$0")/.."
sudo_=""
if [ "$(id -u)" != 0 ]; then sudo_="sudo"; fi
# apt-get install, and when the package lists are stale, update them and try again.
install() {
  echo "installing $* (apt-get)" >&2
  $sudo_ apt-get install -y -q "$@" >/dev/null 2>&1 \
    || { $sudo_ apt-get update -q >/dev/null && $sudo_ apt-get install -y -q "$@" >/dev/null; }
}
command -v chromium >/dev/null 2>&1 || install chromium
# About 180 MB and half a minute to three minutes of dpkg: the interpreter alone is needed.
bash tests/install-rs274.sh
command -v npm >/dev/null 2>&1 || install --no-install-recommends nodejs npm
chromium --version
command -v rs274 || ls target/linuxcnc/bin/rs274
node --version
(cd tests/page && npm ci --no-audit --no-fund --loglevel=error)
# --no-fail-fast: a failing test binary does not hide the results of the others (the doc tests
# run last).
cargo test --release --locked --no-fail-fast "$@"
