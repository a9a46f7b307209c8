#!/usr/bin/env bash
# Installs LinuxCNC's standalone interpreter, rs274, which the conformance test (tests/linuxcnc.rs)
# runs side by side with threadcheck. Two paths, the one taken said on stderr:
#
#   1. apt-get install --no-install-recommends linuxcnc-uspace (rs274 then on the PATH).
#   2. When that fails (on a Debian 12 machine whose installed libraries are newer than the
#      archive's, linuxcnc-uspace's -dev dependencies cannot be installed: "libpcre2-dev : Depends:
#      libpcre2-8-0 (= 10.42-1) but 10.42-1+deb12u1 is to be installed"), the package is fetched
#      with `apt-get download`, unpacked with `dpkg-deb -x` into DIR (default target/linuxcnc),
#      only the runtime libraries rs274 links against are installed (none downgraded: apt-get is
#      never told a version), and DIR/bin/rs274 runs the unpacked interpreter with the unpacked
#      libraries. The conformance test finds rs274 on the PATH or there.
#
#   tests/install-rs274.sh [--ignore-path] [DIR]
#
# --ignore-path installs even when an rs274 is on the PATH: .ci/run runs it with
# tests/data/failing-apt/apt-get first on the PATH, which fails `apt-get install linuxcnc-uspace`
# as the archive does, to exercise path 2 on any machine.
set -euo pipefail
cd "$(dirname "$0")/.."
ignore_path=0
if [ "${1:-}" = "--ignore-path" ]; then ignore_path=1; shift; fi
dir="${1:-target/linuxcnc}"
mkdir -p "$(dirname "$dir")"
dir="$(cd "$(dirname "$dir")" && pwd)/$(basename "$dir")"
sudo_=""
if [ "$(id -u)" != 0 ]; then sudo_="sudo"; fi
# The shared libraries rs274 needs beyond what linuxcnc-uspace itself ships (checked below with
# ldd: a missing one fails this script naming it).
runtime_libs=(libboost-python1.74.0 libpython3.11 libedit2 libtirpc3)

# rs274 as the conformance test will run it: prints a canonical traverse for a one-line program.
works() {
  local exe="$1" probe
  probe="$(mktemp -d)"
  printf 'G21 G90 G0 X1 Z2\nM2\n' > "$probe/p.ngc"
  printf 'T1 P1 D0 ;\n' > "$probe/tool.tbl"
  if (cd "$probe" && HOME="$probe" "$exe" -t tool.tbl -g p.ngc </dev/null 2>&1) | grep -q STRAIGHT_TRAVERSE; then
    rm -rf "$probe"; return 0
  fi
  rm -rf "$probe"; return 1
}

if [ "$ignore_path" = 0 ] && command -v rs274 >/dev/null 2>&1; then
  echo "rs274: on the PATH ($(command -v rs274))" >&2
  exit 0
fi
if [ -x "$dir/bin/rs274" ] && works "$dir/bin/rs274"; then
  echo "rs274: unpacked earlier in $dir" >&2
  exit 0
fi
echo "rs274: installing linuxcnc-uspace (apt-get)" >&2
log="$(mktemp)"
if $sudo_ apt-get install -y -q --no-install-recommends linuxcnc-uspace >"$log" 2>&1 \
  || { $sudo_ apt-get update -q >>"$log" 2>&1 \
       && $sudo_ apt-get install -y -q --no-install-recommends linuxcnc-uspace >>"$log" 2>&1; }; then
  rm -f "$log"
  echo "rs274: installed with linuxcnc-uspace ($(command -v rs274))" >&2
  exit 0
fi
echo "rs274: apt-get install linuxcnc-uspace failed:" >&2
grep -E 'Depends|E:' "$log" | head -5 | sed 's/^/  /' >&2 || true
rm -f "$log"

echo "rs274: unpacking linuxcnc-uspace into $dir (apt-get download, dpkg-deb -x)" >&2
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# apt-get download writes into the current folder; as root it warns that the download is not
# sandboxed (the _apt user cannot write a mktemp folder): that is expected.
(cd "$work" && $sudo_ apt-get download -q linuxcnc-uspace >/dev/null 2>&1) \
  || { $sudo_ apt-get update -q >/dev/null && (cd "$work" && $sudo_ apt-get download -q linuxcnc-uspace >/dev/null 2>&1); }
deb="$(ls "$work"/linuxcnc-uspace_*.deb)"
rm -rf "$dir"
mkdir -p "$dir/bin"
dpkg-deb -x "$deb" "$dir/root"
echo "rs274: installing its runtime libraries: ${runtime_libs[*]} (apt-get, no version named)" >&2
$sudo_ apt-get install -y -q --no-install-recommends "${runtime_libs[@]}" >/dev/null
cat > "$dir/bin/rs274" <<EOF
#!/bin/sh
# LinuxCNC's rs274 unpacked from $(basename "$deb") by tests/install-rs274.sh
LD_LIBRARY_PATH="$dir/root/usr/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}" exec "$dir/root/usr/bin/rs274" "\$@"
EOF
chmod +x "$dir/bin/rs274"
missing="$(LD_LIBRARY_PATH="$dir/root/usr/lib" ldd "$dir/root/usr/bin/rs274" | grep 'not found' || true)"
if [ -n "$missing" ]; then
  echo "rs274: unpacked, but these libraries are missing:" >&2
  echo "$missing" >&2
  exit 1
fi
works "$dir/bin/rs274" || { echo "rs274: unpacked in $dir but does not run a program" >&2; exit 1; }
echo "rs274: unpacked, runs as $dir/bin/rs274" >&2
