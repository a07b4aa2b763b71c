#!/usr/bin/env bash
# The force admittances' cost per cycle (docs/BENCHMARKS.md, "Force admittance per cycle"), counted
# in instructions by valgrind's callgrind: mrqp-run on a force-control scene (simulated buses, the
# ideal plant by default) for N cycles, collecting only inside the controller's cycle
# (--toggle-collect: boot, plant and emulated firmware not counted). Prints, per loop cycle, the
# inclusive instructions of the cycle, of the problem's update and solve, of the estimate phase,
# and of the admittance hook (every admittance of the scene: its sensor reading, eq. 45-46, the
# Butterworth filter, the bound and the task references it writes). Counts are deterministic for a
# given binary: the load of the machine does not change them (timing the hook is below the noise
# of this machine: a few hundred nanoseconds against a cycle of ~150 µs).
#
# Usage: tools/run/bench_admittance.sh [--build DIR] [--cycles N] [--scene FILE] [--plant P]
#        defaults: build/release, 1000, tools/scenes/carry_box.yaml, ideal (≈ 4 min under callgrind)
# Needs valgrind (Debian package valgrind).
set -euo pipefail

here=$(cd "$(dirname "$0")/../.." && pwd)
build=$here/build/release
cycles=1000
scene=$here/tools/scenes/carry_box.yaml
plant=ideal
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --cycles) cycles=$2; shift 2 ;;
    --scene) scene=$2; shift 2 ;;
    --plant) plant=$2; shift 2 ;;
    -h | --help) sed -n '2,14s/^# \{0,1\}//p' "$0"; exit 0 ;;
    *) echo "bench_admittance: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
run=$build/tools/run/mrqp-run
[ -x "$run" ] || { echo "bench_admittance: $run not built (cmake --build $build --target mrqp-run)" >&2; exit 1; }
[[ $cycles =~ ^[1-9][0-9]*$ ]] || { echo "bench_admittance: --cycles needs a positive integer, got '$cycles'" >&2; exit 2; }
command -v valgrind > /dev/null || { echo "bench_admittance: valgrind not found (apt-get install valgrind)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "bench_admittance: $(basename "$scene"), $cycles cycles under callgrind ..." >&2
valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" \
  --toggle-collect='mrqp::loop::Controller::cycle(long)' \
  "$run" "$scene" --plant "$plant" --cycles "$cycles" --quiet --out "$work/run" > "$work/log" 2>&1 \
  || { tail -20 "$work/log" >&2; echo "bench_admittance: mrqp-run failed under callgrind" >&2; exit 1; }
callgrind_annotate --inclusive=yes --threshold=100 "$work/cg.out" > "$work/annotate" 2> /dev/null

python3 - "$work/annotate" "$cycles" << 'PY'
import re, sys
text = open(sys.argv[1]).read()
n = int(sys.argv[2])
def ir(name):
    m = re.search(r"^\s*([\d,]+)\s+\([^)]*\)\s+\?\?\?:" + re.escape(name), text, re.M)
    return int(m.group(1).replace(",", "")) if m else 0
rows = [("controller cycle (read → write)", "mrqp::loop::Controller::cycle(long)"),
        ("  problem update", "mrqp::problem::MultiRobotProblem::update()"),
        ("  problem solve", "mrqp::problem::MultiRobotProblem::solve()"),
        ("  state estimate", "mrqp::loop::Controller::estimate(long)"),
        ("  admittance hook (every admittance)", "mrqp::force::AdmittanceHook::onCycle(")]
total = ir(rows[0][1])
if total == 0:
    sys.exit("bench_admittance: no instructions counted inside Controller::cycle")
print("| part | instructions per loop cycle | share of the cycle |")
print("|---|--:|--:|")
for label, name in rows:
    v = ir(name)
    print(f"| {label} | {v / n:,.0f} | {100.0 * v / total:.2f} % |")
PY
