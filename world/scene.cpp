#include "world/scene.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "base/error.hpp"
#include "base/json_file.hpp"
#include "world/model_cache.hpp"
#include "world/mujoco_errors.hpp"
#include "world/robot.hpp"
#include "world/static_mesh.hpp"

#ifndef CHORE_ASSETS_DIR
#define CHORE_ASSETS_DIR "assets"
#endif

namespace fs = std::filesystem;

namespace chore {

std::string default_assets_dir() {
  const char* env = std::getenv("CHORE_ASSETS");
  return (env && *env) ? env : CHORE_ASSETS_DIR;
}

namespace {

// Physics and rendering settings shared by every scene (seed: physics 1/120 s).
constexpr double kTimestep = 1.0 / 120.0;
constexpr double kExtent = 10.0;       // metres; sets the depth range with znear/zfar below
constexpr double kZNear = 0.005;       // near plane = 0.05 m
constexpr double kZFar = 5.0;          // far plane = 50 m, or beyond the overview camera's floor
constexpr double kCameraHeight = 1.1;  // the robot-less stand-in camera, like Tiago's head
const Rgb kWallColor = {0.86, 0.84, 0.80};

const Rgb kCeilingColor = {0.95, 0.95, 0.93};

double geom_volume(const GeomSpec& g) {
  const auto& s = g.size;
  if (g.type == "box") return 8 * s[0] * s[1] * s[2];
  if (g.type == "cylinder") return M_PI * s[0] * s[0] * 2 * s[1];
  if (g.type == "sphere") return 4.0 / 3.0 * M_PI * s[0] * s[0] * s[0];
  return M_PI * s[0] * s[0] * (2 * s[1] + 4.0 / 3.0 * s[0]);  // capsule
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string fmt(const Eigen::Vector3d& v) {
  return fmt(v[0]) + " " + fmt(v[1]) + " " + fmt(v[2]);
}

std::string fmt_quat(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  return fmt(q.w()) + " " + fmt(q.x()) + " " + fmt(q.y()) + " " + fmt(q.z());
}

std::string pose_attributes(const Eigen::Isometry3d& pose) {
  return "pos=\"" + fmt(Eigen::Vector3d(pose.translation())) + "\" quat=\"" + fmt_quat(pose.linear()) + "\"";
}

void add_to_static_mesh(StaticMesh& mesh, const Eigen::Isometry3d& world, const GeomSpec& g) {
  const Eigen::Isometry3d pose = world * g.pose;
  if (g.type == "box")
    mesh.add_box(pose, {g.size[0], g.size[1], g.size[2]}, g.rgb);
  else if (g.type == "cylinder")
    mesh.add_cylinder(pose, g.size[0], g.size[1], g.rgb);
  else if (g.type == "sphere")
    mesh.add_sphere(pose, g.size[0], g.rgb);
  else
    mesh.add_capsule(pose, g.size[0], g.size[1], g.rgb);
}

std::string size_attribute(const GeomSpec& g) {
  std::string s;
  for (size_t i = 0; i < g.size.size(); ++i) s += (i ? " " : "") + fmt(g.size[i]);
  return s;
}

// A geom element. `drawn`: the camera sees it (group 0); otherwise it is a
// collision-only geom of a static part whose look lives in the static mesh.
std::string geom_xml(const std::string& name, const GeomSpec& g, bool drawn, double mass) {
  std::string xml = "<geom name=\"" + name + "\" type=\"" + g.type + "\" size=\"" + size_attribute(g) + "\" " +
                    pose_attributes(g.pose);
  if (drawn) {
    xml += " class=\"object\" rgba=\"" + fmt(g.rgb[0]) + " " + fmt(g.rgb[1]) + " " + fmt(g.rgb[2]) + " 1\"";
  }
  if (mass > 0) xml += " mass=\"" + fmt(mass) + "\"";
  return xml + "/>";
}

// Emits a link's geoms; those of a fixed object's root go to the static mesh.
void emit_link_geoms(std::string& xml, StaticMesh& mesh, const std::string& prefix, const LinkSpec& link,
                     bool static_link, const Eigen::Isometry3d& world, const std::string& indent) {
  double volume = 0;
  for (const GeomSpec& g : link.geoms) volume += geom_volume(g);
  for (size_t i = 0; i < link.geoms.size(); ++i) {
    const GeomSpec& g = link.geoms[i];
    const std::string name = prefix + "/" + std::to_string(i);
    if (static_link) add_to_static_mesh(mesh, world, g);
    const double mass = static_link ? 0.0 : link.mass * geom_volume(g) / volume;
    xml += indent + geom_xml(name, g, !static_link, mass) + "\n";
  }
}

void emit_child_links(std::string& xml, std::string& welds, StaticMesh& mesh, const std::string& object,
                      const LinkSpec& parent, const Eigen::Isometry3d& parent_world, const std::string& indent) {
  for (const LinkSpec& link : parent.links) {
    const std::string name = object + "/" + link.name;
    Eigen::Isometry3d world = parent_world;
    world.translation() += parent_world.linear() * link.pos;
    xml += indent + "<body name=\"" + name + "\" pos=\"" + fmt(link.pos) + "\">\n";
    xml += indent + "  <joint name=\"" + name + "\" type=\"" + link.joint_type + "\" axis=\"" +
           fmt(link.axis.normalized()) + "\" range=\"" + fmt(link.range[0]) + " " + fmt(link.range[1]) +
           "\" limited=\"true\" damping=\"" + fmt(link.damping) + "\" armature=\"0.01\"/>\n";
    emit_link_geoms(xml, mesh, name, link, false, world, indent + "  ");
    emit_child_links(xml, welds, mesh, object, link, world, indent + "  ");
    xml += indent + "</body>\n";
    // The gripper can hold a drawer or door by its link (OmniGibson's assisted grasp does).
    welds += "    <weld name=\"grasp_" + name + "\" body1=\"gripper\" body2=\"" + name +
             "\" active=\"false\" solref=\"0.005 1\"/>\n";
  }
}

// A cloth's bodies are <object>B<i>_<j> (as MuJoCo 2.2.2's composite named them); its root is its centre.
std::string root_body_name(const std::string& object, const ObjectModel& model, bool cloth) {
  if (!model.cloth || !cloth) return object;
  const std::string c = std::to_string(model.cloth->count / 2);
  return object + "B" + c + "_" + c;
}

// A cloth: the body tree MuJoCo 2.2.2's <composite type="cloth"> made (MuJoCo
// 3 has no such composite), written out. It lies flat in the object's frame,
// just above its origin: the centre body is the root, a spine runs along x
// from it, and from each spine body a branch along y; each body hangs from
// its parent by two hinges, in-plane and about z. The grid's x edges that
// the tree leaves out are tendons that cannot stretch past the spacing
// (limits: MuJoCo's sleeping supports no tendon equality). Each body is a
// capsule, drawn and colliding (a skin costs ~2 ms per frame on llvmpipe, a
// geom ~30 us and is culled out of view), laid along x and y in a
// checkerboard as the composite laid them.
struct ClothXml {
  std::string bodies;   // the root's contents and its subtree
  std::string tendons;  // <tendon> children
};

ClothXml cloth_xml(const std::string& name, const ClothSpec& c, double mass) {
  const double per_body = mass / (c.count * c.count);
  const int centre = c.count / 2;
  // Inertia of a flat square plate, a side of `spacing`, 1% of it thick.
  const double side = c.spacing, thick = 0.01 * c.spacing;
  const double flat = per_body * (side * side + thick * thick) / 12, normal = per_body * 2 * side * side / 12;
  const auto body_name = [&](int i, int j) { return name + "B" + std::to_string(i) + "_" + std::to_string(j); };
  const auto suffix = [&](int i, int j) { return std::to_string(i) + "_" + std::to_string(j); };
  const auto contents = [&](int i, int j, const std::string& indent) {
    const char* along = (i + j) % 2 ? "0.707107 0.707107 0 0" : "0.5 0.5 0.5 0.5";
    return indent + "<inertial pos=\"0 0 0\" mass=\"" + fmt(per_body) + "\" diaginertia=\"" + fmt(flat) + " " +
           fmt(flat) + " " + fmt(normal) + "\"/>\n" + indent + "<geom name=\"" + name + "G" + suffix(i, j) +
           "\" type=\"capsule\" size=\"" + fmt(c.radius) + " " + fmt(c.spacing * 0.4) + "\" quat=\"" + along +
           "\" mass=\"0\" group=\"" + std::to_string(kStaticGroup) +
           // contype 4, conaffinity 3: tiles touch the scene (1) and the robot (2), not each other.
           "\" contype=\"4\" conaffinity=\"3\" rgba=\"" + fmt(c.rgb[0]) + " " + fmt(c.rgb[1]) + " " + fmt(c.rgb[2]) +
           " 1\" friction=\"0.8 0.02 0.001\"/>\n" + indent + "<site name=\"" + name + "S" + suffix(i, j) +
           "\" group=\"3\"/>\n";
  };
  // A child (i, j) one spacing along `axis` (0: x, 1: y) in direction `sign` from its parent.
  const auto open_child = [&](int i, int j, int axis, int sign, const std::string& indent) {
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    offset[axis] = sign * c.spacing;
    const char* bend = axis == 0 ? "0 1 0" : "1 0 0";
    std::string xml = indent + "<body name=\"" + body_name(i, j) + "\" pos=\"" + fmt(offset) + "\">\n";
    const std::string hinge = "\" pos=\"" + fmt(Eigen::Vector3d(-offset)) + "\" group=\"3\" damping=\"0.01\" armature=\"0.0005\"/>\n";
    xml += indent + "  <joint name=\"" + name + "J0_" + suffix(i, j) + "\" axis=\"" + bend + hinge;
    xml += indent + "  <joint name=\"" + name + "J1_" + suffix(i, j) + "\" axis=\"0 0 1" + hinge;
    return xml + contents(i, j, indent + "  ");
  };
  // The branch along y from spine body (i, centre), into `xml` at `indent`.
  const auto branch = [&](int i, const std::string& indent) {
    std::string xml;
    for (const int sign : {1, -1}) {
      std::string close;
      std::string in = indent;
      for (int j = centre + sign; j >= 0 && j < c.count; j += sign) {
        xml += open_child(i, j, 1, sign, in);
        close = in + "</body>\n" + close;
        in += "  ";
      }
      xml += close;
    }
    return xml;
  };
  ClothXml out;
  const std::string root_indent = "      ";
  out.bodies = contents(centre, centre, root_indent) + branch(centre, root_indent);
  for (const int sign : {1, -1}) {
    std::string close;
    std::string in = root_indent;
    for (int i = centre + sign; i >= 0 && i < c.count; i += sign) {
      out.bodies += open_child(i, centre, 0, sign, in) + branch(i, in + "  ");
      close = in + "</body>\n" + close;
      in += "  ";
    }
    out.bodies += close;
  }
  for (int j = 0; j < c.count; ++j) {
    if (j == centre) continue;
    for (int i = 0; i + 1 < c.count; ++i) {
      out.tendons += "    <spatial name=\"" + name + "T" + suffix(i, j) + "\" group=\"3\" limited=\"true\" range=\"0 " +
                     fmt(c.spacing) + "\">\n      <site site=\"" + name + "S" + suffix(i, j) +
                     "\"/>\n      <site site=\"" + name + "S" + suffix(i + 1, j) + "\"/>\n    </spatial>\n";
    }
  }
  return out;
}

std::string resolve_scene_path(const std::string& name, const std::string& assets) {
  if (name.ends_with(".json") || name.find('/') != std::string::npos) {
    if (!fs::exists(name)) throw Error("scene file '" + name + "' does not exist");
    return name;
  }
  const fs::path path = fs::path(assets) / "scenes" / (name + ".json");
  if (fs::exists(path)) return path.string();
  std::string known;
  if (fs::is_directory(fs::path(assets) / "scenes")) {
    for (const auto& entry : fs::directory_iterator(fs::path(assets) / "scenes")) {
      if (entry.path().extension() == ".json") {
        known += (known.empty() ? "" : ", ") + entry.path().stem().string();
      }
    }
  }
  throw Error("unknown scene '" + name + "' (no " + path.string() +
              "); known scenes: " + (known.empty() ? "none" : known));
}

// The scene file places each object touching what it stands on; MuJoCo's
// soft contacts rest a little into it, and only a contact that is there
// counts (onfloor, ontop). So the objects are let fall into their resting
// poses once, when the model is compiled (then cached): from the model's
// reference pose, with the robot colliding with nothing, each tree steps
// until MuJoCo puts it to sleep (at most kSettleSeconds), and the joints of
// those that slept take their pose as the reference (qpos0) that every reset
// starts from. One still moving then (dropped from a height, or pressed into
// another) keeps the pose it was placed in.
constexpr double kSettleSeconds = 2.0;

void settle_placed_objects(mjModel* m, const std::vector<char>& object_root, int robot_root) {
  const auto of_object = [&](int body) { return object_root[m->body_rootid[body]] != 0; };
  bool any = false;
  for (int t = 0; t < m->ntree; ++t) any |= of_object(m->tree_bodyadr[t]);
  if (!any || !(m->opt.enableflags & mjENBL_SLEEP)) return;
  std::vector<std::pair<int, int>> collisions(m->ngeom);  // contype, conaffinity
  for (int g = 0; g < m->ngeom; ++g) {
    collisions[g] = {m->geom_contype[g], m->geom_conaffinity[g]};
    if (m->body_rootid[m->geom_bodyid[g]] == robot_root) m->geom_contype[g] = m->geom_conaffinity[g] = 0;
  }
  mjData* d = mj_makeData(m);
  if (!d) throw Error("scene: out of memory to settle the objects");
  const auto all_asleep = [&] {
    for (int t = 0; t < m->ntree; ++t) {
      if (of_object(m->tree_bodyadr[t]) && d->tree_asleep[t] < 0) return false;
    }
    return true;
  };
  const int steps = static_cast<int>(std::lround(kSettleSeconds / m->opt.timestep));
  for (int k = 0; k < steps && !all_asleep(); ++k) mj_step(m, d);
  for (int j = 0; j < m->njnt; ++j) {
    const int body = m->jnt_bodyid[j];
    if (!of_object(body) || d->tree_asleep[m->body_treeid[body]] < 0) continue;
    const int size = m->jnt_type[j] == mjJNT_FREE ? 7 : m->jnt_type[j] == mjJNT_BALL ? 4 : 1;
    std::copy_n(d->qpos + m->jnt_qposadr[j], size, m->qpos0 + m->jnt_qposadr[j]);
  }
  mj_deleteData(d);
  for (int g = 0; g < m->ngeom; ++g) std::tie(m->geom_contype[g], m->geom_conaffinity[g]) = collisions[g];
}

}  // namespace

std::shared_ptr<const Scene> Scene::load(const std::string& name, const SceneOptions& options) {
  const std::string assets = options.assets_dir.empty() ? default_assets_dir() : options.assets_dir;
  return build(read_scene_file(resolve_scene_path(name, assets), assets), options);
}

std::shared_ptr<const Scene> Scene::build(const SceneFile& file, const SceneOptions& options) {
  install_mujoco_handlers();
  const std::string assets = options.assets_dir.empty() ? default_assets_dir() : options.assets_dir;
  const std::string& path = file.path;
  std::shared_ptr<Scene> scene(new Scene());
  scene->name_ = file.name;
  scene->path_ = path;
  scene->has_robot_ = options.robot;
  scene->rooms_ = file.rooms;
  scene->robot_start_ = file.robot_start;

  const double wall_height = file.wall_height, wall_thickness = file.wall_thickness;
  StaticMesh mesh("static_visual", kMergedGroup);
  // Ceilings in their own group, so that views from above can leave them out.
  StaticMesh ceilings("ceiling_visual", kCeilingGroup);
  std::string world;  // <worldbody> children
  std::string welds;  // <equality> children
  std::string lights;
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);

  // Rooms: floor slabs (collision + static look) and ceilings (look only).
  for (const Room& room : file.rooms) {
    for (size_t k = 0; k < room.rects.size(); ++k) {
      const auto& v = room.rects[k];
      lo = lo.cwiseMin(Eigen::Vector2d(v[0], v[1]));
      hi = hi.cwiseMax(Eigen::Vector2d(v[2], v[3]));
      Eigen::Isometry3d floor = Eigen::Isometry3d::Identity();
      const Eigen::Vector3d half((v[2] - v[0]) / 2, (v[3] - v[1]) / 2, 0.05);
      floor.translation() = Eigen::Vector3d((v[0] + v[2]) / 2, (v[1] + v[3]) / 2, -0.05);
      mesh.add_box(floor, half, room.floor_rgb);
      world += "    <geom name=\"floor_" + room.name + "_" + std::to_string(k) + "\" type=\"box\" size=\"" + fmt(half) +
               "\" pos=\"" + fmt(Eigen::Vector3d(floor.translation())) + "\"/>\n";
      Eigen::Isometry3d ceiling = floor;
      ceiling.translation().z() = wall_height + 0.05;
      ceilings.add_box(ceiling, half, kCeilingColor);
    }
  }

  for (size_t i = 0; i < file.walls.size(); ++i) {
    const auto& w = file.walls[i];
    const Eigen::Vector2d a(w[0], w[1]), b(w[2], w[3]);
    const double length = (b - a).norm();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d((a.x() + b.x()) / 2, (a.y() + b.y()) / 2, wall_height / 2);
    pose.linear() =
        Eigen::AngleAxisd(std::atan2(b.y() - a.y(), b.x() - a.x()), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    // Extended by half a thickness at both ends so corners close.
    const Eigen::Vector3d half((length + wall_thickness) / 2, wall_thickness / 2, wall_height / 2);
    mesh.add_box(pose, half, kWallColor);
    world += "    <geom name=\"wall_" + std::to_string(i) + "\" type=\"box\" size=\"" + fmt(half) + "\" " +
             pose_attributes(pose) + "/>\n";
  }

  for (size_t i = 0; i < file.ceiling_lights.size(); ++i) {
    const Rgb& rgb = file.ceiling_lights[i].rgb;
    lights += "    <light name=\"ceiling_" + std::to_string(i) + "\" pos=\"" + fmt(file.ceiling_lights[i].pos) +
              "\" dir=\"0 0 -1\" directional=\"false\" castshadow=\"false\" cutoff=\"85\" "
              "exponent=\"1\" attenuation=\"1 0 0\" diffuse=\"" +
              fmt(rgb[0]) + " " + fmt(rgb[1]) + " " + fmt(rgb[2]) + "\" specular=\"0.1 0.1 0.1\"/>\n";
  }

  // Objects.
  std::vector<std::string> holder_bodies;        // per object: its root body's name, or "world"
  std::vector<char> in_world_body;              // per object: its geoms are the world body's
  std::vector<std::optional<ClothSpec>> cloths;  // per object: its cloth, if simulated
  std::string static_geoms;                      // the world body's furniture
  std::vector<std::string> static_roots;         // fixed objects with moving parts: their static roots
  // Bodies that move: cloths, fixed objects' links, free objects.
  std::string cloth_bodies, free_bodies, linked_bodies, cloth_tendons;
  for (const ObjectPlacement& placement : file.objects) {
    const auto found = file.models.find(placement.model);
    if (found == file.models.end()) {
      throw Error(path + ": object '" + placement.name + "': no model '" + placement.model + "'");
    }
    const ObjectModel& model = found->second;
    SceneObject object;
    object.name = placement.name;
    object.model = placement.model;
    object.category = model.category;
    object.synset = placement.synset;
    object.fixed = placement.fixed;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = placement.pos;
    pose.linear() = Eigen::AngleAxisd(placement.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();

    if (model.cloth) pose.translation().z() += model.cloth->radius;  // capsules rest on the support
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(object.mat.data()) = pose.linear();
    Eigen::Map<Eigen::Vector3d>(object.pos.data()) = pose.translation();
    if (model.light) {
      lights += "    <light name=\"lamp_" + object.name + "\" pos=\"" + fmt(Eigen::Vector3d(pose * model.light->pos)) +
                "\" dir=\"0 0 -1\" directional=\"false\" castshadow=\"false\" cutoff=\"90\" "
                "exponent=\"0\" attenuation=\"1 0 0.2\" diffuse=\"" +
                fmt(model.light->rgb[0]) + " " + fmt(model.light->rgb[1]) + " " + fmt(model.light->rgb[2]) +
                "\" specular=\"0.1 0.1 0.1\"/>\n";
    }
    if (object.fixed && !model.cloth && model.root.links.empty()) {
      // Furniture without moving parts: its geoms, posed in the world, are
      // the world body's (MuJoCo's midphase finds the few near a moving body).
      for (size_t g = 0; g < model.root.geoms.size(); ++g) {
        GeomSpec placed = model.root.geoms[g];
        placed.pose = pose * placed.pose;
        add_to_static_mesh(mesh, Eigen::Isometry3d::Identity(), placed);
        static_geoms += "    " + geom_xml(object.name + "/" + std::to_string(g), placed, false, 0) + "\n";
      }
      holder_bodies.push_back("world");
      in_world_body.push_back(1);
      cloths.emplace_back();
      scene->objects_.push_back(std::move(object));
      continue;
    }
    const std::string body = root_body_name(object.name, model, options.cloth);
    holder_bodies.push_back(body);
    in_world_body.push_back(0);
    cloths.push_back(model.cloth && options.cloth ? model.cloth : std::nullopt);
    std::string& world = model.cloth ? cloth_bodies : object.fixed ? linked_bodies : free_bodies;
    world += "    <body name=\"" + body + "\" " + pose_attributes(pose) + ">\n";
    if (!object.fixed) {
      world += "      <freejoint name=\"" + object.name + "\"/>\n";
      welds += "    <weld name=\"grasp_" + object.name + "\" body1=\"gripper\" body2=\"" + body +
               "\" active=\"false\" solref=\"0.005 1\"/>\n";
    } else {
      static_roots.push_back(body);
    }
    if (model.cloth && options.cloth) {
      const ClothXml cloth = cloth_xml(object.name, *model.cloth, model.root.mass);
      world += cloth.bodies;
      cloth_tendons += cloth.tendons;
    } else if (model.cloth) {
      // Cloth simulation off: one rigid tile of the cloth's size.
      const ClothSpec& c = *model.cloth;
      GeomSpec tile;
      tile.type = "box";
      tile.size = {c.count * c.spacing / 2, c.count * c.spacing / 2, c.radius};
      tile.rgb = c.rgb;
      world += "      " + geom_xml(object.name + "/0", tile, true, model.root.mass) + "\n";
    } else {
      emit_link_geoms(world, mesh, object.name, model.root, object.fixed, pose, "      ");
      emit_child_links(world, welds, mesh, object.name, model.root, pose, "      ");
    }
    world += "    </body>\n";
    scene->objects_.push_back(std::move(object));
  }

  world += cloth_bodies + linked_bodies + free_bodies;
  // What never moves is the world body's: the furniture's geoms and the drawn
  // static meshes; the pairs among it and the roots of fixed objects with
  // moving parts are excluded.
  const std::string statics = static_geoms + mesh.mjcf_geom() + ceilings.mjcf_geom();
  std::vector<std::string> unmoving = {"world"};
  unmoving.insert(unmoving.end(), static_roots.begin(), static_roots.end());
  std::string excludes;
  for (size_t a = 0; a < unmoving.size(); ++a) {
    for (size_t b = a + 1; b < unmoving.size(); ++b) {
      excludes += "    <exclude body1=\"" + unmoving[a] + "\" body2=\"" + unmoving[b] + "\"/>\n";
    }
  }

  // Cameras: a top-down overview, and a stand-in for the head camera when the
  // robot is left out.
  const Eigen::Vector2d center = (lo + hi) / 2, span = hi - lo;
  const double overview_height = wall_height + 0.5 * std::max(span.x(), span.y()) / std::tan(30.0 * M_PI / 180.0);
  world += "    <camera name=\"overview\" pos=\"" + fmt(Eigen::Vector3d(center.x(), center.y(), overview_height)) +
           "\" xyaxes=\"1 0 0 0 1 0\" fovy=\"60\"/>\n";
  const double zfar = std::max(kZFar, 1.1 * overview_height / kExtent);  // a large garden's floor in view
  if (!options.robot) {
    const Pose2& p = scene->robot_start_;
    world += "    <camera name=\"scene_camera\" pos=\"" + fmt(Eigen::Vector3d(p.x, p.y, kCameraHeight)) +
             "\" xyaxes=\"" + fmt(std::sin(p.yaw)) + " " + fmt(-std::cos(p.yaw)) + " 0 0 0 1\" fovy=\"58\"/>\n";
  }

  // <size memory>: MuJoCo's arena, where each step's contacts and constraint
  // rows go. malloc'd and never cleared whole, it costs the memory of what a
  // step uses, not of its size (docs/benchmarks.md): with sleeping, the
  // contacts of what is awake. Its size is room for every object at rest on
  // something awake at once (a reset puts the scene's objects to sleep after
  // one step of them all: MuJoCo's sleep="init"), ~32 KB each.
  const long arena_mb = 64 + (32L * scene->objects_.size()) / 1024;
  std::string xml = "<mujoco model=\"" + scene->name_ +
                    "\">\n"
                    "  <compiler angle=\"radian\" autolimits=\"true\" fusestatic=\"false\"/>\n"
                    "  <option timestep=\"" +
                    fmt(kTimestep) +
                    "\" integrator=\"Euler\" solver=\"Newton\" "
                    "iterations=\"30\" tolerance=\"1e-6\">\n"
                    "    <flag sleep=\"enable\"/>\n"
                    "  </option>\n"
                    "  <size memory=\"" +
                    std::to_string(arena_mb) +
                    "M\"/>\n"
                    "  <visual>\n"
                    "    <global offwidth=\"128\" offheight=\"128\" fovy=\"58\"/>\n"
                    "    <quality shadowsize=\"0\" offsamples=\"0\"/>\n"
                    "    <map znear=\"" +
                    fmt(kZNear) + "\" zfar=\"" + fmt(zfar) +
                    "\"/>\n"
                    "    <headlight ambient=\"0.25 0.25 0.25\" diffuse=\"0 0 0\" specular=\"0 0 0\"/>\n"
                    "  </visual>\n"
                    "  <statistic extent=\"" +
                    fmt(kExtent) + "\" center=\"" + fmt(Eigen::Vector3d(center.x(), center.y(), 1.0)) +
                    "\"/>\n"
                    "  <default>\n"
                    "    <geom contype=\"1\" conaffinity=\"1\" group=\"" +
                    std::to_string(kCollisionGroup) +
                    "\" friction=\"0.8 0.02 0.001\"/>\n"
                    "    <default class=\"visual\"><geom contype=\"0\" conaffinity=\"0\" group=\"" +
                    std::to_string(kStaticGroup) +
                    "\" mass=\"0\"/></default>\n"
                    "    <default class=\"object\"><geom group=\"" +
                    std::to_string(kStaticGroup) +
                    "\"/></default>\n"
                    "  </default>\n"
                    "  <asset>\n" +
                    mesh.mjcf_assets() + ceilings.mjcf_assets() + "  </asset>\n";
  // The robot first: its bodies and degrees of freedom are the model's first.
  if (options.robot) {
    const std::string robot_path = (fs::path(assets) / "robots" / "tiago.xml").string();
    xml += robot_mjcf_children(read_text_file(robot_path, kMaxMjcfBytes, "a robot file"), robot_path);
  }
  xml += "  <worldbody>\n" + lights + world + "  </worldbody>\n";
  if (!excludes.empty()) xml += "  <contact>\n" + excludes + "  </contact>\n";
  if (!cloth_tendons.empty()) xml += "  <tendon>\n" + cloth_tendons + "  </tendon>\n";
  // Attachments: a weld each, from the object's body to what it attaches to.
  std::string attach_welds;
  std::vector<std::pair<int, int>> attached;  // object indices, in weld order
  const auto index_of = [&](const std::string& name) {
    for (size_t i = 0; i < scene->objects_.size(); ++i) {
      if (scene->objects_[i].name == name) return static_cast<int>(i);
    }
    throw Error(path + ": attachment names no object '" + name + "'");
  };
  for (const chore::Attachment& a : file.attachments) {
    const int object = index_of(a.object), to = index_of(a.to);
    if (in_world_body[object] || object == to) continue;  // welded to the world already
    attach_welds += "    <weld name=\"attach_" + std::to_string(attached.size()) + "\" body1=\"" + holder_bodies[to] +
                    "\" body2=\"" + holder_bodies[object] + "\" active=\"false\" solref=\"0.005 1\"/>\n";
    attached.push_back({object, to});
  }
  if (!attach_welds.empty()) xml += "  <equality>\n" + attach_welds + "  </equality>\n";
  if (options.robot) {
    if (!welds.empty()) xml += "  <equality>\n" + welds + "  </equality>\n";
  }
  xml += "  <worldbody>\n" + statics + "  </worldbody>\n</mujoco>\n";
  scene->mjcf_ = xml;

  const auto object_roots = [&](const mjModel* m) {
    std::vector<char> root(m->nbody, 0);
    for (size_t i = 0; i < holder_bodies.size(); ++i) {
      if (!in_world_body[i]) root[mj_name2id(m, mjOBJ_BODY, holder_bodies[i].c_str())] = 1;
    }
    return root;
  };
  mjModel* model = load_mjcf_cached(xml, path + ": MuJoCo rejected the compiled scene", options.model_cache,
                                    &scene->from_cache_,
                                    [&](mjModel* m) {
                                      const int robot = options.robot ? mj_name2id(m, mjOBJ_BODY, "robot") : -1;
                                      settle_placed_objects(m, object_roots(m), robot);
                                    });
  scene->model_ = model;  // owned from here: ~Scene frees it on any later error
  mesh.paint_palette(model);
  ceilings.paint_palette(model);

  std::vector<int> root_object(model->nbody, -1);
  std::map<std::string, int, std::less<>> static_object;  // name -> index, furniture in the world body
  for (size_t i = 0; i < scene->objects_.size(); ++i) {
    SceneObject& object = scene->objects_[i];
    const int body = mj_name2id(model, mjOBJ_BODY, holder_bodies[i].c_str());
    if (in_world_body[i]) {
      static_object[object.name] = static_cast<int>(i);
    } else {
      object.body = body;
      root_object[body] = static_cast<int>(i);
    }
  }
  // Objects are children of the world: their links share the root body.
  scene->body_object_.resize(model->nbody);
  for (int b = 0; b < model->nbody; ++b) scene->body_object_[b] = root_object[model->body_rootid[b]];
  // The scene's objects rest where they settled: each reset puts them to sleep
  // (MuJoCo's sleep="init": after one step of them all, islands that touch
  // nothing awake sleep), where a tree may sleep at all (MuJoCo's compiler
  // keeps trees with actuators, the robot's, awake).
  for (int t = 0; t < model->ntree; ++t) {
    if (model->tree_sleep_policy[t] == mjSLEEP_AUTO_ALLOWED &&
        scene->body_object_[model->tree_bodyadr[t]] >= 0) {
      model->tree_sleep_policy[t] = mjSLEEP_INIT;
    }
  }
  // The world body's furniture geoms are named "<object>/<index>".
  scene->geom_object_.resize(model->ngeom);
  for (int g = 0; g < model->ngeom; ++g) {
    int& object = scene->geom_object_[g] = scene->body_object_[model->geom_bodyid[g]];
    const char* name = mj_id2name(model, mjOBJ_GEOM, g);
    if (object < 0 && name && model->geom_bodyid[g] == 0) {
      const std::string_view n(name);
      const auto it = static_object.find(n.substr(0, n.find('/')));
      if (it != static_object.end()) object = it->second;
    }
    const bool collides = model->geom_contype[g] || model->geom_conaffinity[g];
    if (collides && object >= 0) scene->objects_[object].geoms.push_back(g);
  }
  for (size_t i = 0; i < scene->objects_.size(); ++i) {
    SceneObject& object = scene->objects_[i];
    if (const auto& cloth = cloths[i]) {
      const std::string last = std::to_string(cloth->count - 1);
      for (const std::string& corner : {std::string("0_0"), "0_" + last, last + "_0", last + "_" + last}) {
        object.keypoints.push_back(mj_name2id(model, mjOBJ_BODY, (object.name + "B" + corner).c_str()));
      }
      object.flat_diagonal = (cloth->count - 1) * cloth->spacing * std::sqrt(2.0);
    }
    if (options.robot && !object.fixed) {
      object.grasp_weld = mj_name2id(model, mjOBJ_EQUALITY, ("grasp_" + object.name).c_str());
    }
    for (int jnt = 0; jnt < model->njnt; ++jnt) {
      const char* jname = mj_id2name(model, mjOBJ_JOINT, jnt);
      if (jname && std::string_view(jname).starts_with(object.name + "/")) {
        object.joints.push_back(jnt);
        object.link_welds.push_back(
            options.robot ? mj_name2id(model, mjOBJ_EQUALITY, ("grasp_" + std::string(jname)).c_str()) : -1);
      }
    }
  }
  for (size_t k = 0; k < attached.size(); ++k) {
    const int weld = mj_name2id(model, mjOBJ_EQUALITY, ("attach_" + std::to_string(k)).c_str());
    scene->attachments_.push_back({attached[k].first, attached[k].second, weld});
  }
  for (const Room& room : scene->rooms_) {
    std::vector<int> floors;
    for (size_t k = 0; k < room.rects.size(); ++k) {
      floors.push_back(mj_name2id(model, mjOBJ_GEOM, ("floor_" + room.name + "_" + std::to_string(k)).c_str()));
    }
    scene->floor_geoms_.push_back(std::move(floors));
  }
  for (int l = 0; l < model->nlight; ++l) {
    const char* lname = mj_id2name(model, mjOBJ_LIGHT, l);
    if (lname && std::string_view(lname).starts_with("ceiling_")) scene->ceiling_lights_.push_back(l);
  }
  scene->overview_camera_ = mj_name2id(model, mjOBJ_CAMERA, "overview");
  scene->camera_ = mj_name2id(model, mjOBJ_CAMERA, options.robot ? "head_camera" : "scene_camera");
  if (scene->camera_ < 0) throw Error(path + ": the robot has no camera named 'head_camera'");
  return scene;
}

Scene::~Scene() {
  if (model_) mj_deleteModel(model_);
}

const SceneObject* Scene::find_object(std::string_view name) const {
  for (const SceneObject& o : objects_) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

const Room* Scene::room_at(double x, double y) const {
  for (const Room& room : rooms_) {
    for (const auto& r : room.rects) {
      if (x >= r[0] && x <= r[2] && y >= r[1] && y <= r[3]) return &room;
    }
  }
  return nullptr;
}

}  // namespace chore
