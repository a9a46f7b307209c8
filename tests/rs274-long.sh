#!/usr/bin/env bash
# The long local run of the LinuxCNC conformance test (issue 26): 10 000 generated programs from
# seeds no CI run uses, each run by LinuxCNC's rs274 and read by threadcheck, pass for pass.
# Needs rs274 (Debian's linuxcnc-uspace; tests/install-and-test.sh installs it).
set -euo pipefail
cd "$(dirname "$0")/.."
THREADCHECK_RS274_SEED="${THREADCHECK_RS274_SEED:-1000000}" \
THREADCHECK_RS274_PROGRAMS="${THREADCHECK_RS274_PROGRAMS:-10000}" \
  cargo test --release --locked --test integration linuxcnc::generated -- --nocapture "$@"
