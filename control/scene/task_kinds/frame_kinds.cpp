// Scene kinds `frame_position`, `frame_orientation` and `frame_pose` (problem::FramePositionTask,
// FrameOrientationTask, FramePoseTask): `frame` of `entity`, at `point` (frame coordinates) for
// position and pose, to `target` [x, y, z], [roll, pitch, yaw] or [x, y, z, roll, pitch, yaw]
// (default: the pose at start). `dims` follows the target's order; a pose task's rows are
// (angular; linear), so its dims are swapped into that order.
#include "problem/tasks/frame_orientation_task.hpp"
#include "problem/tasks/frame_pose_task.hpp"
#include "problem/tasks/frame_position_task.hpp"
#include "scene/scene_builder.hpp"
#include "scene/task_kind.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

namespace {

void readSubject(const Map& m, TaskSpec* t) {
  readEntitySubject(m, t);
  t->frame = m.name("frame");
  t->point = m.vec3("point", t->point);
}

struct Resolved {
  int entity, frame;
  Eigen::Vector3d position;
  Eigen::Matrix3d rotation;
};

Resolved resolve(const TaskSpec& ts, const BuildContext& ctx, const std::string& field) {
  Resolved r;
  r.entity = taskEntity(ts, ctx, field);
  r.frame = ctx.frame(r.entity, ts.frame, ts.source, field + ".frame");
  const problem::Pose P = ctx.problem().entity(r.entity).framePose(r.frame);
  r.position = P.R * ts.point + P.p;
  r.rotation = P.R;
  return r;
}

std::unique_ptr<problem::Task> makePosition(const TaskSpec& ts, const BuildContext& ctx,
                                            const std::string& field) {
  const Resolved r = resolve(ts, ctx, field);
  const Eigen::Vector3d target = ts.target ? Eigen::Vector3d(ts.target->head<3>()) : r.position;
  auto task = std::make_unique<problem::FramePositionTask>(r.entity, r.frame, ts.point, target, r.rotation);
  task->setSelection(fileSelection(ts));
  return task;
}

std::unique_ptr<problem::Task> makeOrientation(const TaskSpec& ts, const BuildContext& ctx,
                                               const std::string& field) {
  const Resolved r = resolve(ts, ctx, field);
  const Eigen::Matrix3d R = ts.target ? rotationFromRpy(ts.target->head<3>()) : r.rotation;
  auto task = std::make_unique<problem::FrameOrientationTask>(r.entity, r.frame, ts.point, r.position, R);
  task->setSelection(fileSelection(ts));
  return task;
}

std::unique_ptr<problem::Task> makePose(const TaskSpec& ts, const BuildContext& ctx,
                                        const std::string& field) {
  const Resolved r = resolve(ts, ctx, field);
  Eigen::Vector3d p = r.position;
  Eigen::Matrix3d R = r.rotation;
  if (ts.target) {
    p = ts.target->head<3>();
    R = rotationFromRpy(ts.target->segment<3>(3));
  }
  auto task = std::make_unique<problem::FramePoseTask>(r.entity, r.frame, ts.point, p, R);
  problem::Task::Selection sel = fileSelection(ts);
  if (ts.dims.size() == 6) {  // file (x, y, z, rx, ry, rz) → rows (angular; linear)
    for (std::size_t k = 0; k < 3; ++k) {
      sel[k] = ts.dims[k + 3] ? 1 : 0;
      sel[k + 3] = ts.dims[k] ? 1 : 0;
    }
  }
  task->setSelection(sel);
  return task;
}

}  // namespace

TaskKindEntry framePositionKind() {
  return {"frame_position", 3,           {{"entity", "frame", "point", "target"}}, false, readSubject,
          nullptr,          makePosition};
}

TaskKindEntry frameOrientationKind() {
  return {"frame_orientation", 3, {{"entity", "frame", "target", nullptr}}, false, readSubject, nullptr,
          makeOrientation};
}

TaskKindEntry framePoseKind() {
  return {"frame_pose", 6, {{"entity", "frame", "point", "target"}}, false, readSubject, nullptr, makePose};
}

}  // namespace mrqp::scene
