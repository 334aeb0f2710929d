# scripts/lib/deps.sh — sourced by the set-up scripts: installs missing Debian packages.
#
# ensure_packages PKG...   installs those of PKG... that are not installed (apt-get, with
#                          sudo when not root); quiet and quick when all are present.
# RT2_BUILD_PACKAGES       everything the build and the tests need.

RT2_BUILD_PACKAGES="scons g++ pkg-config libgtest-dev libgmock-dev libtbb-dev \
libtinyobjloader-dev libopenimageio-dev openimageio-tools libcli11-dev libtomlplusplus-dev \
nlohmann-json3-dev libtinygltf-dev libdraco-dev libmeshoptimizer-dev assimp-testmodels jq libsdl2-dev libimgui-dev xvfb xauth \
libopenmpi-dev openmpi-bin"

ensure_packages() {
  local missing=() pkg
  for pkg in "$@"; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' \
      || missing+=("$pkg")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "rt2: need root or sudo to install: ${missing[*]}" >&2; return 1; }
    sudo=(sudo)
  fi
  echo "rt2: installing Debian packages: ${missing[*]}" >&2
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 -qq update >&2 \
    && "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 \
         install -y -qq --no-install-recommends "${missing[@]}" >&2
}
