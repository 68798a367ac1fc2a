#include "analogs/scene_analogs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#include "base/csv_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/json_file.hpp"
#include "base/random.hpp"
#include "tasks/knowledge_base.hpp"
#include "world/robot.hpp"
#include "world/scene.hpp"

namespace chore {
namespace {

// TYPE_INDEX: lowercase letters and underscores, '_', digits ("living_room_1").
bool is_room_name(const std::string& room) {
  const size_t underscore = room.rfind('_');
  if (underscore == std::string::npos || underscore == 0 || underscore + 1 == room.size()) return false;
  const auto in = [](char c, char low, char high) { return c >= low && c <= high; };
  return std::all_of(room.begin(), room.begin() + underscore, [&](char c) { return in(c, 'a', 'z') || c == '_'; }) &&
         std::all_of(room.begin() + underscore + 1, room.end(), [&](char c) { return in(c, '0', '9'); });
}

constexpr double kWall = 0.1;        // wall thickness (m)
constexpr double kDoorway = 1.2;     // width of a doorway: the base passes with its margin
constexpr double kDoorClear = 1.0;   // kept free before a doorway, on each side
constexpr double kGap = 0.05;        // between neighbouring pieces of furniture
constexpr double kRobotClear = 0.5;  // around the robot's start
// Floor kept clear where the robot stands to reach a piece of furniture (its
// base is 0.6 m across; 0.7 leaves room to turn), and how deep into a top
// the arm reaches from there (1 m from the base's centre at table height,
// which stands 0.3 m off the edge).
constexpr double kAisle = 0.7;
// Before what opens (a cabinet, a fridge, a car): room to stand and pull a
// drawer out or swing a door (a car's drawer 0.6 m out, the robot 0.5-0.9 m
// before its handle, left no room in 1.35 m of a garage's floor).
constexpr double kOpeningAisle = 1.3;
constexpr double kReachDepth = 0.6;
constexpr double kHeadroom = 0.5;  // m kept between furniture's top and a wall item above it
// A wall item shorter than this (a nail, a hook, a switch) hangs with its
// centre at kWallItemHeight, where the hand, level, reaches it (at 1.4 m, as
// larger items' centres are, the arm does not), unless something hangs on it
// from the start (AnalogExtras::holding_at_start).
constexpr double kSmallWallItem = 0.3;
constexpr double kWallItemHeight = 1.15;
constexpr int kTries = 60;           // random placements tried per object
constexpr double kCounterTop = 0.6;  // m: an appliance lower than this stands on a surface
constexpr int kAttachments = 64;     // weld pairs per pair of synsets an activity attaches

// An axis-aligned rectangle of the floor.
struct Rect {
  double x0, y0, x1, y1;
  bool overlaps(const Rect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  Rect grown(double m) const { return {x0 - m, y0 - m, x1 + m, y1 + m}; }
  double width() const { return x1 - x0; }
  double depth() const { return y1 - y0; }
};

// The category models at their sizes in this scene: a synset's own (or that
// of the synset the caller models it as), no taller than the greatest height
// and grown to the least size the caller asks of it.
struct Models {
  const CategoryModels& models;
  const AnalogExtras& extras;

  const std::string& resolve(const std::string& synset) const {
    const auto as = extras.modelled_as.find(synset);
    return as == extras.modelled_as.end() ? synset : as->second;
  }
  Eigen::Vector3d size(const std::string& synset) const {
    const auto least = extras.least_sizes.find(synset);
    const auto greatest = extras.greatest_heights.find(synset);
    Eigen::Vector3d s = models.size(resolve(synset));
    if (greatest != extras.greatest_heights.end()) s.z() = std::min(s.z(), greatest->second);
    return least == extras.least_sizes.end() ? s : s.cwiseMax(least->second);
  }
  ObjectModel model(const std::string& synset) const {
    const auto inner = extras.least_inner_heights.find(synset);
    ObjectModel m =
        models.model(resolve(synset), size(synset), inner == extras.least_inner_heights.end() ? 0.0 : inner->second);
    m.synset = synset;
    return m;
  }
  Archetype archetype(const std::string& synset) const { return models.archetype(resolve(synset)); }
  // Whether the knowledge base's `ancestor` is one of what `synset` is modelled as.
  bool is_a(const std::string& synset, const std::string& ancestor) const {
    const KnowledgeBase& kb = models.knowledge_base();
    return kb.contains(ancestor) && kb.is_a(resolve(synset), ancestor);
  }
  bool has_property(const std::string& synset, const char* property) const {
    return models.knowledge_base().has_property(resolve(synset), property);
  }
};

// What an inventory object is to the layout.
// Ground (lawns, driveways) is furniture a hand's breadth high: an object of
// the scene BDDL places things on, a slab over part of its room's floor.
enum class Kind { structure, ground, door, on_wall, furniture, small };
bool stands_on_floor(Kind kind) {
  return kind == Kind::furniture || kind == Kind::ground;
}

Kind kind_of(const Models& models, const std::string& synset) {
  const auto is = [&](const char* ancestor) { return models.is_a(synset, ancestor); };
  // Floors, walls and ceilings are the scene's own.
  for (const char* s : {"floor.n.01", "ceiling.n.01", "wall.n.01"}) {
    if (is(s)) return Kind::structure;
  }
  if (is("lawn.n.01") || is("driveway.n.01")) return Kind::ground;
  if (is("door.n.01")) return Kind::door;
  for (const char* s : {"window.n.01", "picture.n.01", "mirror.n.01", "switch.n.01", "wall_socket.n.01",
                        "wall_clock.n.01", "towel_rack.n.01", "poster.n.01", "wall_nail.n.01"}) {
    if (is(s)) return Kind::on_wall;
  }
  if (!models.has_property(synset, "sceneObject")) return Kind::small;
  // A kitchen appliance lower than a counter (a microwave, a toaster) is a
  // fixture that stands on one; ovens and stoves stand on the floor.
  return is("kitchen_appliance.n.01") && models.size(synset).z() < kCounterTop ? Kind::small : Kind::furniture;
}

// A model's footprint half-extents at a yaw that is a multiple of 90 degrees.
Eigen::Vector2d half_footprint(const Eigen::Vector3d& size, int quarter_turns) {
  return quarter_turns % 2 == 0 ? Eigen::Vector2d(size.x() / 2, size.y() / 2)
                                : Eigen::Vector2d(size.y() / 2, size.x() / 2);
}

Rect footprint(const Eigen::Vector2d& centre, const Eigen::Vector2d& half) {
  return {centre.x() - half.x(), centre.y() - half.y(), centre.x() + half.x(), centre.y() + half.y()};
}

Rgb floor_colour(const std::string& type) {
  const uint64_t hash = fnv1a(type);
  const double t = static_cast<double>(hash % 1000) / 1000.0;
  return {0.45 + 0.3 * t, 0.4 + 0.2 * (1 - t), 0.35 + 0.15 * t};
}

// One room of the layout: its rectangle, doorways, and what stands in it.
struct RoomLayout {
  const RoomInventory* inventory;
  Rect rect;
  std::vector<Rect> keep_clear;  // before doorways
  std::vector<Rect> taken;       // footprints of what stands on the floor
  std::vector<double> heights;   // and its heights
  std::vector<Rect> aisles;      // floor the robot reaches furniture from (may overlap each other)
  struct Surface {
    Rect top;
    double height;
    std::vector<Rect> taken;
    int turns;                                                   // of the furniture it tops: its front faces the room
    double clearance = std::numeric_limits<double>::infinity();  // m up to the board above (a shelf's)
  };
  std::vector<Surface> surfaces;
  // Stretches of wall free for wall items: per side (0 bottom, 1 right, 2 top, 3 left), intervals used.
  std::vector<std::pair<double, double>> wall_used[4];

  bool free(const Rect& r, bool flat = false) const {
    const Rect inner = rect.grown(-kWall / 2);
    if (r.x0 < inner.x0 || r.y0 < inner.y0 || r.x1 > inner.x1 || r.y1 > inner.y1) return false;
    for (const Rect& o : keep_clear)
      if (o.overlaps(r)) return false;
    for (const Rect& o : taken)
      if (o.grown(kGap).overlaps(r)) return false;
    for (const Rect& o : aisles)
      if (!flat && o.overlaps(r)) return false;
    return true;
  }
  // Whether an aisle can be kept: inside the room, on no furniture.
  bool can_keep(const Rect& aisle) const {
    const Rect inner = rect.grown(-kWall / 2);
    if (aisle.x0 < inner.x0 || aisle.y0 < inner.y0 || aisle.x1 > inner.x1 || aisle.y1 > inner.y1) return false;
    return std::none_of(taken.begin(), taken.end(), [&](const Rect& o) { return o.grown(kGap).overlaps(aisle); });
  }
};

// Room areas from their furniture, then rows of one width: a rectangle of rooms.
// The room an extra object goes in: by name, else by type; "" the first.
size_t room_of(const SceneInventory& inventory, const ExtraObject& e) {
  if (e.room.empty()) return 0;
  for (int by_type = 0; by_type < 2; ++by_type) {
    for (size_t r = 0; r < inventory.rooms.size(); ++r) {
      if ((by_type ? inventory.rooms[r].type : inventory.rooms[r].name) == e.room) return r;
    }
  }
  throw Error("scene " + inventory.name + ": no room '" + e.room + "' for " + e.synset);
}

bool is_furniture(const Models& models, const ExtraObject& e) {
  return !e.loose && stands_on_floor(kind_of(models, e.synset));
}

std::vector<RoomLayout> lay_out_rooms(const SceneInventory& inventory, const std::vector<ExtraObject>& extra,
                                      const Models& models, Rng& rng) {
  std::vector<RoomLayout> rooms;
  std::vector<Eigen::Vector2d> sizes;
  double total = 0;
  for (size_t r = 0; r < inventory.rooms.size(); ++r) {
    const RoomInventory& room = inventory.rooms[r];
    double footprint_area = 0;  // of each piece and the aisle along its long side
    auto add_footprint = [&](const std::string& synset, int count) {
      const Eigen::Vector3d s = models.size(synset);
      footprint_area += count * ((s.x() + kGap) * (s.y() + kGap) + kAisle * std::max(s.x(), s.y()));
    };
    for (const auto& [synset, count] : room.objects) {
      if (stands_on_floor(kind_of(models, synset))) add_footprint(synset, count);
    }
    for (const ExtraObject& e : extra) {
      if (is_furniture(models, e) && room_of(inventory, e) == r) add_footprint(e.synset, 1);
    }
    const double area = std::max(6.0, 3.0 * footprint_area + 4.0), aspect = uniform(rng, 1.0, 1.5);
    sizes.push_back({std::sqrt(area * aspect), std::sqrt(area / aspect)});
    total += area;
    rooms.push_back({&room, {}, {}, {}, {}, {}});
  }
  double width = std::sqrt(total) * 1.2;
  for (const Eigen::Vector2d& s : sizes) width = std::max(width, s.x());
  // Rows left to right; a row's rooms share its depth and its last room is
  // widened to the common width.
  double y = 0;
  for (size_t first = 0; first < rooms.size();) {
    size_t last = first;
    double x = sizes[first].x(), depth = sizes[first].y();
    while (last + 1 < rooms.size() && x + sizes[last + 1].x() <= width) {
      ++last;
      x += sizes[last].x();
      depth = std::max(depth, sizes[last].y());
    }
    double x0 = 0;
    for (size_t i = first; i <= last; ++i) {
      const double x1 = i == last ? width : x0 + sizes[i].x();
      rooms[i].rect = {x0, y, x1, y + depth};
      x0 = x1;
    }
    y += depth;
    first = last + 1;
  }
  return rooms;
}

// A doorway on the wall between rooms a and b (sharing a vertical edge when
// `vertical`) at `along` (y or x), kept clear on both sides.
struct Doorway {
  int a, b;
  bool vertical;
  double at, along;  // the shared edge's x (vertical) or y; the doorway's centre along it
};

std::vector<Doorway> doorways(std::vector<RoomLayout>& rooms) {
  std::vector<Doorway> doors;
  for (size_t i = 0; i + 1 < rooms.size(); ++i) {
    const Rect &a = rooms[i].rect, &b = rooms[i + 1].rect;
    if (a.y0 == b.y0 && a.x1 == b.x0) doors.push_back({int(i), int(i + 1), true, a.x1, (a.y0 + a.y1) / 2});
  }
  // Each row's first room to the room of the row before that shares the most wall with it.
  for (size_t i = 1; i < rooms.size(); ++i) {
    const Rect& r = rooms[i].rect;
    if (r.x0 != 0 || r.y0 == 0) continue;
    int best = -1;
    double best_overlap = 0;
    for (size_t j = 0; j < i; ++j) {
      const Rect& o = rooms[j].rect;
      const double overlap = std::min(r.x1, o.x1) - std::max(r.x0, o.x0);
      if (o.y1 == r.y0 && overlap > best_overlap) best = int(j), best_overlap = overlap;
    }
    if (best < 0 || best_overlap < kDoorway + 2 * kWall) continue;
    const Rect& o = rooms[best].rect;
    doors.push_back({best, int(i), false, r.y0, (std::max(r.x0, o.x0) + std::min(r.x1, o.x1)) / 2});
  }
  for (const Doorway& d : doors) {
    const double half = kDoorway / 2 + kGap;
    const Rect clear = d.vertical ? Rect{d.at - kDoorClear, d.along - half, d.at + kDoorClear, d.along + half}
                                  : Rect{d.along - half, d.at - kDoorClear, d.along + half, d.at + kDoorClear};
    rooms[d.a].keep_clear.push_back(clear);
    rooms[d.b].keep_clear.push_back(clear);
  }
  return doors;
}

// Wall segments of every room's sides, with the doorways cut out.
std::vector<std::array<double, 4>> walls(const std::vector<RoomLayout>& rooms, const std::vector<Doorway>& doors) {
  std::vector<std::array<double, 4>> segments;
  auto add = [&](double x0, double y0, double x1, double y1, bool vertical) {
    // Gaps of the doorways on this line, in order along it.
    std::vector<std::pair<double, double>> gaps;
    for (const Doorway& d : doors) {
      if (d.vertical != vertical) continue;
      if (std::abs(d.at - (vertical ? x0 : y0)) > 1e-9) continue;
      gaps.push_back({d.along - kDoorway / 2, d.along + kDoorway / 2});
    }
    std::sort(gaps.begin(), gaps.end());
    double from = vertical ? y0 : x0;
    const double to = vertical ? y1 : x1;
    for (const auto& [g0, g1] : gaps) {
      if (g1 <= from || g0 >= to) continue;
      if (g0 > from) segments.push_back(vertical ? std::array{x0, from, x0, g0} : std::array{from, y0, g0, y0});
      from = std::max(from, g1);
    }
    if (to > from) segments.push_back(vertical ? std::array{x0, from, x0, to} : std::array{from, y0, to, y0});
  };
  for (const RoomLayout& room : rooms) {
    const Rect& r = room.rect;
    add(r.x0, r.y0, r.x1, r.y0, false);
    add(r.x0, r.y1, r.x1, r.y1, false);
    add(r.x0, r.y0, r.x0, r.y1, true);
    add(r.x1, r.y0, r.x1, r.y1, true);
  }
  return segments;
}

class Builder {
 public:
  Builder(const Models& models, SceneAnalog& out) : models_(models), out_(out) {}

  // Adds an instance of `synset`: model once per synset, a BDDL-style name.
  void add(const std::string& synset, const Eigen::Vector3d& pos, int quarter_turns, bool fixed) {
    if (!out_.file.models.contains(synset)) out_.file.models[synset] = models_.model(synset);
    add(synset, synset, pos, quarter_turns, fixed);
  }
  // Adds an instance with a model of its own (a room's floor), under `key`.
  void add(const std::string& key, ObjectModel model, const Eigen::Vector3d& pos) {
    const std::string synset = model.synset;
    out_.file.models[key] = std::move(model);
    add(synset, key, pos, 0, true);
  }

 private:
  void add(const std::string& synset, const std::string& model, const Eigen::Vector3d& pos, int quarter_turns,
           bool fixed) {
    const std::string category = synset.substr(0, synset.find('.'));
    ObjectPlacement p;
    p.name = category + "_" + std::to_string(++count_[category]);
    p.model = model;
    p.synset = synset;
    p.fixed = fixed;
    p.pos = pos;
    p.yaw = quarter_turns * M_PI / 2;
    out_.file.objects.push_back(p);
    ++out_.placed;
  }

  const Models& models_;
  SceneAnalog& out_;
  std::map<std::string, int> count_;
};

// Yaw (quarter turns) that puts a model's back (+y) against wall side `side`
// (0 bottom, 1 right, 2 top, 3 left), facing into the room.
int facing_in(int side) {
  static const int turns[4] = {2, 3, 0, 1};
  return turns[side];
}

// Furniture against a wall with an aisle `aisle` deep before its front, else
// free-standing with aisles along both long sides (a table: the arm reaches
// its middle from either); false when nowhere fits. `top`: the part of its
// top the arm reaches from its aisles. What is flat needs no aisle and may lie
// in one.
bool place_furniture(RoomLayout& room, const Eigen::Vector3d& size, bool free_standing_first, double aisle, Rng& rng,
                     Eigen::Vector2d& at, int& turns, Rect* top = nullptr) {
  const Rect inner = room.rect.grown(-kWall / 2);
  for (int t = 0; t < 2 * kTries; ++t) {
    const bool against_wall = (t < kTries) != free_standing_first;
    const int side = uniform_index(rng, 4);
    turns = against_wall ? facing_in(side) : uniform_index(rng, 4);
    const Eigen::Vector2d half = half_footprint(size, turns);
    if (2 * half.x() > inner.width() || 2 * half.y() > inner.depth()) continue;
    Eigen::Vector2d c(uniform(rng, inner.x0 + half.x(), inner.x1 - half.x()),
                      uniform(rng, inner.y0 + half.y(), inner.y1 - half.y()));
    if (against_wall) {
      if (side == 0) c.y() = inner.y0 + half.y();
      if (side == 1) c.x() = inner.x1 - half.x();
      if (side == 2) c.y() = inner.y1 - half.y();
      if (side == 3) c.x() = inner.x0 + half.x();
    }
    const Rect r = footprint(c, half);
    const bool flat = size.z() < Robot::kDrivesOver;  // a rug: it may lie in an aisle
    std::vector<Rect> aisles;
    Rect reached = r;
    if (!flat && against_wall) {
      // The front faces the room's middle, away from wall `side`.
      if (side == 0) aisles = {{r.x0, r.y1, r.x1, r.y1 + aisle}}, reached.y0 = std::max(r.y0, r.y1 - kReachDepth);
      if (side == 1) aisles = {{r.x0 - aisle, r.y0, r.x0, r.y1}}, reached.x1 = std::min(r.x1, r.x0 + kReachDepth);
      if (side == 2) aisles = {{r.x0, r.y0 - aisle, r.x1, r.y0}}, reached.y1 = std::min(r.y1, r.y0 + kReachDepth);
      if (side == 3) aisles = {{r.x1, r.y0, r.x1 + aisle, r.y1}}, reached.x0 = std::max(r.x0, r.x1 - kReachDepth);
    } else if (!flat && r.width() >= r.depth()) {
      aisles = {{r.x0, r.y0 - aisle, r.x1, r.y0}, {r.x0, r.y1, r.x1, r.y1 + aisle}};
    } else if (!flat) {
      aisles = {{r.x0 - aisle, r.y0, r.x0, r.y1}, {r.x1, r.y0, r.x1 + aisle, r.y1}};
    }
    if (!room.free(r, flat) ||
        !std::all_of(aisles.begin(), aisles.end(), [&](const Rect& a) { return room.can_keep(a); })) {
      continue;
    }
    room.taken.push_back(r);
    room.heights.push_back(size.z());
    room.aisles.insert(room.aisles.end(), aisles.begin(), aisles.end());
    at = c;
    if (top) *top = reached;
    return true;
  }
  return false;
}

// On a wall at the item's height, not over a doorway, another wall item nor
// furniture that reaches up to it, with room for what stands on that (a rod
// on a nail would lie on a bookcase, a window's frame knock a lamp off a
// counter); `on_floor` (doors): standing on the floor, clear of the furniture
// too.
bool place_on_wall(RoomLayout& room, const Eigen::Vector3d& size, bool on_floor, Rng& rng, Eigen::Vector3d& at,
                   int& turns, bool holds_something = false) {
  const Rect inner = room.rect.grown(-kWall / 2 - 0.01);  // not touching the wall: a door's leaf swings free
  for (int t = 0; t < kTries; ++t) {
    const int side = uniform_index(rng, 4);
    const bool horizontal = side % 2 == 0;
    const double length = horizontal ? inner.width() : inner.depth();
    if (size.x() + 0.2 > length) continue;
    const double along = uniform(rng, 0.1 + size.x() / 2, length - 0.1 - size.x() / 2);
    const std::pair<double, double> span = {along - size.x() / 2 - kGap, along + size.x() / 2 + kGap};
    bool free = true;
    for (const auto& [u0, u1] : room.wall_used[side]) free &= span.second <= u0 || span.first >= u1;
    turns = facing_in(side);
    const Eigen::Vector2d half = half_footprint(size, turns);
    Eigen::Vector2d c = horizontal
                            ? Eigen::Vector2d(inner.x0 + along, side == 0 ? inner.y0 + half.y() : inner.y1 - half.y())
                            : Eigen::Vector2d(side == 1 ? inner.x1 - half.x() : inner.x0 + half.x(), inner.y0 + along);
    const Rect r = footprint(c, half);
    const double bottom = on_floor                                        ? 0
                          : size.z() > 1.4                                ? 0.3
                          : size.z() < kSmallWallItem && !holds_something ? kWallItemHeight - size.z() / 2
                                                                          : std::max(0.9, 1.4 - size.z() / 2);
    for (const Rect& o : room.keep_clear) free &= !o.overlaps(r);
    for (size_t i = 0; i < room.taken.size() && !on_floor; ++i) {
      free &= room.heights[i] + kHeadroom <= bottom || !room.taken[i].grown(kGap).overlaps(r);
    }
    if (on_floor) free &= room.free(r);
    if (!free) continue;
    room.wall_used[side].push_back(span);
    if (on_floor) room.taken.push_back(r), room.heights.push_back(size.z());
    at = {c.x(), c.y(), bottom};
    return true;
  }
  return false;
}

// On a surface of the room (the top of a table, counter, cabinet, shelf), else
// the floor. A fixture (a microwave) faces the way the furniture under it does.
bool place_small(RoomLayout& room, const Eigen::Vector3d& size, Rng& rng, Eigen::Vector3d& at, int& turns,
                 bool fixture = false) {
  turns = uniform_index(rng, 4);
  for (int t = 0; t < kTries && !room.surfaces.empty(); ++t) {
    RoomLayout::Surface& s = room.surfaces[uniform_index(rng, static_cast<int>(room.surfaces.size()))];
    if (fixture) turns = s.turns;
    const Eigen::Vector2d half = half_footprint(size, turns);
    const Rect top = s.top.grown(-0.02);
    if (2 * half.x() > top.width() || 2 * half.y() > top.depth() || size.z() > s.clearance) continue;
    const Eigen::Vector2d c(uniform(rng, top.x0 + half.x(), top.x1 - half.x()),
                            uniform(rng, top.y0 + half.y(), top.y1 - half.y()));
    const Rect r = footprint(c, half);
    if (std::any_of(s.taken.begin(), s.taken.end(), [&](const Rect& o) { return o.grown(0.01).overlaps(r); })) continue;
    s.taken.push_back(r);
    at = {c.x(), c.y(), s.height + 0.002};
    return true;
  }
  Eigen::Vector2d c;
  if (!place_furniture(room, size, false, kAisle, rng, c, turns)) return false;
  at = {c.x(), c.y(), 0.002};
  return true;
}

// A piece of furniture placed (fixed) with its top as a surface for small
// objects when it has a flat one at a height they are put at.
bool furnish(RoomLayout& room, const Models& models, const std::string& synset,
             const std::vector<std::string>& clear_tops, std::map<std::string, int>& kept_clear, Rng& rng,
             Builder& builder) {
  const Eigen::Vector3d size = models.size(synset);
  const Archetype archetype = models.archetype(synset);
  Eigen::Vector2d at;
  int turns = 0;
  Rect top;
  // What opens with room to open it where it fits, else as the rest: a
  // fridge with little floor before it is better than none in a small bar.
  const bool opens = archetype == Archetype::cabinet;
  const bool free_standing_first = archetype == Archetype::table;
  if (!(opens && place_furniture(room, size, free_standing_first, kOpeningAisle, rng, at, turns, &top)) &&
      !place_furniture(room, size, free_standing_first, kAisle, rng, at, turns, &top)) {
    return false;
  }
  builder.add(synset, {at.x(), at.y(), 0}, turns, true);
  const bool flat_top = archetype == Archetype::table || archetype == Archetype::cabinet ||
                        archetype == Archetype::shelf || archetype == Archetype::block;
  const bool clear =
      std::any_of(clear_tops.begin(), clear_tops.end(), [&](const std::string& s) { return models.is_a(synset, s); });
  if (flat_top && !clear && size.z() > 0.3 && size.z() < 1.6) {
    room.surfaces.push_back({top, size.z(), {}, turns});
  }
  // A shelf's boards below its top hold things too, as a store's and a
  // bookcase's do: strewn on the floor instead (a grocery store's 1,400
  // items), they left the base no pose before the shelves. Clear are only
  // as many shelves of a synset as the activity names (the first ones
  // placed, which the activity binds: tasks/activity.cpp), not a store's
  // every shelf.
  const auto named =
      std::count_if(clear_tops.begin(), clear_tops.end(), [&](const std::string& s) { return models.is_a(synset, s); });
  const bool boards_clear = named > kept_clear[synset];
  if (boards_clear) ++kept_clear[synset];
  if (archetype == Archetype::shelf && !boards_clear) {
    const ShelfBoards boards = shelf_boards(size);
    for (size_t b = 0; b + 1 < boards.tops.size(); ++b) {
      room.surfaces.push_back({top, boards.tops[b], {}, turns, boards.clearance});
    }
  }
  return true;
}

}  // namespace

int SceneInventory::object_count() const {
  int n = 0;
  for (const RoomInventory& r : rooms)
    for (const auto& [synset, count] : r.objects) n += count;
  return n;
}

std::vector<SceneInventory> read_scene_inventories(const std::string& inventory_path,
                                                   const std::string& category_path) {
  const CsvTable categories = read_csv_file(category_path);
  std::map<std::string, std::string> synset_of;
  const size_t category_column = categories.column("category"), synset_column = categories.column("synset");
  for (const auto& row : categories.rows) synset_of[row[category_column]] = row[synset_column];
  const nlohmann::json file = read_json_file(inventory_path);
  const JsonReader root(file, inventory_path);
  const JsonReader scenes = root.at("scenes");
  if (!file["scenes"].is_object()) scenes.fail("expected an object of scenes");
  std::vector<SceneInventory> inventories;
  for (const auto& [scene, rooms] : file["scenes"].items()) {
    const JsonReader where = scenes.at(scene.c_str());
    if (!rooms.is_object()) where.fail("expected an object of rooms");
    SceneInventory inventory{scene, {}};
    for (const auto& [room, objects] : rooms.items()) {
      if (!is_room_name(room)) where.fail("room '" + room + "' is not TYPE_INDEX");
      if (!objects.is_object()) where.at(room.c_str()).fail("expected an object of counts");
      std::map<std::string, int> counts;
      for (const auto& [model, count] : objects.items()) {
        const std::string category = model.substr(0, model.rfind('-'));
        const auto synset = synset_of.find(category);
        if (synset == synset_of.end()) {
          where.at(room.c_str()).fail("category '" + category + "' is not in " + category_path);
        }
        if (!count.is_number_integer() || count.get<int64_t>() < 1 || count.get<int64_t>() > 100000) {
          where.at(room.c_str()).fail("'" + model + "' = " + json_text(count) + " is not a count");
        }
        counts[synset->second] += count.get<int>();
      }
      inventory.rooms.push_back({room, room.substr(0, room.rfind('_')), {counts.begin(), counts.end()}});
    }
    inventories.push_back(std::move(inventory));
  }
  std::sort(inventories.begin(), inventories.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return inventories;
}

const std::vector<SceneInventory>& shipped_scene_inventories() {
  static std::once_flag once;
  static std::vector<SceneInventory> inventories;
  std::call_once(once, [] {
    inventories = read_scene_inventories(default_tasks_dir() + "/kb/behavior-1k/combined_room_object_list.json",
                                         default_tasks_dir() + "/kb/behavior-1k/category_mapping.csv");
  });
  return inventories;
}

const SceneInventory& find_scene_inventory(const std::string& name) {
  std::string known;
  for (const SceneInventory& s : shipped_scene_inventories()) {
    if (s.name == name) return s;
    known += (known.empty() ? "" : ", ") + s.name;
  }
  throw Error("no scene '" + name + "' among BEHAVIOR-1K's inventories (" + known + ")");
}

SceneAnalog generate_scene_analog(const SceneInventory& inventory, const CategoryModels& category_models, uint64_t seed,
                                  const AnalogExtras& extras) {
  const Models models{category_models, extras};
  const std::vector<ExtraObject>& extra = extras.objects;
  if (inventory.rooms.empty()) throw Error("scene " + inventory.name + ": no rooms");
  Rng rng(seed);
  SceneAnalog analog;
  SceneFile& file = analog.file;
  file.name = inventory.name;
  file.path = inventory.name + " (analog, seed " + std::to_string(seed) + ")";
  file.wall_thickness = kWall;
  std::vector<RoomLayout> rooms = lay_out_rooms(inventory, extra, models, rng);
  const std::vector<Doorway> doors = doorways(rooms);
  file.walls = walls(rooms, doors);
  for (const RoomLayout& room : rooms) {
    const Rect& r = room.rect;
    file.rooms.push_back(
        {room.inventory->name, room.inventory->type, {{r.x0, r.y0, r.x1, r.y1}}, floor_colour(room.inventory->type)});
    file.ceiling_lights.push_back({{(r.x0 + r.x1) / 2, (r.y0 + r.y1) / 2, file.wall_height - 0.1}, {0.5, 0.5, 0.5}});
  }
  Builder builder(models, analog);
  std::map<std::string, int> kept_clear;  // furnish(): shelves of each synset whose boards stay clear
  // Floors asked for as objects: a slab over the room inside its walls, its
  // top the floor's, in the floor's colour; under everything, taking no space.
  for (const std::string& name : extras.floors) {
    const RoomLayout& room = rooms[room_of(inventory, {name, "floor.n.01"})];
    const Rect inner = room.rect.grown(-kWall / 2);
    constexpr double kSlab = 0.002;
    ObjectModel model = category_models.model("floor.n.01", {inner.width(), inner.depth(), kSlab});
    for (GeomSpec& g : model.root.geoms) g.rgb = floor_colour(room.inventory->type);
    builder.add("floor.n.01 " + room.inventory->name, std::move(model),
                {(inner.x0 + inner.x1) / 2, (inner.y0 + inner.y1) / 2, -kSlab});
  }
  // Per room: doors (the doorways stay open: a door of the inventory stands
  // closed against a wall, openable), then furniture, largest first, then what
  // goes on walls and surfaces.
  for (RoomLayout& room : rooms) {
    std::vector<std::pair<std::string, int>> furniture;
    for (const auto& [synset, count] : room.inventory->objects) {
      const Kind kind = kind_of(models, synset);
      if (stands_on_floor(kind)) furniture.push_back({synset, count});
      for (int n = 0; kind == Kind::door && n < count; ++n) {
        Eigen::Vector3d at;
        int turns = 0;
        if (!place_on_wall(room, models.size(synset), true, rng, at, turns)) {
          ++analog.left_out;
          continue;
        }
        builder.add(synset, at, turns, true);
      }
    }
    std::stable_sort(furniture.begin(), furniture.end(), [&](const auto& a, const auto& b) {
      const Eigen::Vector3d sa = models.size(a.first), sb = models.size(b.first);
      return sa.x() * sa.y() > sb.x() * sb.y();
    });
    for (const auto& [synset, count] : furniture) {
      for (int n = 0; n < count; ++n) {
        analog.left_out += !furnish(room, models, synset, extras.clear_tops, kept_clear, rng, builder);
      }
    }
  }
  const auto holds_from_start = [&](const std::string& synset) {
    return std::any_of(extras.holding_at_start.begin(), extras.holding_at_start.end(),
                       [&](const std::string& to) { return models.is_a(synset, to); });
  };
  // What the caller adds, before the inventory's small objects take the
  // space: furniture first (it makes surfaces), then the rest.
  for (int pass = 0; pass < 2; ++pass) {
    for (const ExtraObject& e : extra) {
      if (e.future || is_furniture(models, e) != (pass == 0)) continue;
      RoomLayout& room = rooms[room_of(inventory, e)];
      if (pass == 0) {
        analog.left_out += !furnish(room, models, e.synset, extras.clear_tops, kept_clear, rng, builder);
        continue;
      }
      Eigen::Vector3d at;
      int turns = 0;
      if (!e.loose && kind_of(models, e.synset) == Kind::on_wall) {  // a window the room lacks: on its wall
        // With the wall to either side kept for what hangs on it (a rod on
        // its nail, clear of the next wall item and of furniture below).
        Eigen::Vector3d size = models.size(e.synset);
        for (const auto& [object, to] : extras.attachments) {
          if (models.is_a(e.synset, to)) size.x() = std::max(size.x(), models.size(object).head<2>().maxCoeff());
        }
        if (place_on_wall(room, size, false, rng, at, turns, holds_from_start(e.synset))) {
          builder.add(e.synset, at, turns, true);
        } else {
          ++analog.left_out;
        }
        continue;
      }
      // An object of no room given goes in the first room with space for it.
      const bool fixture = !e.loose && models.has_property(e.synset, "sceneObject");
      bool placed = place_small(room, models.size(e.synset), rng, at, turns, fixture);
      for (size_t r = 0; !placed && e.room.empty() && r < rooms.size(); ++r) {
        placed = place_small(rooms[r], models.size(e.synset), rng, at, turns, fixture);
      }
      if (!placed) {
        ++analog.left_out;
        continue;
      }
      builder.add(e.synset, at, turns, fixture);
    }
  }
  for (RoomLayout& room : rooms) {
    for (const auto& [synset, count] : room.inventory->objects) {
      const Kind kind = kind_of(models, synset);
      if (kind != Kind::on_wall && kind != Kind::small) continue;
      const Eigen::Vector3d size = models.size(synset);
      for (int n = 0; n < count; ++n) {
        Eigen::Vector3d at;
        int turns = 0;
        const bool on_wall = kind == Kind::on_wall;
        const bool fixture = models.has_property(synset, "sceneObject");
        if (!(on_wall ? place_on_wall(room, size, false, rng, at, turns, holds_from_start(synset))
                      : place_small(room, size, rng, at, turns, fixture))) {
          ++analog.left_out;
          continue;
        }
        builder.add(synset, at, turns, on_wall || fixture);
      }
    }
  }
  // The pairs an activity may attach, at most kAttachments per pair of synsets.
  for (const auto& [object, to] : extras.attachments) {
    int pairs = 0;
    for (const ObjectPlacement& a : file.objects) {
      for (const ObjectPlacement& b : file.objects) {
        if (&a == &b || pairs >= kAttachments || !models.is_a(a.synset, object) || !models.is_a(b.synset, to)) continue;
        file.attachments.push_back({a.name, b.name});
        ++pairs;
      }
    }
  }
  // The robot: in the first room with floor clear of everything around it.
  bool robot = false;
  for (size_t s = 0; s < rooms.size() && !robot; ++s) {
    const RoomLayout& start = rooms[s];
    const Rect inner = start.rect.grown(-kWall / 2 - kRobotClear);
    for (int t = 0; t < 20 * kTries && inner.width() > 0 && inner.depth() > 0 && !robot; ++t) {
      const Eigen::Vector2d c(uniform(rng, inner.x0, inner.x1), uniform(rng, inner.y0, inner.y1));
      const Rect r = footprint(c, {kRobotClear, kRobotClear});
      if (std::any_of(start.taken.begin(), start.taken.end(), [&](const Rect& o) { return o.overlaps(r); })) continue;
      file.robot_start = {c.x(), c.y(), uniform(rng, -M_PI, M_PI)};
      robot = true;
    }
  }
  if (!robot) throw Error("scene " + inventory.name + ": no room has free floor for the robot");
  // Last, what transitions make: hidden from the start, anywhere there is room.
  Rng futures(0);
  for (const ExtraObject& e : extra) {
    if (!e.future) continue;
    Eigen::Vector3d at;
    int turns = 0;
    bool placed = false;
    for (size_t r = 0; !placed && r < rooms.size(); ++r) {
      placed = place_small(rooms[r], models.size(e.synset), futures, at, turns);
    }
    if (placed) {
      builder.add(e.synset, at, turns, false);
    } else {
      ++analog.left_out;
    }
  }
  return analog;
}

}  // namespace chore
