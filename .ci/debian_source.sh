#!/usr/bin/env bash
# Unpacks the upstream sources of a Debian source package (the version of an installed binary
# package) into DEST/SOURCE-<version>/ and prints that folder. The WebAssembly build compiles
# Dear ImGui (source `imgui`, as libimgui-dev) and giflib (source `giflib`, as libgif-dev) with
# em++ from them. Leaves the system's apt configuration alone: a deb-src list and package lists
# of its own under DEST/apt. Fast (no network) when the folder is already there.
#   usage: debian_source.sh DEST SOURCE BINARY      e.g. debian_source.sh build-web/_deps imgui libimgui-dev
set -euo pipefail
dest=${1:?usage: $0 DEST SOURCE BINARY}
source_pkg=${2:?usage: $0 DEST SOURCE BINARY}
binary_pkg=${3:?usage: $0 DEST SOURCE BINARY}
mkdir -p "$dest"
dest=$(cd "$dest" && pwd)
version=$(dpkg-query -W -f='${Version}' "$binary_pkg" 2>/dev/null || true)
if [[ -z $version ]]; then
    echo "debian_source: $binary_pkg is not installed (apt-get install $binary_pkg)" >&2
    exit 1
fi
version=${version%+b[0-9]*}  # a binary-only rebuild (+bN) has the source of the version before
upstream=${version#*:}
upstream=${upstream%-*}
folder=$dest/$source_pkg-$upstream
stamp=$folder/.unpacked
if [[ -f $stamp ]]; then
    echo "$folder"
    exit 0
fi
apt_dir=$dest/apt
mkdir -p "$apt_dir/lists/partial"
echo "deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg]" \
    "http://deb.debian.org/debian bookworm main" >"$apt_dir/sources.list"
opts=(-o "Dir::Etc::SourceList=$apt_dir/sources.list" -o Dir::Etc::SourceParts=/dev/null
      -o "Dir::State::Lists=$apt_dir/lists" -o Debug::NoLocking=1)
if ! ls "$dest/${source_pkg}_${version#*:}".dsc >/dev/null 2>&1; then
    apt-get "${opts[@]}" -qq update >&2
    (cd "$dest" && apt-get "${opts[@]}" -qq source --download-only "$source_pkg=$version" 2>&1 |
        grep -v 'Download is performed unsandboxed' >&2 || true)
fi
dsc=$(ls "$dest/${source_pkg}_${version#*:}".dsc 2>/dev/null | head -n 1 || true)
if [[ -z $dsc ]]; then
    echo "debian_source: could not download the source of $source_pkg $version" \
        "(needs http://deb.debian.org)" >&2
    exit 1
fi
# Debian's patches applied, as the binary package was built (giflib declares more in gif_lib.h).
rm -rf "$folder"
dpkg-source --no-check -x "$dsc" "$folder" >&2
touch "$stamp"
echo "$folder"
