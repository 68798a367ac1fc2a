#include "analogs/category_models.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <mutex>
#include <set>
#include <vector>

#include "base/csv_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/json_file.hpp"
#include "world/scene.hpp"

namespace chore {
namespace {

// Median annotated mass per synset, from BEHAVIOR's category table (columns
// "synset" and "mass (auto)"; "2,000.000" is 2000 kg; blank: not annotated).
std::map<std::string, double> read_masses(const std::string& path) {
  const CsvTable table = read_csv_file(path);
  const size_t synset_column = table.column("synset"), mass_column = table.column("mass (auto)");
  std::map<std::string, std::vector<double>> all;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::string& cell = table.rows[r][mass_column];
    std::string text = cell;
    std::erase(text, ',');
    if (text.empty()) continue;
    double mass = 0;
    try {
      size_t used = 0;
      mass = std::stod(text, &used);
      if (used != text.size()) throw std::invalid_argument(text);
    } catch (const std::exception&) {
      throw Error(table.where(r) + ": mass '" + cell + "' is not a number");
    }
    within(table.where(r) + ": mass", mass, 1e-4, 1e5);
    all[table.rows[r][synset_column]].push_back(mass);
  }
  std::map<std::string, double> median;
  for (auto& [synset, masses] : all) {
    std::sort(masses.begin(), masses.end());
    median[synset] = masses[masses.size() / 2];
  }
  return median;
}

// A hue per synset: FNV-1a of its name, spread over the circle, at one of
// three saturation/value pairs (more categories than hues tell apart).
Rgb hashed_colour(const std::string& synset) {
  const uint64_t hash = fnv1a(synset);
  const double hue = static_cast<double>(hash % 3600) / 10.0;
  static const double shades[3][2] = {{0.55, 0.80}, {0.70, 0.60}, {0.35, 0.90}};
  const double s = shades[(hash / 3600) % 3][0], v = shades[(hash / 3600) % 3][1];
  const double c = v * s, h = hue / 60.0, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
  const int sector = static_cast<int>(h) % 6;
  const double rgb[6][3] = {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}};
  return {rgb[sector][0] + m, rgb[sector][1] + m, rgb[sector][2] + m};
}

Rgb shade(const Rgb& rgb, double factor) {
  return {rgb[0] * factor, rgb[1] * factor, rgb[2] * factor};
}

GeomSpec box(const Eigen::Vector3d& half, const Eigen::Vector3d& centre, const Rgb& rgb) {
  GeomSpec g;
  g.type = "box";
  g.size = {half.x(), half.y(), half.z()};
  g.pose.translation() = centre;
  g.rgb = rgb;
  return g;
}

// An open-topped box of outer size `s` whose floor stands at z0: a floor and
// four walls `t` thick (containers, basins, drawers).
void add_tray(std::vector<GeomSpec>& geoms, const Eigen::Vector3d& s, double z0, double t, const Rgb& rgb) {
  geoms.push_back(box({s.x() / 2, s.y() / 2, t / 2}, {0, 0, z0 + t / 2}, rgb));
  const double wall = (s.z() - t) / 2, zc = z0 + t + wall;
  for (double side : {-1.0, 1.0}) {
    geoms.push_back(box({s.x() / 2, t / 2, wall}, {0, side * (s.y() - t) / 2, zc}, rgb));
    geoms.push_back(box({t / 2, s.y() / 2 - t, wall}, {side * (s.x() - t) / 2, 0, zc}, rgb));
  }
}

constexpr double kShelfPitch = 0.6;  // m between shelves behind a cabinet's door

// A drawer where the cabinet is wider than tall, else a door; an appliance
// (a microwave, an oven) opens with a door whatever its shape.
LinkSpec cabinet(const Eigen::Vector3d& size, double mass, const Rgb& rgb, bool appliance, double inner_height) {
  const double t = 0.02;
  const Eigen::Vector3d s = size.cwiseMax(0.15);  // room for a carcass, a drawer or a door
  const bool drawer = s.x() > s.z() && !appliance;
  // A drawer kDrawerHeight deep (or as deep as what goes in it) over a solid
  // carcass: what lies in it is within an arm's reach from above once it is
  // pulled out (a drawer the cabinet's height kept it 4 cm above the floor).
  // Its top no higher than kHighestDrawer, solid above: a car's, 1.5 m up,
  // had its handle beyond the arm.
  // Behind a door of one space (an oven, a kitchen's base cabinet: 0.6-1.2 m
  // tall), the bottom halfway up, where a base cabinet's shelf was, as on a
  // plinth; lower where what goes in needs the room: an arm reaching in
  // through the door does not get to the floor. (A fridge keeps its: under
  // its 0.6 m shelf, a space 0.3 m high was out of the hand's reach in 25
  // activities.)
  constexpr double kDrawerHeight = 0.3, kHighestDrawer = 1.0;
  const double depth = std::max(kDrawerHeight, inner_height);
  const double top = drawer ? std::min(s.z() - t, std::max(kHighestDrawer, depth + 2 * t)) : s.z() - t;
  const bool one_space = s.z() >= kShelfPitch && s.z() < 2 * kShelfPitch;
  const double raised = one_space ? std::min(s.z() / 2, s.z() - 2 * t - inner_height) : t;
  const double below = drawer ? std::max(t, top - t - depth) : std::max(t, raised);  // carcass
  const double tray_height = top - t - below;
  LinkSpec root;
  root.mass = mass;
  auto& g = root.geoms;
  g.push_back(box({s.x() / 2, s.y() / 2 - t / 2, below / 2}, {0, t / 2, below / 2}, rgb));  // bottom
  if (top < s.z() - t - 1e-9) {                                                             // above a drawer
    g.push_back(box({s.x() / 2, s.y() / 2 - t / 2, (s.z() - t - top) / 2}, {0, t / 2, (top + s.z() - t) / 2}, rgb));
  }
  g.push_back(box({s.x() / 2, s.y() / 2 - t / 2, t / 2}, {0, t / 2, s.z() - t / 2}, rgb));          // top
  g.push_back(box({s.x() / 2 - t, t / 2, s.z() / 2 - t}, {0, s.y() / 2 - t / 2, s.z() / 2}, rgb));  // back
  for (double side : {-1.0, 1.0}) {
    g.push_back(box({t / 2, s.y() / 2 - t / 2, s.z() / 2 - t}, {side * (s.x() - t) / 2, t / 2, s.z() / 2}, rgb));
  }
  if (!drawer) {
    // Shelves about 0.6 m apart (a fridge's at 0.6 and 1.2 m), none within
    // half that of the bottom (a kitchen's base cabinet keeps one space):
    // what is inside need not lie on the bottom. (What is too tall for a
    // level stands on the bottom.)
    const int levels = static_cast<int>(std::lround(s.z() / kShelfPitch));
    for (int k = 1; k < levels; ++k) {
      const double z = k * s.z() / levels;
      if (z >= below + kShelfPitch / 2) {
        g.push_back(box({s.x() / 2 - t, s.y() / 2 - 1.5 * t, t / 2}, {0, t / 2, z}, shade(rgb, 1.1)));
      }
    }
  }
  LinkSpec front;
  front.mass = std::max(0.2, mass * 0.1);
  if (drawer) {  // sliding out towards -y
    front.name = "drawer";
    front.joint_type = "slide";
    front.axis = {0, -1, 0};
    // Out by most of its depth, but no more than an arm standing before it
    // reaches into (a car's, 4.5 m deep, needed 3.2 m of floor behind the
    // robot pulling it).
    constexpr double kLongestPull = 0.6;
    front.range[1] = std::min(0.8 * s.y(), kLongestPull);
    front.pos = {0, 0, below};
    const Eigen::Vector3d tray(s.x() - 2.5 * t, s.y() - 2 * t, tray_height);
    add_tray(front.geoms, tray, 0, t, shade(rgb, 0.9));
    const double panel = (tray_height + t) / 2;  // half its height
    front.geoms.push_back(box({s.x() / 2 - t, t / 2, panel}, {0, -s.y() / 2 + t / 2, panel}, shade(rgb, 1.15)));
  } else {  // a door hinged on its left edge, swinging out
    front.name = "door";
    front.joint_type = "hinge";
    front.axis = {0, 0, -1};
    front.range[1] = 100.0 * M_PI / 180.0;
    front.pos = {-s.x() / 2, -s.y() / 2, t};
    front.geoms.push_back(
        box({s.x() / 2 - 0.002, t / 2, s.z() / 2 - t}, {s.x() / 2, -t / 2, s.z() / 2 - t}, shade(rgb, 1.15)));
  }
  root.links.push_back(front);
  return root;
}

LinkSpec door(const Eigen::Vector3d& s, double mass, const Rgb& rgb) {
  LinkSpec root;  // the lintel above the opening; the leaf swings on the left jamb
  root.mass = mass * 0.2;
  root.geoms.push_back(box({s.x() / 2, s.y() / 2, 0.03}, {0, 0, s.z() + 0.03}, shade(rgb, 0.8)));
  LinkSpec leaf;
  leaf.name = "leaf";
  leaf.joint_type = "hinge";
  leaf.axis = {0, 0, -1};
  leaf.range[1] = 100.0 * M_PI / 180.0;
  leaf.pos = {-s.x() / 2, 0, 0};
  leaf.mass = mass * 0.8;
  leaf.geoms.push_back(box({s.x() / 2 - 0.005, s.y() / 2, s.z() / 2 - 0.01}, {s.x() / 2, 0, s.z() / 2}, rgb));
  root.links.push_back(leaf);
  return root;
}

LinkSpec table(const Eigen::Vector3d& s, double mass, const Rgb& rgb) {
  LinkSpec root;
  root.mass = mass;
  const double top = std::min(0.04, s.z() * 0.1), leg = std::min(0.03, 0.1 * std::min(s.x(), s.y()));
  root.geoms.push_back(box({s.x() / 2, s.y() / 2, top / 2}, {0, 0, s.z() - top / 2}, rgb));
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      root.geoms.push_back(box({leg, leg, (s.z() - top) / 2},
                               {sx * (s.x() / 2 - 2 * leg), sy * (s.y() / 2 - 2 * leg), (s.z() - top) / 2},
                               shade(rgb, 0.7)));
    }
  }
  return root;
}

LinkSpec seat(const Eigen::Vector3d& s, double mass, const Rgb& rgb) {
  LinkSpec root;
  root.mass = mass;
  const double height = s.z() > 0.65 ? std::min(0.47, 0.55 * s.z()) : s.z(), cushion = std::min(0.15, 0.4 * height);
  root.geoms.push_back(box({s.x() / 2, s.y() / 2, cushion / 2}, {0, 0, height - cushion / 2}, rgb));
  root.geoms.push_back(box({s.x() / 2 - 0.03, s.y() / 2 - 0.03, (height - cushion) / 2}, {0, 0, (height - cushion) / 2},
                           shade(rgb, 0.7)));
  if (s.z() > 0.65) {  // a back
    const double back = std::min(0.12, 0.2 * s.y());
    root.geoms.push_back(
        box({s.x() / 2, back / 2, (s.z() - height) / 2}, {0, s.y() / 2 - back / 2, (s.z() + height) / 2}, rgb));
  }
  return root;
}

LinkSpec bed(const Eigen::Vector3d& s, double mass, const Rgb& rgb) {
  LinkSpec root;
  root.mass = mass;
  const double mattress = std::min(0.55, 0.6 * s.z());
  root.geoms.push_back(box({s.x() / 2, s.y() / 2, mattress / 2}, {0, 0, mattress / 2}, rgb));
  root.geoms.push_back(box({s.x() / 2, 0.04, s.z() / 2}, {0, s.y() / 2 - 0.04, s.z() / 2}, shade(rgb, 0.7)));
  return root;
}

constexpr double kBoard = 0.02;  // m: a shelf's boards and sides

LinkSpec shelf(const Eigen::Vector3d& s, double mass, const Rgb& rgb) {
  LinkSpec root;
  root.mass = mass;
  const double t = kBoard;
  for (double side : {-1.0, 1.0})
    root.geoms.push_back(box({t / 2, s.y() / 2, s.z() / 2}, {side * (s.x() - t) / 2, 0, s.z() / 2}, rgb));
  root.geoms.push_back(box({s.x() / 2 - t, t / 2, s.z() / 2}, {0, s.y() / 2 - t / 2, s.z() / 2}, rgb));
  for (const double top : shelf_boards(s).tops) {
    root.geoms.push_back(box({s.x() / 2 - t, s.y() / 2 - t / 2, t / 2}, {0, -t / 2, top - t / 2}, shade(rgb, 1.1)));
  }
  return root;
}

// A container's or a basin's walls: thinner for smaller ones.
double wall_thickness(const Eigen::Vector3d& size) {
  return std::clamp(0.08 * std::min(size.x(), size.y()), 0.003, 0.03);
}

LinkSpec container(const Eigen::Vector3d& size, double mass, const Rgb& rgb, bool lidded) {
  LinkSpec root;
  const double t = wall_thickness(size);
  const Eigen::Vector3d s(size.x(), size.y(), std::max(size.z(), 4 * t));  // a floor, walls and a lid
  root.mass = mass;
  add_tray(root.geoms, {s.x(), s.y(), lidded ? s.z() - t : s.z()}, 0, t, rgb);
  if (lidded) {  // hinged on the back top edge, opening upwards
    LinkSpec lid;
    lid.name = "lid";
    lid.joint_type = "hinge";
    lid.axis = {-1, 0, 0};
    lid.range[1] = 110.0 * M_PI / 180.0;
    lid.pos = {0, s.y() / 2, s.z() - t};
    lid.mass = std::max(0.01, mass * 0.15);
    lid.geoms.push_back(box({s.x() / 2, s.y() / 2, t / 2}, {0, -s.y() / 2, t / 2}, shade(rgb, 1.15)));
    root.links.push_back(lid);
  }
  return root;
}

// A scene's basin (a sink, a bathtub): a solid stand, and on it an open box
// kBasinDepth deep (or as deep as what goes in it), so that what lies in it is
// within an arm's reach from above (a sink 0.9 m deep to the floor kept its
// dirt, and what lay in it, out of every reach).
LinkSpec basin(const Eigen::Vector3d& size, double mass, const Rgb& rgb, double inner_height) {
  constexpr double kBasinDepth = 0.3;
  const double depth = std::max(kBasinDepth, inner_height);
  if (size.z() <= depth) return container(size, mass, rgb, false);
  LinkSpec root;
  root.mass = mass;
  const double stand = size.z() - depth;
  root.geoms.push_back(box({size.x() / 2, size.y() / 2, stand / 2}, {0, 0, stand / 2}, shade(rgb, 0.9)));
  const double t = wall_thickness(size);
  add_tray(root.geoms, {size.x(), size.y(), depth}, stand, t, rgb);
  return root;
}

LinkSpec ball(const Eigen::Vector3d& s, double mass, const Rgb& rgb) {
  LinkSpec root;
  root.mass = mass;
  const double r = s.minCoeff() / 2;
  GeomSpec sphere;
  sphere.type = "sphere";
  sphere.size = {r};
  sphere.pose.translation() = Eigen::Vector3d(0, 0, r);
  sphere.rgb = rgb;
  root.geoms.push_back(sphere);
  root.geoms.push_back(box({0.4 * r, 0.4 * r, 0.003}, {0, 0, 0.003}, rgb));  // a flat spot: it does not roll away
  return root;
}

}  // namespace

const char* to_string(Archetype a) {
  static const char* const names[] = {"cloth", "cabinet",          "basin",          "door", "table", "seat", "bed",
                                      "shelf", "lidded_container", "open_container", "ball", "block"};
  return names[static_cast<int>(a)];
}

ShelfBoards shelf_boards(const Eigen::Vector3d& size) {
  const double t = kBoard;
  const int boards = std::clamp(static_cast<int>(size.z() / 0.35), 1, 8);
  ShelfBoards out;
  for (int b = 0; b <= boards; ++b) out.tops.push_back(std::min(size.z(), t + b * (size.z() - t) / boards));
  out.clearance = (size.z() - t) / boards - t;
  return out;
}

std::shared_ptr<const CategoryModels> CategoryModels::load(std::shared_ptr<const KnowledgeBase> kb,
                                                           const std::string& size_table,
                                                           const std::string& mass_table) {
  std::shared_ptr<CategoryModels> models(new CategoryModels());
  models->kb_ = std::move(kb);
  const nlohmann::json sizes = read_json_file(size_table);
  const JsonReader table = JsonReader(sizes, size_table).at("sizes");
  if (!sizes["sizes"].is_object()) table.fail("expected an object of synsets");
  for (const auto& [synset, value] : sizes["sizes"].items()) {
    const JsonReader entry = table.at(synset.c_str());
    if (!models->kb_->contains(synset)) entry.fail(models->kb_->unknown(synset));
    const std::vector<double> size = entry.numbers("size", 3, Bounds{0.002, 50.0});
    models->sizes_[synset] = {{size[0], size[1], size[2]}, entry.number("mass", {1e-4, 1e5})};
  }
  if (!models->sizes_.contains("entity.n.01")) table.fail("no entry for the root, entity.n.01");
  models->masses_ = read_masses(mass_table);
  return models;
}

std::shared_ptr<const CategoryModels> CategoryModels::shipped() {
  static std::once_flag once;
  static std::shared_ptr<const CategoryModels> models;
  std::call_once(once, [] {
    models = load(KnowledgeBase::load(default_tasks_dir() + "/kb/behavior-1k"),
                  default_assets_dir() + "/analogs/category_sizes.json",
                  default_tasks_dir() + "/kb/behavior-1k/category_mapping.csv");
  });
  return models;
}

void CategoryModels::check_object(const std::string& synset) const {
  if (!kb_->contains(synset)) throw Error(kb_->unknown(synset));
  if (kb_->is_substance(synset)) throw Error("'" + synset + "' is a substance, not an object");
}

std::string CategoryModels::size_entry(const std::string& synset) const {
  check_object(synset);
  // Breadth first up the parents: the nearest ancestor with an entry (ties:
  // the first in name order, as parents() lists them).
  std::deque<std::string> queue = {synset};
  std::set<std::string> seen = {synset};
  while (!queue.empty()) {
    const std::string s = queue.front();
    queue.pop_front();
    if (sizes_.contains(s)) return s;
    for (const std::string& p : kb_->parents(s)) {
      if (seen.insert(p).second) queue.push_back(p);
    }
  }
  return "entity.n.01";
}

Eigen::Vector3d CategoryModels::size(const std::string& synset) const {
  const std::string entry = size_entry(synset);
  const SizeEntry& e = sizes_.at(entry);
  const auto own = masses_.find(synset);
  if (entry == synset || own == masses_.end()) return e.size;
  return e.size * std::clamp(std::cbrt(own->second / e.mass), 0.5, 2.0);
}

double CategoryModels::mass(const std::string& synset) const {
  check_object(synset);
  const auto own = masses_.find(synset);
  return own != masses_.end() ? own->second : sizes_.at(size_entry(synset)).mass;
}

Rgb CategoryModels::colour(const std::string& synset) const {
  check_object(synset);
  return hashed_colour(synset);
}

Archetype CategoryModels::archetype(const std::string& synset) const {
  check_object(synset);
  const KnowledgeBase& kb = *kb_;
  auto is = [&](const char* ancestor) { return kb.contains(ancestor) && kb.is_a(synset, ancestor); };
  if (kb.has_property(synset, "cloth") || kb.has_property(synset, "drapeable")) return Archetype::cloth;
  if (is("door.n.01")) return Archetype::door;
  const bool openable = kb.is_openable(synset), fillable = kb.has_property(synset, "fillable");
  if (kb.has_property(synset, "sceneObject")) {
    if (openable) return Archetype::cabinet;
    // (A bookcase holds things on shelves, not in a basin 1.8 m deep; so does
    // what holds things and stands taller than wide and than a basin's stand
    // keeps within an arm's reach: a grocery store's shelves and open
    // fridges, a wardrobe. A basin on a 1.5 m stand held their contents out
    // of reach.)
    constexpr double kTallestBasin = 1.2;
    const Eigen::Vector3d s = size(synset);
    const bool tall = s.z() > kTallestBasin && s.z() > std::max(s.x(), s.y());
    if (is("shelf.n.01") || is("bookcase.n.01") || (fillable && tall)) return Archetype::shelf;
    if (fillable) return Archetype::basin;
    if (is("seat.n.03")) return Archetype::seat;
    if (is("bed.n.01")) return Archetype::bed;
    if (is("table.n.02") || is("desk.n.01")) return Archetype::table;
    return Archetype::block;
  }
  if (openable && size(synset).maxCoeff() > 0.6) return Archetype::cabinet;  // appliances, wardrobes
  if (openable) return Archetype::lidded_container;
  if (fillable) return Archetype::open_container;
  if (is("seat.n.03")) return Archetype::seat;
  if (is("table.n.02")) return Archetype::table;
  if (is("edible_fruit.n.01") || is("ball.n.01")) return Archetype::ball;
  return Archetype::block;
}

ObjectModel CategoryModels::model(const std::string& synset) const {
  return model(synset, size(synset));
}

ObjectModel CategoryModels::model(const std::string& synset, const Eigen::Vector3d& s, double inner_height) const {
  const Archetype a = archetype(synset);
  const double m = mass(synset);
  const Rgb rgb = colour(synset);
  ObjectModel model;
  model.synset = synset;
  model.category = synset.substr(0, synset.find('.'));
  switch (a) {
    case Archetype::cloth: {
      ClothSpec cloth;
      cloth.spacing = 0.06;
      cloth.count = std::clamp(2 * static_cast<int>(std::max(s.x(), s.y()) / cloth.spacing / 2) + 1, 3, 9);
      cloth.spacing = std::max(s.x(), s.y()) / cloth.count;
      cloth.radius = std::clamp(0.1 * cloth.spacing, 0.003, 0.01);
      cloth.rgb = rgb;
      model.cloth = cloth;
      model.root.mass = m;
      break;
    }
    case Archetype::cabinet:
      model.root = cabinet(
          s, m, rgb, knowledge_base().contains("appliance.n.02") && knowledge_base().is_a(synset, "appliance.n.02"),
          inner_height);
      break;
    case Archetype::basin:
      model.root = basin(s, m, rgb, inner_height);
      break;
    case Archetype::door:
      model.root = door(s, m, rgb);
      break;
    case Archetype::table:
      model.root = table(s, m, rgb);
      break;
    case Archetype::seat:
      model.root = seat(s, m, rgb);
      break;
    case Archetype::bed:
      model.root = bed(s, m, rgb);
      break;
    case Archetype::shelf:
      model.root = shelf(s, m, rgb);
      break;
    case Archetype::lidded_container:
    case Archetype::open_container:
      model.root = container(s, m, rgb, a == Archetype::lidded_container);
      break;
    case Archetype::ball:
      model.root = ball(s, m, rgb);
      break;
    case Archetype::block:
      model.root.mass = m;
      model.root.geoms.push_back(box(s / 2, {0, 0, s.z() / 2}, rgb));
      break;
  }
  return model;
}

}  // namespace chore
