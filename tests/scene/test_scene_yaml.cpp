// Scene files (control/scene/scene_yaml.hpp, docs/scenes.md): a full scene read field by field,
// and one file per error under tests/data/scenes/bad, each naming file, line and field.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "scene/scene_yaml.hpp"

using namespace mrqp::scene;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

const std::string kScenes = std::string(MRQP_TEST_DATA_DIR) + "/scenes/";

std::string errorOf(const std::string& path) {
  try {
    loadSceneFile(path);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string errorOfText(const std::string& text) {
  try {
    loadSceneString(text, "mem.yaml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

/// The error of bad/<name> starts with "FILE:LINE: FIELD: " and contains `part`.
void expectError(const std::string& name, int line, const std::string& field, const std::string& part) {
  const std::string path = kScenes + "bad/" + name;
  const std::string prefix = path + ":" + std::to_string(line) + ": " + field + ": ";
  const std::string what = errorOf(path);
  CHECK_THAT(what, StartsWith(prefix) && Contains(part));
}

bool near(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && (a - b).cwiseAbs().maxCoeff() < 1e-12;
}

}  // namespace

TEST_CASE("good_full.yaml: settings and entities", "[scene]") {
  const std::string path = kScenes + "good_full.yaml";
  const SceneSpec s = loadSceneFile(path);
  CHECK(s.file == path);

  const SettingsSpec& st = s.settings;
  CHECK(st.dt == 0.002);
  CHECK(st.duration == 4.0);
  CHECK(near(st.gravity, Eigen::Vector3d(0, 0, -9.8)));
  CHECK(st.max_tasks == 24);
  CHECK(st.max_contacts == 12);
  CHECK(st.max_contact_generators == 192);
  CHECK(st.contact_stiffness == 50.0);
  CHECK(st.contact_damping == 14.0);
  CHECK(st.regularisation == 1.0e-7);
  CHECK(st.source.file == path);
  CHECK(st.source.line == 3);

  REQUIRE(s.entities.size() == 3);
  const EntitySpec& jvrc = s.entities[0];
  CHECK(jvrc.name == "jvrc");
  CHECK(jvrc.model == "jvrc1");
  CHECK(near(jvrc.pose.xyz, Eigen::Vector3d(0, 0, 0.8)));
  CHECK(near(jvrc.pose.rpy, Eigen::Vector3d(0, 0, 1.5707963)));
  CHECK(jvrc.q == std::map<std::string, double>{{"L_ELBOW_P", -0.5}, {"R_ELBOW_P", -0.5}});
  CHECK(jvrc.actuation == "list");
  CHECK(jvrc.actuated_joints == std::vector<std::string>{"R_HIP_P", "L_HIP_P"});
  CHECK(jvrc.passive_joints == std::vector<std::string>{"R_WRIST_Y"});
  CHECK(jvrc.springs.empty());
  CHECK(jvrc.source.file == path);
  CHECK(jvrc.source.line == 14);

  const EntitySpec& door = s.entities[1];
  CHECK(door.name == "door");
  CHECK(door.model == "door");
  CHECK(near(door.pose.xyz, Eigen::Vector3d(1.2, 0, 0)));
  CHECK(near(door.pose.rpy, Eigen::Vector3d::Zero()));
  CHECK(door.q.empty());
  CHECK(door.actuation == "none");
  CHECK(door.actuated_joints.empty());
  CHECK(door.passive_joints == std::vector<std::string>{"door"});
  REQUIRE(door.springs.size() == 2);
  const SpringSpec& handle = door.springs.at("handle");
  CHECK(handle.stiffness == 2.0);
  CHECK(handle.damping == 0.1);
  CHECK(handle.offset == 0.3);
  CHECK(handle.source.line == 27);
  const SpringSpec& hinge = door.springs.at("door");
  CHECK(hinge.stiffness == 0.0);
  CHECK(hinge.damping == 0.0);
  CHECK(hinge.offset == 0.0);
  CHECK(hinge.source.line == 28);
  CHECK(door.source.line == 21);

  const EntitySpec& box = s.entities[2];
  CHECK(box.name == "box");
  CHECK(box.model == "rigid_object");
  CHECK(box.actuation == "default");
  CHECK(box.object.mass == 2.0);
  CHECK(near(box.object.com, Eigen::Vector3d(0, 0, 0.01)));
  Eigen::Matrix3d inertia;
  inertia << 0.02, 0.001, 0, 0.001, 0.03, 0, 0, 0, 0.04;
  CHECK(box.object.inertia == inertia);
  CHECK(near(box.pose.xyz, Eigen::Vector3d(0.5, 0, 1.0)));
  CHECK(near(box.pose.rpy, Eigen::Vector3d(0.1, 0.2, 0.3)));
  CHECK(box.source.line == 30);
}

TEST_CASE("good_full.yaml: contacts", "[scene]") {
  const SceneSpec s = loadSceneFile(kScenes + "good_full.yaml");
  REQUIRE(s.contacts.size() == 2);
  const ContactSpec& foot = s.contacts[0];
  CHECK(foot.name == "left_foot");
  CHECK(foot.entity == "jvrc");
  CHECK(foot.frame == "L_ANKLE_P_S");
  CHECK(foot.other_entity.empty());
  CHECK(foot.other_frame.empty());
  REQUIRE(foot.points.size() == 4);
  CHECK(near(foot.points[0], Eigen::Vector3d(0.1, 0.05, -0.1)));
  CHECK(near(foot.points[3], Eigen::Vector3d(-0.1, -0.05, -0.1)));
  CHECK(near(foot.normal, Eigen::Vector3d::UnitZ()));
  CHECK(foot.friction == 0.7);
  CHECK(foot.generators == 4);
  CHECK(foot.active);
  CHECK(foot.source.line == 38);

  const ContactSpec& hand = s.contacts[1];
  CHECK(hand.name == "right_hand");
  CHECK(hand.entity == "jvrc");
  CHECK(hand.frame == "R_WRIST_Y_S");
  CHECK(hand.other_entity == "box");
  CHECK(hand.other_frame == "box");
  REQUIRE(hand.points.size() == 1);
  CHECK(near(hand.points[0], Eigen::Vector3d(0, 0, -0.05)));
  CHECK(near(hand.normal, Eigen::Vector3d(0, 0.6, 0.8)));  // [0, 3, 4] normalised
  CHECK(hand.friction == 0.5);
  CHECK(hand.generators == 6);
  CHECK_FALSE(hand.active);
  CHECK(hand.source.line == 43);
}

TEST_CASE("good_full.yaml: tasks", "[scene]") {
  const SceneSpec s = loadSceneFile(kScenes + "good_full.yaml");
  REQUIRE(s.tasks.size() == 8);

  const TaskSpec& posture = s.tasks[0];
  CHECK(posture.name == "posture");
  CHECK(posture.type == "posture");
  CHECK(posture.entities == std::vector<std::string>{"jvrc"});
  CHECK(posture.weight == 1.0);
  CHECK(posture.stiffness == 5.0);
  CHECK_FALSE(posture.damping.has_value());
  CHECK(posture.dims.empty());
  CHECK_FALSE(posture.target.has_value());
  CHECK(posture.posture_target == std::map<std::string, double>{{"NECK_Y", 0.2}, {"R_ELBOW_P", -1.0}});
  CHECK(posture.active);
  CHECK(posture.source.line == 54);

  const TaskSpec& com = s.tasks[1];
  CHECK(com.type == "com");
  CHECK(com.entities == std::vector<std::string>{"jvrc", "box"});
  CHECK(com.weight == 1.0);
  CHECK(com.stiffness == 10.0);
  CHECK(com.dims == std::vector<int>{1, 1, 0});
  REQUIRE(com.target.has_value());
  CHECK(near(*com.target, Eigen::Vector3d(0.1, 0.2, 0.7)));
  CHECK(com.source.line == 60);

  const TaskSpec& hand = s.tasks[2];
  CHECK(hand.type == "frame_position");
  CHECK(hand.entities == std::vector<std::string>{"jvrc"});
  CHECK(hand.frame == "R_WRIST_Y_S");
  CHECK(near(hand.point, Eigen::Vector3d(0, 0, -0.05)));
  CHECK(hand.weight == 10.0);
  CHECK(hand.stiffness == 20.0);
  REQUIRE(hand.damping.has_value());
  CHECK(*hand.damping == 9.0);
  CHECK_FALSE(hand.target.has_value());

  const TaskSpec& head = s.tasks[3];
  CHECK(head.type == "frame_orientation");
  CHECK(head.frame == "NECK_P_S");
  CHECK(near(head.point, Eigen::Vector3d::Zero()));
  REQUIRE(head.target.has_value());
  CHECK(near(*head.target, Eigen::Vector3d(0, 0.3, 0)));

  const TaskSpec& pose = s.tasks[4];
  CHECK(pose.type == "frame_pose");
  CHECK(pose.entities == std::vector<std::string>{"box"});
  CHECK(pose.frame == "box");
  CHECK(pose.weight == 100.0);
  CHECK(pose.dims == std::vector<int>{1, 1, 1, 1, 1, 1});
  REQUIRE(pose.target.has_value());
  Eigen::VectorXd pose_target(6);
  pose_target << 0.5, 0, 1.2, 0, 0, 0.5;
  CHECK(near(*pose.target, pose_target));
  CHECK_FALSE(pose.active);

  const TaskSpec& open = s.tasks[5];
  CHECK(open.type == "joint");
  CHECK(open.entities == std::vector<std::string>{"door"});
  CHECK(open.joint == "door");
  REQUIRE(open.target.has_value());
  CHECK(near(*open.target, Eigen::VectorXd::Constant(1, 0.8)));

  const TaskSpec& push = s.tasks[6];
  CHECK(push.type == "force");
  CHECK(push.entities.empty());
  CHECK(push.contact == "right_hand");
  REQUIRE(push.target.has_value());
  CHECK(near(*push.target, Eigen::Vector3d(0, 0, 15)));

  const TaskSpec& rest = s.tasks[7];
  CHECK(rest.type == "force_min");
  CHECK(rest.contact == "left_foot");
  CHECK(rest.weight == 0.01);
  CHECK(rest.dims.empty());
  CHECK_FALSE(rest.target.has_value());
  CHECK(rest.source.line == 96);
}

TEST_CASE("good_full.yaml: com dampers and joint inequalities", "[scene]") {
  const SceneSpec s = loadSceneFile(kScenes + "good_full.yaml");
  REQUIRE(s.com_dampers.size() == 1);
  const ComDamperSpec& d = s.com_dampers[0];
  CHECK(d.entity == "jvrc");
  CHECK(d.interaction == 0.06);
  CHECK(d.security == 0.02);
  CHECK(d.damping == 0.4);
  CHECK(d.source.line == 103);

  REQUIRE(s.joint_inequalities.size() == 2);
  const JointInequalitySpec& latch = s.joint_inequalities[0];
  CHECK(latch.name == "latch");
  REQUIRE(latch.terms.size() == 2);
  CHECK(latch.terms[0].entity == "door");
  CHECK(latch.terms[0].joint == "door");
  CHECK(latch.terms[0].coeff == 1.0);
  CHECK(latch.terms[1].joint == "handle");
  CHECK(latch.terms[1].coeff == 2.0);
  CHECK(latch.upper == 0.02);
  CHECK(latch.interaction == 0.05);
  CHECK(latch.security == 0.0);
  CHECK(latch.damping == 0.5);
  CHECK(latch.source.line == 106);

  const JointInequalitySpec& elbow = s.joint_inequalities[1];
  CHECK(elbow.name.empty());
  REQUIRE(elbow.terms.size() == 1);
  CHECK(elbow.terms[0].entity == "jvrc");
  CHECK(elbow.terms[0].joint == "R_ELBOW_P");
  CHECK(elbow.terms[0].coeff == 1.0);
  CHECK(elbow.upper == 0.0);
  CHECK(elbow.interaction == 0.05);
  CHECK(elbow.security == 0.0);
  CHECK(elbow.damping == 0.5);
  CHECK(elbow.source.line == 112);
}

TEST_CASE("a minimal scene takes every default", "[scene]") {
  const SceneSpec s = loadSceneString("entities: [{name: arm, model: panda}]\n", "mini.yaml");
  CHECK(s.file == "mini.yaml");
  CHECK(s.settings.dt == 0.001);
  CHECK(s.settings.duration == 5.0);
  CHECK(s.settings.max_tasks == 32);
  CHECK(s.settings.source.file == "mini.yaml");
  CHECK(s.settings.source.line == 1);
  REQUIRE(s.entities.size() == 1);
  CHECK(s.entities[0].actuation == "default");
  CHECK(s.entities[0].source.line == 1);
  CHECK(s.contacts.empty());
  CHECK(s.tasks.empty());
  CHECK(s.com_dampers.empty());
  CHECK(s.joint_inequalities.empty());
}

TEST_CASE("a force_min task without a contact covers every contact", "[scene]") {
  const SceneSpec s = loadSceneString(
      "entities: [{name: arm, model: panda}]\ntasks: [{name: rest, type: force_min}]\n", "m.yaml");
  REQUIRE(s.tasks.size() == 1);
  CHECK(s.tasks[0].type == "force_min");
  CHECK(s.tasks[0].contact.empty());
  CHECK(s.tasks[0].entities.empty());
  CHECK(s.tasks[0].source.line == 2);
}

TEST_CASE("file and YAML errors", "[scene]") {
  const std::string missing = kScenes + "no_such_scene.yaml";
  CHECK(errorOf(missing) == missing + ": cannot open: No such file or directory");
  CHECK_THAT(errorOf(kScenes + "bad"), StartsWith(kScenes + "bad: cannot open: "));
  const std::string syntax = kScenes + "bad/yaml_syntax.yaml";
  CHECK_THAT(errorOf(syntax), StartsWith(syntax + ":5: yaml: ") && Contains("flow"));
  CHECK(errorOfText("") == "mem.yaml:1: (top level): missing required field 'entities'");
  CHECK(errorOfText("[1, 2]") == "mem.yaml:1: (top level): expected a map, got a list of 2");
  CHECK_THAT(errorOfText("entities: [{name: a, model: b}]\n---\nentities: []\n"),
             StartsWith("mem.yaml:3: (top level): expected one YAML document"));
  CHECK(errorOfText("entities: []\n") == "mem.yaml:1: entities: expected at least one entity");
}

TEST_CASE("more checks of the values", "[scene]") {
  const std::string ent = "entities:\n  - {name: a, model: b}\n";
  CHECK(errorOfText("entities:\n  - {name: ground, model: b}\n") ==
        "mem.yaml:2: entities[0].name: 'ground' is reserved for the environment");
  CHECK(errorOfText(ent + "tasks:\n  - {name: t, type: joint, entity: a, joint: j, target: [1, 2]}\n") ==
        "mem.yaml:4: tasks[0].target: expected a list of 1 number, got a list of 2");
  CHECK(errorOfText(ent + "tasks:\n  - {name: t, type: force_min, contact: c, target: [0]}\n") ==
        "mem.yaml:4: tasks[0].target: not used by a force_min task");
  CHECK(errorOfText(ent + "tasks:\n  - {name: t, type: com, entity: a, entities: [a]}\n") ==
        "mem.yaml:4: tasks[0].entity: give either 'entity' or 'entities', not both");
  CHECK(errorOfText(ent + "tasks:\n  - {name: t, type: posture, entity: a, dims: []}\n") ==
        "mem.yaml:4: tasks[0].dims: expected at least one entry");
  CHECK(errorOfText(ent + "tasks:\n  - {name: t, type: com, entity: a, active: maybe}\n") ==
        "mem.yaml:4: tasks[0].active: expected true or false, got \"maybe\"");
  CHECK(errorOfText(ent + "contacts:\n  - {name: c, entity: a, frame: f, other: {entity: a, frame: f}, "
                          "points: [[0, 0, 0]]}\n") ==
        "mem.yaml:4: contacts[0].other: a frame cannot be in contact with itself");
  CHECK(errorOfText(ent + "com_dampers:\n  - {entity: a, security: 0.1}\n") ==
        "mem.yaml:4: com_dampers[0].security: expected a number < interaction (0.05), got 0.1");
  CHECK(errorOfText(ent + "com_dampers:\n  - {entity: a}\n  - {entity: a}\n") ==
        "mem.yaml:5: com_dampers[1].entity: duplicate com_damper for entity 'a' (first at line 4)");
  CHECK(errorOfText(ent + "joint_inequalities:\n  - {terms: [{entity: a, joint: j}]}\n") ==
        "mem.yaml:4: joint_inequalities[0]: missing required field 'upper'");
  CHECK(errorOfText("settings: {dt: 1e400}\n" + ent) ==
        "mem.yaml:1: settings.dt: expected a finite number, got 1e400");
}

TEST_CASE("every file under bad/ is rejected with FILE:LINE", "[scene]") {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenes + "bad")) {
    const std::string path = entry.path().string();
    INFO(path);
    CHECK_THAT(errorOf(path), StartsWith(path + ":"));
    ++files;
  }
  CHECK(files >= 15);
}

TEST_CASE("bad scene: task weight not number", "[scene]") {
  expectError("task_weight_not_number.yaml", 10, "tasks[2].weight", "expected a number >= 0, got \"abc\"");
}

TEST_CASE("bad scene: entity missing model", "[scene]") {
  expectError("entity_missing_model.yaml", 3, "entities[0]", "missing required field 'model'");
}

TEST_CASE("bad scene: task unknown key", "[scene]") {
  expectError("task_unknown_key.yaml", 8, "tasks[0].wieght", "unknown key");
}

TEST_CASE("bad scene: top unknown key", "[scene]") {
  expectError("top_unknown_key.yaml", 4, "constraints", "unknown key");
}

TEST_CASE("bad scene: number not finite", "[scene]") {
  expectError("number_not_finite.yaml", 6, "entities[0].pose.xyz[2]", "expected a finite number, got .nan");
}

TEST_CASE("bad scene: task negative stiffness", "[scene]") {
  expectError("task_negative_stiffness.yaml", 5, "tasks[0].stiffness", "expected a number >= 0, got -1");
}

TEST_CASE("bad scene: task negative damping", "[scene]") {
  expectError("task_negative_damping.yaml", 8, "tasks[0].damping", "expected a number >= 0, got -0.5");
}

TEST_CASE("bad scene: contact friction zero", "[scene]") {
  expectError("contact_friction_zero.yaml", 10, "contacts[0].friction", "expected a number > 0, got 0");
}

TEST_CASE("bad scene: contact generators range", "[scene]") {
  expectError("contact_generators_range.yaml", 10, "contacts[0].generators",
              "expected an integer in [3, 16], got 17");
}

TEST_CASE("bad scene: contact too many points", "[scene]") {
  expectError("contact_too_many_points.yaml", 9, "contacts[0].points",
              "expected a list of 1 to 8 points, got a list of 9");
}

TEST_CASE("bad scene: contact no points", "[scene]") {
  expectError("contact_no_points.yaml", 9, "contacts[0].points",
              "expected a list of 1 to 8 points, got a list of 0");
}

TEST_CASE("bad scene: contact point length", "[scene]") {
  expectError("contact_point_length.yaml", 11, "contacts[0].points[1]",
              "expected a list of 3 numbers, got a list of 2");
}

TEST_CASE("bad scene: contact zero normal", "[scene]") {
  expectError("contact_zero_normal.yaml", 10, "contacts[0].normal", "expected a non-zero vector");
}

TEST_CASE("bad scene: contact other unknown", "[scene]") {
  expectError("contact_other_unknown.yaml", 8, "contacts[0].other",
              "expected ground or a map {entity, frame}, got \"floor\"");
}

TEST_CASE("bad scene: contact other missing frame", "[scene]") {
  expectError("contact_other_missing_frame.yaml", 8, "contacts[0].other", "missing required field 'frame'");
}

TEST_CASE("bad scene: contact missing name", "[scene]") {
  expectError("contact_missing_name.yaml", 5, "contacts[0]", "missing required field 'name'");
}

TEST_CASE("bad scene: contact duplicate name", "[scene]") {
  expectError("contact_duplicate_name.yaml", 6, "contacts[1].name",
              "duplicate contact name 'foot' (first at line 5)");
}

TEST_CASE("bad scene: task dims length", "[scene]") {
  expectError("task_dims_length.yaml", 8, "tasks[0].dims", "expected 3 entries for a com task, got 2");
}

TEST_CASE("bad scene: task dims value", "[scene]") {
  expectError("task_dims_value.yaml", 11, "tasks[0].dims[1]", "expected 0 or 1, got 2");
}

TEST_CASE("bad scene: task target length", "[scene]") {
  expectError("task_target_length.yaml", 9, "tasks[0].target",
              "expected a list of 6 numbers, got a list of 3");
}

TEST_CASE("bad scene: task posture target list", "[scene]") {
  expectError("task_posture_target_list.yaml", 8, "tasks[0].target", "expected a map, got a list of 2");
}

TEST_CASE("bad scene: task unknown type", "[scene]") {
  expectError("task_unknown_type.yaml", 6, "tasks[0].type", "expected posture, com, frame_position");
}

TEST_CASE("bad scene: task key not used", "[scene]") {
  expectError("task_key_not_used.yaml", 8, "tasks[0].frame", "not used by a com task");
}

TEST_CASE("bad scene: task missing name", "[scene]") {
  expectError("task_missing_name.yaml", 5, "tasks[0]", "missing required field 'name'");
}

TEST_CASE("bad scene: task duplicate name", "[scene]") {
  expectError("task_duplicate_name.yaml", 8, "tasks[1].name", "duplicate task name 'com' (first at line 5)");
}

TEST_CASE("bad scene: entity duplicate name", "[scene]") {
  expectError("entity_duplicate_name.yaml", 5, "entities[1].name",
              "duplicate entity name 'jvrc' (first at line 2)");
}

TEST_CASE("bad scene: entity actuated without list", "[scene]") {
  expectError("entity_actuated_without_list.yaml", 5, "entities[0].actuated",
              "only used with actuation: list");
}

TEST_CASE("bad scene: entity spring negative damping", "[scene]") {
  expectError("entity_spring_negative_damping.yaml", 7, "entities[0].springs.handle.damping",
              "expected a number >= 0, got -0.1");
}

TEST_CASE("bad scene: object mass zero", "[scene]") {
  expectError("object_mass_zero.yaml", 4, "entities[0].mass", "expected a number > 0, got 0");
}

TEST_CASE("bad scene: object inertia not pd", "[scene]") {
  expectError("object_inertia_not_pd.yaml", 5, "entities[0].inertia", "not positive definite");
}

TEST_CASE("bad scene: object inertia length", "[scene]") {
  expectError("object_inertia_length.yaml", 5, "entities[0].inertia",
              "expected [ixx, iyy, izz] or [ixx, ixy, ixz, iyy, iyz, izz], got a list of 4");
}

TEST_CASE("bad scene: object joint key", "[scene]") {
  expectError("object_joint_key.yaml", 6, "entities[0].q", "not used by a rigid_object");
}

TEST_CASE("bad scene: settings dt zero", "[scene]") {
  expectError("settings_dt_zero.yaml", 3, "settings.dt", "expected a number > 0, got 0");
}

TEST_CASE("bad scene: settings duration negative", "[scene]") {
  expectError("settings_duration_negative.yaml", 1, "settings.duration", "expected a number > 0, got -4");
}

TEST_CASE("bad scene: settings capacity zero", "[scene]") {
  expectError("settings_capacity_zero.yaml", 2, "settings.max_contacts",
              "expected an integer in [1, 64], got 0");
}

TEST_CASE("bad scene: settings gravity length", "[scene]") {
  expectError("settings_gravity_length.yaml", 2, "settings.gravity",
              "expected a list of 3 numbers, got a list of 2");
}

TEST_CASE("bad scene: com damper order", "[scene]") {
  expectError("com_damper_order.yaml", 5, "com_dampers[0].interaction",
              "expected a number > security (0.02), got 0.01");
}

TEST_CASE("bad scene: com damper damping zero", "[scene]") {
  expectError("com_damper_damping_zero.yaml", 6, "com_dampers[0].damping", "expected a number > 0, got 0");
}

TEST_CASE("bad scene: joint inequality no terms", "[scene]") {
  expectError("joint_inequality_no_terms.yaml", 6, "joint_inequalities[0].terms",
              "expected at least one term");
}

TEST_CASE("bad scene: entities missing", "[scene]") {
  expectError("entities_missing.yaml", 1, "(top level)", "missing required field 'entities'");
}

TEST_CASE("bad scene: duplicate key", "[scene]") {
  expectError("duplicate_key.yaml", 4, "entities[0].model", "duplicate key (first at line 3)");
}
