#!/usr/bin/env bash
# Installs the missing Debian packages named on the command line (as root), or prints the command.
#
# Fast when nothing is missing: one dpkg-query, no apt-get. As root with something missing:
# `apt-get update` once, then `apt-get install -y --no-install-recommends <missing>`.
# Not root with something missing: prints the exact command and exits 1.
# DLAB_SKIP_DEPS=1 skips the check (for machines that are not Debian, or managed by hand).
set -euo pipefail

if [[ ${DLAB_SKIP_DEPS:-0} == 1 ]]; then
    echo "deps: DLAB_SKIP_DEPS=1, not checking Debian packages"
    exit 0
fi
if (($# == 0)); then
    echo "usage: $0 PACKAGE..." >&2
    exit 2
fi
if ! command -v dpkg-query >/dev/null 2>&1; then
    echo "deps: dpkg-query not found: this is not a Debian system." >&2
    echo "deps: install the equivalents of: $*" >&2
    echo "deps: then run again with DLAB_SKIP_DEPS=1" >&2
    exit 1
fi

# Packages whose status is "install ok installed" (Status-Abbrev "ii"); a package dpkg has never
# heard of prints nothing, so anything not listed here is missing.
installed_list() {
    dpkg-query -W -f='${Package} ${db:Status-Abbrev}\n' "$@" 2>/dev/null |
        awk '$2 == "ii" { print $1 }' || true
}
missing_of() {
    local installed
    installed=" $(installed_list "$@" | tr '\n' ' ') "
    local pkg
    for pkg in "$@"; do
        [[ $installed == *" $pkg "* ]] || printf '%s\n' "$pkg"
    done
}

mapfile -t missing < <(missing_of "$@")
if ((${#missing[@]} == 0)); then
    echo "deps: all ${#} Debian packages are installed"
    exit 0
fi

if [[ $(id -u) -ne 0 ]]; then
    echo "deps: missing Debian packages: ${missing[*]}" >&2
    echo "deps: install them (as root), then run make again:" >&2
    echo "  sudo apt-get update && sudo apt-get install -y --no-install-recommends ${missing[*]}" >&2
    exit 1
fi

echo "deps: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends "${missing[@]}"

mapfile -t still < <(missing_of "$@")
if ((${#still[@]} != 0)); then
    echo "deps: still missing after apt-get install: ${still[*]}" >&2
    exit 1
fi
echo "deps: all ${#} Debian packages are installed"
