# Shared by scripts/run, scripts/test and scripts/bench: installs what is missing on a
# Debian machine (apt-get; sudo when not root) and builds with meson.
set -euo pipefail

CT_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
CT_PACKAGES=(gcc binutils meson ninja-build pkg-config libcmocka-dev libinih-dev libgsl-dev gnuplot-nox
    locales librandom123-dev libopenmpi-dev openmpi-bin libzip-dev libxml2-dev
    python3 python3-numpy python3-cffi python3-pytest python3-matplotlib python3-scipy
    python3-mesonpy python3-venv python3-pip)
# what scripts/test needs besides: the formatter its format check runs
CT_TEST_PACKAGES=(clang-format)

ct_need_packages() {
    local missing=() p
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
            missing+=("$p")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    local sudo=""
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null || {
            echo "scripts: need root or sudo to install: ${missing[*]}" >&2
            exit 1
        }
        sudo=sudo
    fi
    echo "scripts: installing ${missing[*]}" >&2
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
        "${missing[@]}" >/dev/null
}

# ct_build DIR [meson options...]: configure once (an existing build directory gets the
# options given, e.g. -Dtests=true after a setup without tests), then build.
ct_build() {
    local dir=$1
    shift
    if [ ! -f "$CT_ROOT/$dir/build.ninja" ]; then
        meson setup "$CT_ROOT/$dir" "$CT_ROOT" "$@" >/dev/null
    elif [ $# -gt 0 ]; then
        meson configure "$CT_ROOT/$dir" "$@" >/dev/null
    fi
    ninja -C "$CT_ROOT/$dir" >/dev/null
}
