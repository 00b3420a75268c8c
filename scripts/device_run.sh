#!/usr/bin/env bash
# One call on the GPU machine (H100, no network): core tests on the GPU, then a benchmark tier.
# Run from the repository root, with .device carried (made by scripts/package_device.sh):
#   scripts/device_run.sh [TIER|CASES.txt] [--no-tests] [--tests-only] [--only SUBSTRING]
# TIER names Benchmarks/cases_TIER.txt: quick, full, xl, large, cgal10M, ablation, crossover,
# 3d_quick, 3d_quick_no_gqm3d, 3d_large, 3d_crossover, 3d_headline, 3d_cgal, 3d_rdt, 3d_rdt_gdr,
# 3d_rdt_features, 2d_size. --only runs the cases whose name contains SUBSTRING.
# Primary path: the programs prebuilt here (.device/bin, .device/tests). If .device/bin has no
# gdr_bench, the core, its tests and gdr_bench are built there with CUDA (no CGAL, no VTK),
# GoogleTest from .device/googletest; the CPU baselines always come prebuilt from .device/bin.
# The anchors (Triangle, the authors' gDP2d and gQM3d) come packed in .device/anchors.tar.gz
# and are unpacked into .device/bin.
# Results go to $OUT (the device tool brings back up to 8 files): device_run.log, tests.log,
# bench.csv, bench.md, histograms.csv (3D dihedral angles). The benchmark table is printed last.
# Environment: GDR_TEST_TIMEOUT (s per test program, default 240), GDR_CALL_BUDGET (s the
# whole script may take, default 570: the device tool stops a call at 600), GDR_BUILD_JOBS.
set -uo pipefail

root=$(pwd)
tier=quick run_tests=1 run_bench=1 only=()
while (( $# )); do
  case $1 in
    --no-tests) run_tests=0 ;;
    --tests-only) run_bench=0 ;;
    --only) only=(--only "${2:?--only needs a substring}"); shift ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) tier=$1 ;;
  esac
  shift
done
if [[ -f $root/Benchmarks/cases_$tier.txt ]]; then
  cases=$root/Benchmarks/cases_$tier.txt
else
  cases=$tier
fi
out=${OUT:-$root/bench-out}
mkdir -p "$out"
dev=$root/.device

# Carried libraries apply to our programs only: system tools (cmake, ctest) keep their own.
with_libs() { LD_LIBRARY_PATH="$dev/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$@"; }

setup_paths() {
  # Test programs carry absolute paths of the machine that built them (the source tree and
  # ../shared/data beside it). Recreate those paths as links when they are missing here.
  local src=${1:-}
  [[ -n $src ]] || src=$(sed -n 's/^source_dir=//p' "$dev/manifest.txt" 2>/dev/null)
  [[ -n $src ]] || return 0
  if [[ ! -e $src ]]; then mkdir -p "$(dirname "$src")" && ln -s "$root" "$src"; fi
  local shared
  shared=$(dirname "$src")/shared
  if [[ ! -e $shared/data && -d $dev/data ]]; then mkdir -p "$shared" && ln -s "$dev/data" "$shared/data"; fi
}

build_here() {
  echo "== building on this machine (no prebuilt gdr_bench in .device/bin)"
  local jobs=${GDR_BUILD_JOBS:-$(nproc)}
  local gtest_prefix=/tmp/gdr-gtest
  if [[ -d $dev/googletest ]]; then
    cmake -S "$dev/googletest" -B /tmp/gdr-gtest-build -G Ninja -DBUILD_GMOCK=OFF \
      -DCMAKE_INSTALL_PREFIX=$gtest_prefix >/dev/null &&
      cmake --build /tmp/gdr-gtest-build -j "$jobs" >/dev/null &&
      cmake --install /tmp/gdr-gtest-build >/dev/null || return 1
  fi
  cmake -S "$root" -B "$root/build-device" -G Ninja -DGDR_ENABLE_VTK=OFF -DGDR_ENABLE_CGAL=OFF \
    -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_PREFIX_PATH=$gtest_prefix || return 1
  ninja -C "$root/build-device" -j "$jobs" || return 1
}

main() {
  echo "== $(date -u '+%Y-%m-%d %H:%M:%S UTC') tier=$tier cases=$cases"
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>&1 || true
  echo "cores: $(nproc)"
  [[ -f $dev/manifest.txt ]] && sed 's/^/  package: /' "$dev/manifest.txt"

  local bench bin_dir=$dev/bin tests=() built_here=0
  if [[ -f $dev/anchors.tar.gz && ! -x $dev/bin/gqm3d ]]; then
    mkdir -p "$dev/bin" && tar -C "$dev/bin" -xzf "$dev/anchors.tar.gz" &&
      echo "anchors: $(tar -tzf "$dev/anchors.tar.gz" | sed -n 's|^\./||p' | tr '\n' ' ')"
  fi
  if [[ -x $dev/bin/gdr_bench ]]; then
    bench=$dev/bin/gdr_bench
    tests=("$dev"/tests/*)
    setup_paths
  else
    build_here || { echo "build failed"; return 1; }
    built_here=1
    setup_paths "$root"
    bench=$root/build-device/bin/gdr_bench
  fi

  local failed=0
  if (( run_tests )); then
    echo "== tests (GPU and CPU backends)"
    : > "$out/tests.log"
    local limit=${GDR_TEST_TIMEOUT:-240}
    if (( built_here )); then
      (cd "$root/build-device" && ctest --output-on-failure --timeout "$limit" -j 4) \
        >> "$out/tests.log" 2>&1 || failed=1
      tail -n 5 "$out/tests.log"
    else
      local t start rc
      for t in "${tests[@]}"; do
        [[ -x $t ]] || continue
        start=$SECONDS
        echo "---- $(basename "$t")" >> "$out/tests.log"
        # Leave the benchmark at least two minutes of the call.
        local room=$(( ${GDR_CALL_BUDGET:-570} - 120 - SECONDS ))
        (( room < limit )) && limit=$room
        (( limit < 10 )) && { echo "  $(basename "$t"): not run (no time left)"; failed=1; continue; }
        with_libs timeout -k 5 "$limit" "$t" --gtest_color=no >> "$out/tests.log" 2>&1
        rc=$?
        (( rc != 0 )) && failed=1
        printf '  %-32s %s (%ds)\n' "$(basename "$t")" \
          "$( ((rc == 0)) && echo passed || { ((rc == 124)) && echo TIMEOUT || echo "FAILED rc=$rc"; })" \
          $((SECONDS - start))
      done
      grep -E '^\[  FAILED  \]|^\[  SKIPPED \]' "$out/tests.log" | sort -u | head -n 20
    fi
  fi

  if (( run_bench )); then
    # Whatever the tests left of the call's budget; gdr_bench rewrites bench.csv after every
    # case, so a run cut short still returns what it measured.
    local left=$(( ${GDR_CALL_BUDGET:-570} - SECONDS ))
    (( left < 30 )) && left=30
    echo "== benchmark: $cases (at most ${left} s)"
    with_libs timeout -k 5 "$left" "$bench" "$cases" --out-dir "$out" \
      --data-dir "$dev/data" --bin-dir "$bin_dir" ${only[@]+"${only[@]}"} 2>&1 || {
        echo "gdr_bench stopped early (rc $?); the cases it finished:"
        cat "$out/bench.md" 2>/dev/null
        failed=1
      }
  fi
  return $failed
}

main 2>&1 | tee "$out/device_run.log"
exit "${PIPESTATUS[0]}"
