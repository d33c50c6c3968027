#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, into build-fuzz/) and runs each for
# SECONDS seconds, seeded from tests/fuzz/seeds, assets/ and ../shared/corpus (when
# present). See docs/fuzzing.md.
#
#   tests/fuzz/run.sh SECONDS [TARGET...]      e.g. tests/fuzz/run.sh 15, or 600 fuzz_ply
#
# Environment: GS_FUZZ_JOBS=N runs N targets at once (default 1); GS_FUZZ_BUILD=DIR
# (default build-fuzz); GS_FUZZ_EXECS=N stops each target after N executions if SECONDS
# have not passed first (e.g. GS_FUZZ_EXECS=10000000 tests/fuzz/run.sh 86400 fuzz_nifti). The growing corpora stay in DIR/corpus/TARGET, logs in
# DIR/logs/TARGET.log and any crashing input in DIR/artifacts/TARGET/. Exits 1 when a
# target found a crash, leak or time-out (its input is printed), 0 otherwise.
set -euo pipefail
top=$(cd "$(dirname "$0")/../.." && pwd)
here="$top/tests/fuzz"
seconds=${1:?usage: run.sh SECONDS [TARGET...]}
shift
build=${GS_FUZZ_BUILD:-$top/build-fuzz}
jobs=${GS_FUZZ_JOBS:-1}
all=(fuzz_vrml_parse fuzz_vrml_stream fuzz_vrml_proto fuzz_x3d_xml fuzz_x3d_json fuzz_qnv_stream fuzz_qnv_compact fuzz_qnv_entropy fuzz_tileset_index
     fuzz_ply fuzz_obj fuzz_gltf fuzz_gltf_scene fuzz_nrrd fuzz_nifti fuzz_dicom fuzz_tiff fuzz_vdb fuzz_image fuzz_dds fuzz_http_response
     fuzz_instance_message fuzz_script fuzz_splats fuzz_dis)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${all[@]}")

launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
# -O1 with line tables: what libFuzzer recommends, and quicker to build than -O2.
generator=()
[ -e "$build/CMakeCache.txt" ] || ! command -v ninja > /dev/null || generator=(-G Ninja)
# A sanitizer build configured with -DGS_FUZZ=ON (CI's, .ci/test) is used as it is: its
# libraries carry libFuzzer's light coverage and its targets run at -O0 (docs/ci.md).
if grep -qs '^GS_SANITIZE:BOOL=ON' "$build/CMakeCache.txt" && grep -qs '^GS_FUZZ:BOOL=ON' "$build/CMakeCache.txt"; then
  echo "fuzz targets of the sanitizer build $build"
else
  cmake -S "$top" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGS_FUZZ=ON -DGS_BUILD_TESTS=OFF \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" \
    -DCMAKE_UNITY_BUILD="${GS_UNITY:-ON}" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" > /dev/null
fi
# Only the targets asked for (and the QNV seed writer): quicker when some are named. A unity
# build (cmake/Unity.cmake) that fails on two files' colliding local names is built again
# one file per unit, saying so.
if ! cmake --build "$build" -j"$(nproc)" --target make_qnv_seeds "${targets[@]}"; then
  [ "${GS_UNITY:-ON}" = ON ] || exit 1
  echo "unity build failed: building one file per unit (add the file to cmake/Unity.cmake)"
  cmake -S "$top" -B "$build" -DCMAKE_UNITY_BUILD=OFF > /dev/null
  cmake --build "$build" -j"$(nproc)" --target make_qnv_seeds "${targets[@]}"
fi

corpus_root="$top/../shared/corpus"
mkdir -p "$build/seeds/qnv" "$build/seeds/compact" "$build/seeds/entropy" "$build/logs"
"$build/fuzz/make_qnv_seeds" "$build/seeds/qnv"
mv -f "$build/seeds/qnv"/compact_*.bin "$build/seeds/compact/"
mv -f "$build/seeds/qnv"/entropy_*.bin "$build/seeds/entropy/"

# Seed folders (those that exist), dictionary and input size cap of each target.
seeds_of() {
  local s=()
  case "$1" in
    fuzz_vrml_parse | fuzz_vrml_stream)
      s=("$here/seeds/vrml" "$top/assets/worlds" "$corpus_root/vrml/openvrml/bad") ;;
    fuzz_vrml_proto) s=("$here/seeds/proto" "$here/seeds/vrml") ;;
    fuzz_x3d_xml) s=("$top/assets/worlds" "$corpus_root/x3d/castle/x3d/warnings") ;;
    fuzz_x3d_json) s=("$top/assets/worlds") ;;
    fuzz_qnv_stream) s=("$here/seeds/qnv" "$build/seeds/qnv") ;;
    fuzz_qnv_compact) s=("$here/seeds/compact" "$build/seeds/compact") ;;
    fuzz_qnv_entropy) s=("$here/seeds/entropy" "$build/seeds/entropy") ;;
    fuzz_tileset_index) s=("$top/tests/qnv/golden/tileset_blob") ;;
    fuzz_ply | fuzz_obj | fuzz_gltf | fuzz_gltf_scene) s=("$here/seeds/mesh") ;;
    fuzz_nrrd | fuzz_nifti) s=("$here/seeds/volume") ;;
    fuzz_dicom) s=("$here/seeds/dicom") ;;
    fuzz_tiff) s=("$here/seeds/tiff") ;;
    fuzz_vdb) s=("$here/seeds/vdb") ;;
    fuzz_image) s=("$here/seeds/image" "$top/assets/worlds/textures") ;;
    fuzz_http_response) s=("$here/seeds/http") ;;
    fuzz_instance_message) s=("$here/seeds/instance") ;;
    fuzz_script) s=("$here/seeds/script") ;;
    fuzz_splats) s=("$here/seeds/splats") ;;
    fuzz_dis) s=("$here/seeds/dis") ;;
  esac
  for d in "${s[@]}"; do [ -d "$d" ] && echo "$d"; done
  return 0
}
dict_of() {
  case "$1" in
    fuzz_vrml_* | fuzz_x3d_xml | fuzz_x3d_json) echo "$here/dict/vrml.dict" ;;
    fuzz_nrrd | fuzz_nifti) echo "$here/dict/nrrd.dict" ;;
    fuzz_script) echo "$here/dict/script.dict" ;;
    fuzz_http_response) echo "$here/dict/http.dict" ;;
  esac
}
max_len_of() {
  case "$1" in
    fuzz_qnv_stream | fuzz_image | fuzz_gltf | fuzz_gltf_scene | fuzz_nifti | fuzz_dicom | fuzz_splats) echo 200000 ;;
    *) echo 65536 ;;
  esac
}

run_one() {
  local t=$1
  local work="$build/corpus/$t" art="$build/artifacts/$t/"
  mkdir -p "$work" "$art"
  local args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
              -max_len="$(max_len_of "$t")" -artifact_prefix="$art")
  [ -n "${GS_FUZZ_EXECS:-}" ] && args+=(-runs="$GS_FUZZ_EXECS")
  # The readers that fork a child per input (base/isolated_process.hpp): no RSS thread
  # (-rss_limit_mb=0 starts none), whose allocations could hold ASan's allocator lock at
  # the fork and leave the child waiting on it; the child's memory has its own bound.
  case "$t" in fuzz_vdb | fuzz_dicom) args+=(-rss_limit_mb=0) ;; esac
  local dict
  dict=$(dict_of "$t")
  [ -n "$dict" ] && args+=(-dict="$dict")
  mapfile -t seeds < <(seeds_of "$t")
  if "$build/fuzz/$t" "${args[@]}" "$work" "${seeds[@]}" > "$build/logs/$t.log" 2>&1; then
    echo "ok"
  else
    echo "FAILED"
  fi
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Leaks of linked libraries on their error paths (GDCM and the codecs it calls), not ours: tests/fuzz/lsan.supp.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/lsan.supp}
results="$build/logs/results.txt"
: > "$results"
running=0
for t in "${targets[@]}"; do
  (echo "$t $(run_one "$t")" >> "$results") &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait

# One line per target: executions, executions per second, coverage, corpus, result.
status=0
printf '%-22s %12s %9s %7s %7s  %s\n' target executions exec/s cov corpus result
for t in "${targets[@]}"; do
  log="$build/logs/$t.log"
  result=$(awk -v t="$t" '$1 == t {print $2}' "$results")
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  corp=$(grep -o 'corp: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  printf '%-22s %12s %9s %7s %7s  %s\n' "$t" "${execs:--}" "${rate:--}" "${cov:--}" "${corp:--}" \
    "${result:-FAILED}"
  if [ "$result" != ok ]; then
    status=1
    grep -m3 -E 'ERROR|SUMMARY|Test unit written' "$log" | sed 's/^/    /' || true
  fi
done
exit $status
