#!/usr/bin/env bash
# Builds the `fuzz` preset and fuzzes the text, ROS 1 bag, MCAP, PX4 ULog and ROS 2 SQLite readers, each for a bounded
# time.
#   fuzz/run.sh [SECONDS]   (default 30; per target)
# Each corpus grows in build/fuzz/corpus*, which starts as a copy of fuzz/seeds* (never modified).
# Crash inputs are written to build/fuzz/artifacts/. Exits non-zero when the fuzzer finds a
# crash, leak, timeout or sanitizer report, or when the build fails.
set -euo pipefail

seconds="${1:-30}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [[ "$seconds" -eq 0 ]]; then
  echo "usage: $0 [SECONDS]  (a positive whole number of seconds)" >&2
  exit 2
fi

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

cmake --preset fuzz >/dev/null
cmake --build build/fuzz --target fuzz_text_reader fuzz_bag_reader fuzz_mcap_reader fuzz_ulog_reader fuzz_db3_reader -j2

artifacts="build/fuzz/artifacts"
mkdir -p "$artifacts"

# One process per target (the build machine is shared). -timeout flags a single input running
# > 10 s as a hang; -rss_limit_mb catches runaway memory; leaks are reported by ASan's leak
# checker. The container seeds are whole files (~5-40 KB), hence the larger -max_len.
fuzz_one() {
  local target="$1" seeds="$2" corpus="$3" max_len="$4"
  mkdir -p "$corpus"
  cp -n "$seeds"/* "$corpus"/   # seeds are copied in, never written to
  ./build/fuzz/fuzz/"$target" \
    -max_total_time="$seconds" \
    -timeout=10 \
    -rss_limit_mb=2048 \
    -max_len="$max_len" \
    -print_final_stats=1 \
    -artifact_prefix="$artifacts/$target-" \
    "$corpus"
}

fuzz_one fuzz_text_reader fuzz/seeds build/fuzz/corpus 65536
fuzz_one fuzz_bag_reader fuzz/seeds_bag build/fuzz/corpus_bag 131072
fuzz_one fuzz_mcap_reader fuzz/seeds_mcap build/fuzz/corpus_mcap 131072
fuzz_one fuzz_ulog_reader fuzz/seeds_ulog build/fuzz/corpus_ulog 131072
fuzz_one fuzz_db3_reader fuzz/seeds_db3 build/fuzz/corpus_db3 65536
