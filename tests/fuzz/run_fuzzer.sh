#!/usr/bin/env bash
# One short libFuzzer run of a harness (the CTest tests fuzz.<name>, tests/fuzz/CMakeLists.txt):
#   run_fuzzer.sh HARNESS SEEDS_FILE WORK_DIR SECONDS
# replays every regression input and seed named by SEEDS_FILE (one file or directory a line; the
# first line is tests/data/fuzz/<name>, the regression inputs), then fuzzes for SECONDS. New corpus
# entries go to WORK_DIR/corpus, a crashing input to WORK_DIR/crash-*: copy it into
# tests/data/fuzz/<name>/ once the reader is fixed, so every later run replays it.
set -euo pipefail
harness=$1 seeds_file=$2 work=$3 seconds=$4
mkdir -p "$work/corpus"
dirs=() files=()
while IFS= read -r line; do
  if [ -d "$line" ]; then dirs+=("$line"); elif [ -f "$line" ]; then files+=("$line"); fi
done < "$seeds_file"
seed_inputs=()
if [ ${#files[@]} -gt 0 ]; then
  seed_inputs=("-seed_inputs=$(IFS=,; echo "${files[*]}")")
fi
# Bounded memory and time per input: an input needing more than 2 GB or 10 s is a finding.
exec "$harness" -max_total_time="$seconds" -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10 \
  -artifact_prefix="$work/" -print_final_stats=1 "${seed_inputs[@]}" "$work/corpus" "${dirs[@]}"
