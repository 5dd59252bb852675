# shellcheck shell=bash
# Sourced by the scripts: what they install beyond Rust and Python, in one place. The system
# packages, in one list, with `system_install`, which installs with apt-get (Debian, as root)
# those that are missing; and cargo-c, with `cargo_c_install`.
#
#   source scripts/system.sh
#   system_install cmake pkg-config   # these entries of the list, where missing
#   system_install                    # every entry (scripts/test.sh, before its first step)
#   cargo_c_install                   # cargo-c, if cargo-cinstall is missing
#
# A package already installed costs one dpkg-query; apt-get runs only for missing ones (one
# `apt-get update` and one `apt-get install` per call). Where the user is not root, the missing
# packages are named and the script stops; on a system without dpkg nothing is checked.

# Debian package    why (which script needs it)
system_packages='
gcc                 the C examples and tests (cc; strip and readelf come with it), crates that compile C
pkg-config          c_package.sh builds the C example with pkg-config; cargo-c finds OpenSSL with it
libssl-dev          the cargo-c install (c_package.sh): cargo, which cargo-c is built on, links OpenSSL
cmake               c_package.sh builds the C example with find_package(leuven_rt)
clang               fuzz_c.sh compiles the libFuzzer harness with AddressSanitizer and UBSan
libclang-rt-dev     fuzz_c.sh: libFuzzer and the sanitizer runtimes for the default clang
python3-venv        wheel_smoke.sh makes a virtualenv with every CPython >= 3.10 here, /usr/bin/python3 too
'

# Installs the named packages of the list (all of them without arguments) that are missing.
system_install() {
    local known wanted=() missing=() package
    known="$(awk 'NF { print $1 }' <<<"$system_packages")"
    if ! command -v dpkg-query >/dev/null; then
        # Not Debian: the names may differ; the commands that need them say what is missing.
        return 0
    fi
    if [ "$#" -eq 0 ]; then
        mapfile -t wanted <<<"$known"
    else
        wanted=("$@")
    fi
    for package in "${wanted[@]}"; do
        if ! grep -qx -- "$package" <<<"$known"; then
            echo "system.sh: $package is not in the list of scripts/system.sh" >&2
            return 2
        fi
        dpkg-query -W -f '${db:Status-Abbrev}' "$package" 2>/dev/null | grep -q '^ii' \
            || missing+=("$package")
    done
    [ "${#missing[@]}" -eq 0 ] && return 0
    if [ "$(id -u)" -ne 0 ]; then
        echo "system.sh: missing ${missing[*]}; install them (Debian, as root: apt-get install ${missing[*]})" >&2
        return 1
    fi
    echo "==> apt-get install ${missing[*]}"
    local start=$SECONDS
    DEBIAN_FRONTEND=noninteractive apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
    echo "    installed in $((SECONDS - start)) s"
}

# cargo-c (`cargo cinstall`, scripts/c_package.sh), pinned to the last release that builds with
# the stable Rust of CI, compiled from crates.io with its locked dependencies once per machine:
# 12 CPU-minutes (user + sys), so about 6 min on 2 free cores; 48 min of wall time measured at
# a load average of 12 on 2 cores. Needs gcc, pkg-config and libssl-dev from the list above.
cargo_c_version=0.10.24
cargo_c_install() {
    command -v cargo-cinstall >/dev/null && return 0
    echo "==> cargo install cargo-c $cargo_c_version (once per machine: 12 CPU-minutes, 6 min on 2 free cores)"
    local start=$SECONDS
    cargo install --quiet --locked cargo-c --version "$cargo_c_version"
    echo "    installed in $((SECONDS - start)) s"
}
