#!/usr/bin/env bash
# Compares the LinuxCNC programs given as arguments with LinuxCNC's rs274, pass for pass (for
# programs that are not the project's, such as a corpus of other people's programs):
#   tests/rs274-files.sh ../shared/corpus/*.ngc
# A subroutine file and a caller joined by '+' are run as one program: the subroutine file
# first, without the lines that end a program there (M2, M30, %), then the caller:
#   tests/rs274-files.sh SUB.ngc+tests/data/rs274/threading-caller.ngc
set -euo pipefail
cd "$(dirname "$0")/.."
files=""
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for f in "$@"; do
  if [[ "$f" == *+* ]]; then
    joined="$tmp/$(basename "${f%%+*}" .ngc)-with-$(basename "${f#*+}")"
    { grep -viE '^[[:space:]]*(m0*2|m30|%)[[:space:]]*$' "${f%%+*}" || true; cat "${f#*+}"; } > "$joined"
    files="$files:$joined"
  else
    files="$files:$(realpath "$f")"
  fi
done
THREADCHECK_RS274_FILES="$files" \
  cargo test --release --locked --test integration linuxcnc::named_files -- --ignored --nocapture
