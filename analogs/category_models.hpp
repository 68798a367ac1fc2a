// Object models for the knowledge base's categories, generated. BEHAVIOR-1K's
// 3D assets are not chore's to ship, so each category (synset) gets a model
// built from what the knowledge base says of it:
//
//   archetype  chosen by its properties and its place in the hierarchy:
//              cloth (cloth, drapeable), cabinet (openable furniture and
//              appliances: a carcass with a hinged door, or a drawer when it is
//              wider than tall), basin (fillable furniture: sinks, tubs), door,
//              table, seat, bed, shelf, lidded and open containers (fillable
//              objects), ball (fruit, balls), block (everything else)
//   size       assets/analogs/category_sizes.json: typical sizes over the
//              hierarchy; a category without an entry takes its nearest
//              ancestor's, scaled by the cube root of its own annotated mass
//              over the entry's (clamped to [0.5, 2])
//   mass       BEHAVIOR's annotation (tasks/kb/behavior-1k/category_mapping.csv,
//              the median over the synset's categories), else the entry's
//   colour     a hue of its own per category (hashed from the synset), so that
//              categories are told apart in RGB
//
// The models follow docs/assets.md's conventions (origin at the footprint's
// centre on the floor, front towards -y) and are plain data: a scene compiles
// them like any model file.
#pragma once

#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>

#include "tasks/knowledge_base.hpp"
#include "world/scene_file.hpp"

namespace chore {

enum class Archetype {
  cloth,
  cabinet,
  basin,
  door,
  table,
  seat,
  bed,
  shelf,
  lidded_container,
  open_container,
  ball,
  block
};
const char* to_string(Archetype archetype);

// A shelf's boards (Archetype::shelf), as the model builds them: the heights
// of their tops above the shelf's bottom, lowest first, the shelf's own top
// last, and the room between one board's top and the next's underside.
struct ShelfBoards {
  std::vector<double> tops;
  double clearance = 0;
};
ShelfBoards shelf_boards(const Eigen::Vector3d& size);

class CategoryModels {
 public:
  // The BEHAVIOR-1K knowledge base with the size table under `assets` and
  // the masses beside the knowledge base; a bad table is a chore::Error
  // naming the file and the entry.
  static std::shared_ptr<const CategoryModels> load(std::shared_ptr<const KnowledgeBase> kb,
                                                    const std::string& size_table, const std::string& mass_table);
  // The shipped tables (assets/analogs/, tasks/kb/behavior-1k/), loaded once.
  static std::shared_ptr<const CategoryModels> shipped();

  // Each throws chore::Error for a synset the knowledge base lacks or a
  // substance (water, dust: not objects).
  Archetype archetype(const std::string& synset) const;
  Eigen::Vector3d size(const std::string& synset) const;  // width x, depth y, height z (m)
  double mass(const std::string& synset) const;           // kg
  Rgb colour(const std::string& synset) const;
  // The entry of the size table that sized it (itself or its nearest ancestor).
  std::string size_entry(const std::string& synset) const;
  ObjectModel model(const std::string& synset) const;
  // Its model at another size (a lawn sized to its garden). A drawer or a
  // basin is at least `inner_height` deep (what an activity puts in it), and
  // no deeper than the arm needs (its floor as high as that leaves it).
  ObjectModel model(const std::string& synset, const Eigen::Vector3d& size, double inner_height = 0) const;

  const KnowledgeBase& knowledge_base() const { return *kb_; }

 private:
  struct SizeEntry {
    Eigen::Vector3d size;
    double mass;
  };
  CategoryModels() = default;
  void check_object(const std::string& synset) const;

  std::shared_ptr<const KnowledgeBase> kb_;
  std::map<std::string, SizeEntry> sizes_;
  std::map<std::string, double> masses_;  // synset -> annotated mass (median)
};

}  // namespace chore
