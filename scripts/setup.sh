#!/usr/bin/env bash
# Sets up a Debian 12 machine and runs the main job on the bundled example:
#   1. installs the Debian packages the build needs (skipped when all are installed),
#   2. configures (with CUDA when /usr/local/cuda/bin/nvcc exists, with ParaView) and
#      builds into build/,
#   3. runs `gdr selfcheck`, meshes apps/gdr/examples/gear.poly into out/example.vtu with
#      --check, and, when the ParaView plugin was built and xvfb-run is present, meshes it
#      again through the plugin and renders out/example.png, then meshes the bundled closed
#      surface Testing/Filters/Data/hollow_sphere.vtp into tetrahedra through the plugin:
#      out/example3d.vtu and out/example3d.png.
# Options: --build-only (stop after step 2).
# Environment: GDR_BUILD_DIR (default build), GDR_JOBS (default: nproc),
#              GDR_CMAKE_ARGS (extra CMake arguments, e.g. "-DGDR_BUILD_BENCHMARKS=OFF").
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BUILD_DIR="${GDR_BUILD_DIR:-build}"
JOBS="${GDR_JOBS:-$(nproc)}"
BUILD_ONLY=0
for arg in "$@"; do
  case "$arg" in
    --build-only) BUILD_ONLY=1 ;;
    -h|--help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "setup.sh: unknown argument '$arg' (try --help)" >&2; exit 2 ;;
  esac
done

step() { printf '\n== %s\n' "$*"; }

# --- 1. Debian packages --------------------------------------------------------
PACKAGES=(
  cmake ninja-build g++ libgtest-dev libgmp-dev
  paraview-dev python3-paraview mpi-default-dev libdouble-conversion-dev
  libcgal-dev libtet1.5-dev tetgen libtbb-dev xvfb xauth qtbase5-dev libglew-dev
  libnetcdf-dev libhdf5-dev libqt5opengl5-dev xdotool imagemagick
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  step "Installing ${#missing[@]} Debian packages: ${missing[*]}"
  if [[ "$(id -u)" == 0 ]]; then
    SUDO=()
  elif command -v sudo >/dev/null; then
    SUDO=(sudo)
  else
    echo "setup.sh: need root (or sudo) to install: ${missing[*]}" >&2
    exit 1
  fi
  "${SUDO[@]}" apt-get update
  "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
    "${missing[@]}"
else
  step "Debian packages: all ${#PACKAGES[@]} already installed"
fi

# --- 2. Configure and build ----------------------------------------------------
CMAKE_ARGS=(-G Ninja -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3)
if [[ -x /usr/local/cuda/bin/nvcc ]]; then
  CMAKE_ARGS+=(-DGDR_ENABLE_CUDA=ON -DCMAKE_CUDA_COMPILER=/usr/local/cuda/bin/nvcc
               -DCMAKE_CUDA_ARCHITECTURES=90)
else
  CMAKE_ARGS+=(-DGDR_ENABLE_CUDA=OFF)
fi
read -r -a EXTRA_ARGS <<<"${GDR_CMAKE_ARGS:-}"
step "Configuring $BUILD_DIR/ (CUDA: $([[ -x /usr/local/cuda/bin/nvcc ]] && echo on || echo off))"
cmake -S . -B "$BUILD_DIR" "${CMAKE_ARGS[@]}" "${EXTRA_ARGS[@]}"
step "Building with $JOBS jobs"
cmake --build "$BUILD_DIR" -j "$JOBS"
if ((BUILD_ONLY)); then exit 0; fi

# --- 3. Main job on the bundled example ------------------------------------------
GDR="$BUILD_DIR/bin/gdr"
step "Self-check"
"$GDR" selfcheck
step "Meshing the bundled example apps/gdr/examples/gear.poly"
mkdir -p out
"$GDR" 2d apps/gdr/examples/gear.poly -o out/example.vtu --min-angle 25 --max-area 0.001 \
  --remove-exterior --check --stats-json out/example.json

plugin="$(find "$BUILD_DIR" -path '*/paraview-*/plugins/*' -name '*.so' -print -quit 2>/dev/null || true)"
if [[ -f scripts/render_example.py && -n "$plugin" ]] && command -v xvfb-run >/dev/null; then
  step "Meshing the example again through the ParaView plugin and rendering out/example.png"
  xvfb-run -a pvbatch scripts/render_example.py apps/gdr/examples/gear.poly out/example.png \
    --vtu out/example_paraview.vtu --min-angle 25 --max-area 0.001 --plugin "$plugin" ||
    echo "setup.sh: warning: rendering failed; the mesh itself is in out/example.vtu" >&2
  # 3D: a ball with a spherical cavity into tetrahedra, pictured cut open beside its
  # dihedral-angle histogram. pvbatch may end with a GLX error under xvfb-run after its
  # work is done, so the outputs say whether it worked.
  step "Meshing the bundled closed surface Testing/Filters/Data/hollow_sphere.vtp into tetrahedra through the plugin: out/example3d.vtu and out/example3d.png"
  rm -f out/example3d.vtu out/example3d.png
  xvfb-run -a pvbatch scripts/render_example3d.py Testing/Filters/Data/hollow_sphere.vtp \
    out/example3d.png --radius-edge 1.4 --plugin "$plugin" || true
  [[ -f out/example3d.vtu && -f out/example3d.png ]] ||
    echo "setup.sh: warning: the 3D example through the ParaView plugin failed (see above)" >&2
fi
outputs="out/example.vtu (open it in ParaView), out/example.json"
for f in out/example.png out/example3d.vtu out/example3d.png; do
  if [[ -f $f ]]; then outputs+=", $f"; fi
done
step "Done: $outputs"
