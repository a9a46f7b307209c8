#!/usr/bin/env bash
# The README's second command: installs what the tests need that cargo does not fetch, then runs
# every test (unit, integration, browser, doc) with the release profile of the README's first
# command, reusing its build (Cargo.toml names the features the test-only dependencies would
# otherwise switch on in shared crates).
#
# Installed when missing, from Debian's archive (sudo when not root):
#   chromium   the browser tests (tests/browser.rs) open the pictures and the HTML report in it
set -euo pipefail
cd "$(dirname "$0")/.."
need=()
command -v chromium >/dev/null 2>&1 || need+=(chromium)
if [ ${#need[@]} -gt 0 ]; then
  echo "installing ${need[*]} (apt-get)" >&2
  sudo_=""
  if [ "$(id -u)" != 0 ]; then sudo_="sudo"; fi
  $sudo_ apt-get install -y -q "${need[@]}" >/dev/null 2>&1 \
    || { $sudo_ apt-get update -q >/dev/null && $sudo_ apt-get install -y -q "${need[@]}" >/dev/null; }
fi
chromium --version
# --no-fail-fast: a failing test binary does not hide the results of the others (the doc tests
# run last).
cargo test --release --locked --no-fail-fast "$@"
