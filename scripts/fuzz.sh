#!/usr/bin/env bash
# Builds the libFuzzer targets with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer in build-fuzz/ and runs each for FUZZ_SECONDS
# (default 300; FUZZ_TARGETS picks targets) from a seed corpus: the shipped scenes, the malformed scenes of
# Testing/Data/BadScenes and its VDB files; for FuzzSceneFiles, the meshes and
# volumes there and in Data/, each behind the byte that picks its format (the
# malformed ones include files announcing absurd component counts). An input
# slower than FUZZ_TIMEOUT seconds (default 10) or using more than FUZZ_RSS_MB
# (default 2048, AddressSanitizer's shadow included) counts as a finding.
# With FUZZ_RUNS, each target instead runs that many mutated inputs from
# seed 1 after its corpus; FUZZ_RUNS=0 runs the seed corpus alone, once
# each, which is the same on every machine (CI runs the targets so:
# mutations from the same seed differed between two fresh machines).
# Findings land in build-fuzz/findings; any finding makes the script fail.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${FUZZ_SECONDS:-300}
# clang and its runtimes (libFuzzer and the sanitizers are in
# libclang-rt-14-dev, which clang only recommends).
if ! command -v clang++ > /dev/null ||
  [ ! -e "$(clang++ -print-file-name=libclang_rt.fuzzer-x86_64.a)" ]; then
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends clang libclang-rt-14-dev
fi
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_C_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DBUILD_TESTING=OFF -DBRUME_WRAP_PYTHON=OFF -DBRUME_BUILD_PARAVIEW_PLUGIN=OFF \
  -DBRUME_BUILD_FUZZERS=ON
cmake --build build-fuzz --parallel "${BUILD_JOBS:-2}" --target FuzzSceneReader FuzzSceneFiles FuzzOpenVDBReader

work=build-fuzz/run
# The corpora start from the seeds on every run (libFuzzer adds to them).
rm -rf build-fuzz/findings "$work"
mkdir -p "$work/scene-corpus" "$work/vdb-corpus" "$work/file-corpus" build-fuzz/findings
cp Testing/Data/BadScenes/* "$work/"
cp Data/scenes/* "$work/"
cp Testing/Data/BadScenes/*.json Data/scenes/*.json "$work/scene-corpus/"
cp Testing/Data/BadScenes/*.vdb "$work/vdb-corpus/"
# FuzzSceneFiles reads its first byte as the format: 0 vti, 1 ply, 2 obj, 3 stl, 4 vtp, 5 vtu.
for f in Testing/Data/BadScenes/*.{vti,ply,obj,stl,vtp,vtu} Data/models/*.obj; do
  case "${f##*.}" in vti) b=0 ;; ply) b=1 ;; obj) b=2 ;; stl) b=3 ;; vtp) b=4 ;; vtu) b=5 ;; esac
  { printf "\\$(printf '%03o' "$b")"; head -c 65535 "$f"; } > "$work/file-corpus/$(basename "$f")"
done
export ASAN_OPTIONS="detect_leaks=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
status=0
for target in ${FUZZ_TARGETS:-FuzzSceneReader FuzzSceneFiles FuzzOpenVDBReader}; do
  corpus=scene-corpus
  [ "$target" = FuzzOpenVDBReader ] && corpus=vdb-corpus
  [ "$target" = FuzzSceneFiles ] && corpus=file-corpus
  if [ -n "${FUZZ_RUNS:-}" ]; then
    budget=(-runs="$FUZZ_RUNS" -seed=1)
    echo "== $target, $FUZZ_RUNS runs"
  else
    budget=(-max_total_time="$seconds")
    echo "== $target, $seconds s"
  fi
  (cd "$work" && "$root/build-fuzz/bin/$target" "$corpus" "${budget[@]}" \
    -max_len=65536 -timeout="${FUZZ_TIMEOUT:-10}" -rss_limit_mb="${FUZZ_RSS_MB:-2048}" \
    -artifact_prefix="$root/build-fuzz/findings/$target-" \
    -print_final_stats=1) 2>&1 | grep -E "^#[0-9]+.*DONE|stat::number_of_executed_units|ERROR|SUMMARY" || status=1
done
ls build-fuzz/findings
exit $status
