#!/usr/bin/env bash
# Builds the `fuzz` preset and fuzzes the text reader for a bounded time.
#   fuzz/run.sh [SECONDS]   (default 30)
# The corpus grows in build/fuzz/corpus, which starts as a copy of fuzz/seeds (never modified).
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
cmake --build build/fuzz --target fuzz_text_reader -j2

corpus="build/fuzz/corpus"
artifacts="build/fuzz/artifacts"
mkdir -p "$corpus" "$artifacts"
cp -n fuzz/seeds/* "$corpus"/   # seeds are copied in, never written to

# One process (the build machine is shared). -timeout flags a single input running > 10 s as a
# hang; -rss_limit_mb catches runaway memory; leaks are reported by ASan's leak checker.
./build/fuzz/fuzz/fuzz_text_reader \
  -max_total_time="$seconds" \
  -timeout=10 \
  -rss_limit_mb=2048 \
  -max_len=65536 \
  -print_final_stats=1 \
  -artifact_prefix="$artifacts/" \
  "$corpus"
