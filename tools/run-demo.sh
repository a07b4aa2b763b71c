#!/usr/bin/env bash
# The main job: generate allocation-free model code for every URDF in ../shared/models
# (control/model/urdf and tests/data/models when that folder is absent), compile it and print a summary table per model
# (links, joints, nq, nv, mass, timing of the generated functions); then run the multi-robot QP
# scenes of tools/scenes closed loop and plot them (build/demo/*.png); last, the controller loop
# (mrqp-run) runs the co-manipulation scene over CAN (simulated buses carrying the emulated drive,
# F/T and IMU firmware) on the MuJoCo plant behind that firmware, then the door scene and JVRC-1's
# box scene the same way; summary, log, plots and the rendered motion in build/demo/comanipulation,
# build/demo/panda_door_mujoco and build/demo/jvrc1_box_mujoco. A build without MuJoCo runs the
# co-manipulation scene on the ideal plant instead (docs/mujoco.md).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
jobs=$(nproc)

./tools/setup-deps.sh
models="$root/../shared/models"
if [ -d "$models" ]; then
  urdfs=("$models"/*.urdf)
else
  urdfs=("$root/control/model/urdf"/*.urdf "$root/tests/data/models"/*.urdf)
  models="control/model/urdf and tests/data/models"
fi

echo "== building mrqp-gen and the summary tool (Release)" >&2
cmake -S . -B build/demo -DCMAKE_BUILD_TYPE=Release -DMRQP_BUILD_TESTS=OFF > /dev/null
cmake --build build/demo -j"$jobs" --target mrqp-gen mrqp-model-summary > build/demo-build.log 2>&1 \
  || { tail -40 build/demo-build.log; exit 1; }

echo "== generating models from $models" >&2
out="$root/build/demo/generated"
mkdir -p "$out"
for urdf in "${urdfs[@]}"; do
  base=$(basename "$urdf" .urdf)
  name=$(echo "$base" | tr -c 'A-Za-z0-9_\n' '_')
  flags=()
  case "$base" in
    jvrc1|human-*) flags+=(--floating-base) ;;
  esac
  case "$base" in
    romeo) flags+=(--allow-nonphysical-inertia) ;;  # two links of the public model break the triangle inequality
  esac
  if ./build/demo/model_gen/mrqp-gen "$urdf" --name "$name" --out "$out" --probe "${flags[@]}" \
       2> "$out/$name.warnings.txt"; then
    echo "   $(grep -c 'warning' "$out/$name.warnings.txt" || true) warnings (see $out/$name.warnings.txt)" >&2
  else
    cat "$out/$name.warnings.txt" >&2
    exit 1
  fi
done

echo "== summary (generated code compiled in, median timings)" >&2
./build/demo/tools/mrqp-model-summary --csv "$root/build/demo/model_summary.csv"
echo "(CSV: build/demo/model_summary.csv; generated sources: build/demo/generated)" >&2

echo "== multi-robot QP scenes, closed loop on their own models (tools/scenes)" >&2
cmake --build build/demo -j"$jobs" --target mrqp-scene > build/demo-build.log 2>&1 \
  || { tail -40 build/demo-build.log; exit 1; }
for scene in jvrc1_box panda_door; do
  ./build/demo/tools/scene_run/mrqp-scene --scene "tools/scenes/$scene.yaml" \
    --csv "build/demo/$scene.csv" --plot "build/demo/$scene.png"
done
echo "(logs and plots: build/demo/jvrc1_box.{csv,png}, build/demo/panda_door.{csv,png})" >&2

echo "== the controller loop over CAN: co-manipulation (mrqp-run, docs/loop.md)" >&2
cmake --build build/demo -j"$jobs" --target mrqp-run > build/demo-build.log 2>&1 \
  || { tail -40 build/demo-build.log; exit 1; }
# One scene through the loop: SCENE PLANT OUT. A safe stop (exit 3) is reported, not fatal.
run_scene() {
  local rc=0
  ./build/demo/tools/run/mrqp-run "tools/scenes/$1.yaml" --plant "$2" --out "$root/build/demo/$3" || rc=$?
  case $rc in
    0) ;;
    3) echo "(the controller went to its safe state on the $2 plant: build/demo/$3/summary.json says why and when)" >&2 ;;
    *) exit "$rc" ;;
  esac
}
# The MuJoCo plant behind the emulated drives where the build has MuJoCo (mrqp-render is built
# with it); the ideal plant (the models as their own plant) otherwise.
if cmake --build build/demo -j"$jobs" --target mrqp-render > build/demo-build.log 2>&1; then
  echo "   co-manipulation, MuJoCo plant (docs/mujoco.md)" >&2
  run_scene comanipulation mujoco comanipulation
  echo "== the door and JVRC-1 carrying a box on the MuJoCo plant (mrqp-run --plant mujoco, docs/mujoco.md)" >&2
  run_scene panda_door mujoco panda_door_mujoco
  run_scene jvrc1_box mujoco jvrc1_box_mujoco
  echo "(on MuJoCo: build/demo/{panda_door_mujoco,jvrc1_box_mujoco}/{summary.json,log.csv,*.png,motion.mp4})" >&2
else
  echo "(this build has no MuJoCo: co-manipulation on the ideal plant, no rendering of the scene)" >&2
  run_scene comanipulation ideal comanipulation
fi
echo "(summary, log, plots and motion: build/demo/comanipulation/{summary.json,log.csv,*.png,motion.mp4})" >&2
