#!/usr/bin/env bash
# Fetch the LAMMPS source that SaltDEM builds against, through apt's source-package machinery.
#
#   scripts/fetch-lammps.sh [CACHE_DIR]
#
# Writes a private deb-src entry (suite from lammps-source.conf) derived from the machine's own apt
# sources, downloads the orig tarball with `apt-get source --download-only` (a missing .dsc is
# tolerated), verifies its SHA-256 and unpacks it once into CACHE_DIR.  Prints the unpacked tree's
# path on the last line of stdout.  Nothing outside CACHE_DIR is modified.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lammps-source.conf
. "$here/lammps-source.conf"
cache=${1:-${SALTDEM_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/saltdem}}
mkdir -p "$cache"
tree="$cache/$LAMMPS_TREE_NAME-$LAMMPS_DEB_VERSION"
if [ -f "$tree/.saltdem-verified" ]; then echo "$tree"; exit 0; fi

log() { echo "fetch-lammps: $*" >&2; }
die() { echo "fetch-lammps: ERROR: $*" >&2; exit 1; }

tarball="$cache/$LAMMPS_ORIG_TARBALL"
verify() { [ -f "$tarball" ] && echo "$LAMMPS_ORIG_SHA256  $tarball" | sha256sum -c --status; }

if ! verify; then
  command -v apt-get >/dev/null || die "apt-get not found. On a non-Debian machine pass an existing LAMMPS 4Feb2025 checkout: cmake -DLAMMPS_SOURCE_DIR=/path/to/lammps"
  apt="$cache/apt"
  rm -rf "$apt"; mkdir -p "$apt/parts" "$apt/lists/partial" "$apt/cache/archives/partial" "$apt/dl"
  # Derive the mirror from the machine's own apt sources: first http(s) URI that serves Debian main.
  uri=$( { grep -hsE '^\s*URIs:' /etc/apt/sources.list.d/*.sources 2>/dev/null | awk '{print $2}';
           grep -hsE '^\s*deb\s' /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null | awk '{for(i=2;i<=NF;i++) if ($i ~ /^https?:/) {print $i; break}}'; } \
         | grep -E '/debian/?$' | head -n1 || true)
  [ -n "$uri" ] || die "no Debian mirror found in /etc/apt/sources*; pass -DLAMMPS_SOURCE_DIR=/path/to/lammps instead"
  keyring=/usr/share/keyrings/debian-archive-keyring.gpg
  {
    echo "Types: deb-src"; echo "URIs: $uri"; echo "Suites: $LAMMPS_DEB_SUITE"; echo "Components: main"
    [ -f "$keyring" ] && echo "Signed-By: $keyring"
  } > "$apt/parts/saltdem-lammps.sources"
  opts=(-o "Dir::Etc::SourceList=/dev/null" -o "Dir::Etc::SourceParts=$apt/parts"
        -o "Dir::State::Lists=$apt/lists" -o "Dir::Cache=$apt/cache" -o "APT::Sandbox::User=root")
  log "apt-get update (deb-src $LAMMPS_DEB_SUITE from $uri)"
  apt-get "${opts[@]}" -q update >&2 || die "apt-get update of the deb-src entry failed"
  apt-get "${opts[@]}" --print-uris source "$LAMMPS_DEB_PACKAGE=$LAMMPS_DEB_VERSION" 2>/dev/null \
    | grep -F "$LAMMPS_ORIG_TARBALL" >&2 || die "apt does not list $LAMMPS_ORIG_TARBALL for $LAMMPS_DEB_PACKAGE=$LAMMPS_DEB_VERSION"
  log "downloading $LAMMPS_ORIG_TARBALL (about 130 MB)"
  # The .dsc may be gone from the mirror: apt then fails for it but still fetches the tarballs.
  (cd "$apt/dl" && apt-get "${opts[@]}" -q source --download-only "$LAMMPS_DEB_PACKAGE=$LAMMPS_DEB_VERSION" >&2) \
    || log "apt-get source reported an error (a missing .dsc is expected); checking the tarball"
  [ -f "$apt/dl/$LAMMPS_ORIG_TARBALL" ] || die "download of $LAMMPS_ORIG_TARBALL failed"
  mv "$apt/dl/$LAMMPS_ORIG_TARBALL" "$tarball"
  rm -rf "$apt"
  verify || { rm -f "$tarball"; die "SHA-256 mismatch for $LAMMPS_ORIG_TARBALL (expected $LAMMPS_ORIG_SHA256)"; }
fi
log "SHA-256 verified; unpacking"
rm -rf "$tree" "$tree.tmp"; mkdir -p "$tree.tmp"
tar -xJf "$tarball" -C "$tree.tmp" --strip-components=1
touch "$tree.tmp/.saltdem-verified"
mv "$tree.tmp" "$tree"
echo "$tree"
