#!/usr/bin/env bash
# Installs whatever QuakeView needs that this machine lacks, and nothing else. Idempotent: a second
# run on a complete machine does no network access and takes about a second.
#
# - Debian packages (apt, as root or through sudo);
# - Dear ImGui 1.86 sources from Debian's source package (and simdjson's single-header sources and
#   GeographicLib's and Zstandard's, used by the WebAssembly build), unpacked under .deps/ (git-ignored, never
#   committed);
# - test data: OpenStreetMap's Liechtenstein extract of 2013 (ODbL, (c) OpenStreetMap contributors),
#   one file of Debian's osm2pgsql source package, in .deps/osm-data/ (the ground tests read it);
# - npm packages pinned by tests/e2e/package-lock.json (playwright-core for Chromium, puppeteer-core
#   for Firefox ESR; never a browser download).
#
# On a system without apt it stops and lists what to install.
set -Eeuo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
deps="$root/.deps"

log() { printf '[setup] %s\n' "$*"; }
die() { printf '[setup] error: %s\n' "$*" >&2; exit 1; }
# Any other failure (set -e) names the command, its status and the line, instead of ending quietly.
on_error() {
  printf '[setup] error: "%s" failed with status %s (scripts/setup.sh line %s)\n' "$3" "$1" "$2" >&2
}
trap 'on_error $? $LINENO "$BASH_COMMAND"' ERR

# shellcheck source=SCRIPTDIR/lib/apt-sources.sh
source "$root/scripts/lib/apt-sources.sh"

# Build tools, libraries (native tools and tests), the WebAssembly toolchain, the two browsers for
# the end-to-end tests, and the fuzzing runtime. Headless Firefox draws WebGL2 only on Mesa's
# llvmpipe through EGL (libgl1-mesa-dri, libegl1, libegl-mesa0; ../shared/TOOLCHAIN.md).
packages=(
  build-essential cmake ninja-build pkg-config git ca-certificates dpkg-dev clang-format
  emscripten clang-14 libclang-rt-14-dev
  libglm-dev libgeographiclib-dev libsimdjson-dev catch2
  libosmium2-dev libprotozero-dev libexpat1-dev libbz2-dev zlib1g-dev liblz4-dev libzstd-dev
  libproj-dev libcgal-dev libgmp-dev libmpfr-dev libmeshoptimizer-dev libtinyobjloader-dev libeigen3-dev
  libmimalloc-dev
  osmium-tool zstd poppler-utils
  chromium fonts-dejavu-core
  firefox-esr libgl1-mesa-dri libegl1 libegl-mesa0
  slurm-wlm munge
)

if ! command -v apt-get >/dev/null 2>&1 || ! command -v dpkg-query >/dev/null 2>&1; then
  cat >&2 <<MSG
[setup] error: this set-up step needs Debian's apt (Debian 12 "bookworm").
Install these by hand (names are Debian's; other systems have equivalents):
  ${packages[*]}
plus Node.js >= 18 with npm, Dear ImGui 1.86 sources in $deps/imgui,
simdjson 3.0.1 sources in $deps/simdjson, GeographicLib 2.1.2 sources in $deps/geographiclib,
Zstandard 1.5.4 sources in $deps/zstd, osm2pgsql 1.8.0's tests/data/liechtenstein-2013-08-03.osm.pbf
in $deps/osm-data/, then run:
  (cd $root/tests/e2e && npm ci)
MSG
  exit 1
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || die "not root and no sudo: run as root, or install sudo"
  sudo_cmd=(sudo)
fi

is_installed() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'
}

missing=()
for p in "${packages[@]}"; do
  is_installed "$p" || missing+=("$p")
done
# npm: this machine kind has NodeSource's node with its own npm (Debian's npm conflicts with it); a
# bare Debian 12 gets Debian's node 18 with emscripten and needs Debian's npm.
if ! command -v npm >/dev/null 2>&1; then
  missing+=(npm)
fi

apt_updated=0
apt_update() {
  if [ "$apt_updated" -eq 0 ]; then
    log "apt-get update"
    "${sudo_cmd[@]}" apt-get update -qq
    apt_updated=1
  fi
}

if [ "${#missing[@]}" -gt 0 ]; then
  log "installing Debian packages: ${missing[*]}"
  apt_update
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}"
fi

# Source packages need a deb-src entry for bookworm main. It must repeat the URI and Signed-By of
# the existing binary entry, or apt rejects the pair as conflicting. Both source formats (one-line
# sources.list, deb822 .sources) are read by scripts/lib/apt-sources.sh.
ensure_deb_src() {
  if qv_apt_has_deb_src /etc/apt; then
    return
  fi
  log "adding a deb-src entry for bookworm main"
  local plan file
  plan=$(qv_apt_plan_deb_src /etc/apt 2>&1) || die "cannot add a deb-src entry: $plan"
  file=${plan%%$'\n'*}
  log "writing $file"
  printf '%s\n' "${plan#*$'\n'}" | "${sudo_cmd[@]}" tee "$file" >/dev/null
  apt_updated=0
}

# Unpacks Debian source package $1 into $deps/$2 (once).
fetch_source() {
  local pkg=$1 dest=$deps/$2 marker=$3
  if [ -f "$dest/$marker" ]; then return; fi
  ensure_deb_src
  apt_update
  local tmp
  tmp=$(mktemp -d)
  chmod 777 "$tmp"  # apt downloads as user _apt
  log "fetching Debian source package $pkg"
  (cd "$tmp" && apt-get source -qq --download-only "$pkg" >/dev/null &&
    dpkg-source --no-check -x ./*.dsc src >/dev/null)
  mkdir -p "$deps"
  rm -rf "$dest"
  mv "$tmp/src" "$dest"
  rm -rf "$tmp"
  [ -f "$dest/$marker" ] || die "source package $pkg has no $marker"
}

fetch_source imgui imgui imgui.cpp
fetch_source simdjson simdjson singleheader/simdjson.cpp
fetch_source geographiclib geographiclib src/TransverseMercator.cpp
fetch_source libzstd zstd lib/zstd.h

# Takes file $2 (a path inside the upstream tarball, below its top folder) out of Debian source
# package $1 into $deps/$3 (once), checking its SHA-256 $4; the rest of the package is not kept.
fetch_source_file() {
  local pkg=$1 member=$2 dest=$deps/$3 sha=$4
  if [ -f "$dest" ] && [ "$(sha256sum "$dest" | cut -d' ' -f1)" = "$sha" ]; then return; fi
  ensure_deb_src
  apt_update
  local tmp
  tmp=$(mktemp -d)
  chmod 777 "$tmp"  # apt downloads as user _apt
  log "fetching $(basename "$member") from Debian source package $pkg"
  (cd "$tmp" && apt-get source -qq --download-only "$pkg" >/dev/null)
  local orig
  orig=$(find "$tmp" -maxdepth 1 -name "${pkg}_*.orig.tar.*" | head -n 1)
  [ -n "$orig" ] || die "source package $pkg has no upstream tarball"
  tar -xf "$orig" -C "$tmp" --wildcards --no-anchored "*/$member" ||
    die "source package $pkg has no $member"
  local got
  got=$(find "$tmp" -path "*/$member" -type f | head -n 1)
  [ -n "$got" ] || die "source package $pkg has no $member"
  [ "$(sha256sum "$got" | cut -d' ' -f1)" = "$sha" ] ||
    die "$member of source package $pkg is not the expected file (SHA-256 differs from $sha)"
  mkdir -p "$(dirname "$dest")"
  mv "$got" "$dest"
  rm -rf "$tmp"
}

# OpenStreetMap's Liechtenstein (2013-08-03; streets, the Rhine, lakes, forests, place names), which
# tests/ingest reads for the ground features; the build passes its path to the tests.
fetch_source_file osm2pgsql tests/data/liechtenstein-2013-08-03.osm.pbf osm-data/liechtenstein-2013-08-03.osm.pbf \
  edb2b075be057662691fc343abed4ed58f139dd7c501c243197640fcb3ea82d4

# npm packages, pinned by the lockfile. A stamp of the lockfile's hash makes the re-run free.
e2e="$root/tests/e2e"
stamp="$e2e/node_modules/.quakeview-lock.sha256"
want=$(sha256sum "$e2e/package-lock.json" | cut -d' ' -f1)
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  log "installing npm packages (tests/e2e)"
  (cd "$e2e" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 PUPPETEER_SKIP_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error)
  echo "$want" >"$stamp"
fi

# Which browsers the end-to-end tests will run in: the versions depend on the APT sources (bookworm
# main alone gives an older Firefox ESR than bookworm-security), and the README lists the tested ones.
pkg_version() { dpkg-query -W -f='${Version}' "$1" 2>/dev/null || echo "not installed"; }
log "browsers for the end-to-end tests: Chromium $(pkg_version chromium), Firefox ESR $(pkg_version firefox-esr)"
log "ok"
