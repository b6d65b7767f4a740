# Debian 12 packages tetrender builds and tests with; sourced by test.sh and demo.sh.
# ensure_packages: installs the missing ones (as root), or prints the apt-get line and fails.

TETRENDER_PACKAGES=(
  cmake make g++ pkg-config clang-format
  libvtk9-dev libcgal-dev libtet1.5-dev libtbb-dev libglm-dev libpng-dev zlib1g-dev
  liblz4-dev liblzma-dev
  nlohmann-json3-dev libcli11-dev libfreetype-dev fonts-dejavu-core
  libglfw3-dev libimgui-dev libepoxy-dev libgl1-mesa-dri xvfb xauth
  libgtest-dev libgmock-dev libbenchmark-dev ffmpeg
  pybind11-dev python3-dev python3-numpy python3-pytest python3-meshio
)

# What the MPI build and its tests add (scripts/test.sh; demo.sh stays lean): OpenMPI, and IceT
# as Debian ships it, inside ParaView (never python3-paraview: it conflicts with python3-vtk9,
# and apt would remove libvtk9-dev). README, "On a cluster".
TETRENDER_MPI_PACKAGES=(libopenmpi-dev openmpi-bin paraview-dev)

ensure_packages() {
  local missing=() pkg
  for pkg in "${TETRENDER_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$pkg")
    fi
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  if [ "$(id -u)" -ne 0 ]; then
    echo "tetrender needs these Debian packages; as root, run:" >&2
    echo "  apt-get update && apt-get install -y --no-install-recommends ${missing[*]}" >&2
    return 1
  fi
  echo "installing: ${missing[*]}" >&2
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}
