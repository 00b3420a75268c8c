#!/usr/bin/env bash
# Collects everything the GPU machine lacks into .device/ (git-ignored), to be carried with
#   run(command="scripts/device_run.sh quick", carry=[".device"])
# The GPU machine has CUDA, CMake and ninja but no CGAL, TetGen, TBB, GMP, VTK or GoogleTest,
# and cannot download anything. So this script
#   1. builds the core, its tests, gdr_bench and the baselines here (CUDA arch 90) unless
#      --no-build is given (then it packages what build-bench already holds);
#   2. copies the programs (bin/), the test programs (tests/) and every shared library they
#      need that is not part of glibc or the NVIDIA driver (lib/), TetGen's libtet.so.1.5
#      among them (Debian has no static libtet), and checks with ldd that each resolves
#      from lib/;
#   2b. packs the anchors (../shared/anchors/bin: Triangle, the authors' gDP2d and gQM3d) into
#      anchors.tar.gz (24 MB of programs, ~9 MB packed); device_run.sh unpacks them into bin/;
#   3. copies the data set (data/) and GoogleTest's sources (googletest/, for building there);
#   4. writes manifest.txt (the absolute source path the test programs were compiled with).
# Environment: GDR_BENCH_BUILD (build dir, default build-bench), GDR_BUILD_JOBS (default 2).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${GDR_BENCH_BUILD:-$root/build-bench}
dest=$root/.device
jobs=${GDR_BUILD_JOBS:-2}
do_build=1
[[ ${1:-} == --no-build ]] && do_build=0

if (( do_build )); then
  cmake -S "$root" -B "$build" -G Ninja -DGDR_ENABLE_VTK=OFF -DGDR_BUILD_TESTING=ON -DGDR_BUILD_BENCHMARKS=ON \
    -DCMAKE_CUDA_COMPILER=/usr/local/cuda/bin/nvcc -DCMAKE_CUDA_ARCHITECTURES=90 >/dev/null
  # CGAL Mesh_3 units need ~3 GB each: build them alone first, then the rest.
  mesh3_objs=$(ninja -C "$build" -t targets all | grep -o '^Benchmarks/CMakeFiles/bench_cgal_mesh3.dir/baselines/mesh3_[a-z]*\.cpp\.o' || true)
  [[ -n $mesh3_objs ]] && ninja -C "$build" -j1 $mesh3_objs
  ninja -C "$build" -j"$jobs"
fi

rm -rf "$dest"
mkdir -p "$dest/bin" "$dest/tests" "$dest/lib"

# Programs in the build's bin/: our tools and baselines go to bin/, everything else is a test.
shopt -s nullglob
for exe in "$build"/bin/*; do
  [[ -f $exe && -x $exe ]] || continue
  case $(basename "$exe") in
    gdr|gdr_bench|bench_*) cp "$exe" "$dest/bin/" ;;
    *) cp "$exe" "$dest/tests/" ;;
  esac
done
strip --strip-unneeded "$dest"/bin/* "$dest"/tests/* 2>/dev/null || true

# Shared libraries: all that ldd resolves, except glibc's own and the driver's (the GPU
# machine must use its own libcuda; static cudart loads it at run time).
for exe in "$dest"/bin/* "$dest"/tests/*; do
  ldd "$exe" | awk '/=> \// {print $3}'
done | sort -u | while read -r lib; do
  case $(basename "$lib") in
    libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*|libresolv.so*) ;;
    libcuda.so*|libnvidia*) ;;
    *) cp -L "$lib" "$dest/lib/" ;;
  esac
done
strip --strip-unneeded "$dest"/lib/* 2>/dev/null || true

# Every library our programs need must come from lib/ or be glibc's or the driver's: the GPU
# machine has no TetGen, CGAL, GMP, TBB.
bad=0
for exe in "$dest"/bin/* "$dest"/tests/*; do
  while read -r name arrow path _; do
    [[ $arrow == "=>" ]] || continue
    case $name in
      libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*|libresolv.so*|libcuda.so*|libnvidia*) continue ;;
    esac
    if [[ $path != "$dest/lib/"* ]]; then
      echo "$(basename "$exe"): $name resolves to '$path', not to .device/lib" >&2
      bad=1
    fi
  done < <(LD_LIBRARY_PATH="$dest/lib" ldd "$exe")
done
(( bad == 0 )) || { echo "package_device.sh: libraries missing from .device/lib" >&2; exit 1; }
echo "ldd: every library of bin/ and tests/ resolves from .device/lib (or glibc, the driver)"

# The anchors: packed, they leave room for the rest within the 64 MiB the device tool carries.
anchors=$root/../shared/anchors/bin
if [[ -d $anchors ]]; then
  tar -C "$anchors" -czf "$dest/anchors.tar.gz" .
  echo "anchors packed: $(cd "$anchors" && echo *)"
else
  echo "no anchors at $anchors: triangle, gdp2d and gqm3d cases will report skipped" >&2
fi

data=$root/../shared/data
[[ -d $data ]] && cp -r "$data" "$dest/data" && chmod -R u+w "$dest/data"

# Everything that travels in one call: the working tree (tracked and untracked, not ignored)
# plus .device. GoogleTest's sources serve only the build-there fallback: they go in when
# they fit.
tree_kib=$(( $(git -C "$root" ls-files -co --exclude-standard -z | (cd "$root" && du -cb --files0-from=-) | tail -n 1 | cut -f1) / 1024 ))
limit_kib=$((62 * 1024))
if [[ -d /usr/src/googletest ]] &&
   (( tree_kib + $(du -sk "$dest" | cut -f1) + $(du -sk /usr/src/googletest | cut -f1) < limit_kib )); then
  cp -r /usr/src/googletest "$dest/googletest"
else
  echo "googletest sources left out (no room): the build-there fallback needs them" >&2
fi

{
  echo "source_dir=$root"
  echo "built=$(date -u '+%Y-%m-%d %H:%M:%S UTC') on $(hostname)"
  echo "commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
} > "$dest/manifest.txt"

echo "packaged into $dest:"
du -sh "$dest"/* | sed 's/^/  /'
total_kib=$(( $(du -sk "$dest" | cut -f1) + tree_kib ))
echo "  .device plus working tree: $((total_kib / 1024)) MiB (the device tool carries 64 MiB)"
if (( total_kib > limit_kib )); then
  echo "package_device.sh: too large to carry" >&2
  exit 1
fi
