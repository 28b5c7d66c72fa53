#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time over a scratch copy of its seed corpus
# (the repository's corpus is only read). Exits non-zero on any crash, leak or
# sanitizer report; a reproducer is left in the scratch folder's artifacts and printed.
# Usage: run_fuzzer.sh FUZZER SEED_CORPUS_DIR SECONDS [MORE_SEED_DIRS...]
# (further seed folders that do not exist are skipped: the real calibration files, when
# they sit beside the source tree)
set -euo pipefail
fuzzer="$1" seeds="$2" seconds="$3"
shift 3
more=()
for dir in "$@"; do [ -d "$dir" ] && more+=("$dir"); done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/corpus" "$work/artifacts"
if "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
     -artifact_prefix="$work/artifacts/" -print_final_stats=1 "$work/corpus" "$seeds" "${more[@]}" > "$work/log" 2>&1; then
  grep -E "^(#[0-9]+.*DONE|stat::number_of_executed_units)" "$work/log" | tail -2
  exit 0
fi
tail -40 "$work/log"
for artifact in "$work"/artifacts/*; do
  [ -e "$artifact" ] || continue
  echo "reproducer $(basename "$artifact") (base64):"
  base64 -w0 "$artifact"; echo
done
exit 1
