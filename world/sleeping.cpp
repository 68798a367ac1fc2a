#include "world/sleeping.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>

namespace chore {
namespace {

// The tree of a contact's side (-1: static, or a flex).
int tree_of(const mjModel* m, int geom) {
  return geom < 0 ? -1 : m->body_treeid[m->geom_bodyid[geom]];
}

}  // namespace

bool RestingContacts::asleep(const mjModel* m, const mjData* d, const mjContact& c) {
  for (const int geom : c.geom) {
    const int tree = tree_of(m, geom);
    if (tree >= 0 && d->tree_asleep[tree] < 0) return false;
  }
  return true;
}

void RestingContacts::before_step(const mjModel* m, const mjData* d) {
  awake_before_.resize(m->ntree);
  for (int t = 0; t < m->ntree; ++t) awake_before_[t] = d->tree_asleep[t] < 0;
}

void RestingContacts::before_reset(const mjModel* m) {
  awake_before_.assign(m->ntree, 1);
  kept_.clear();
}

void RestingContacts::after_step(const mjModel* m, const mjData* d) {
  std::erase_if(kept_, [&](const mjContact& c) { return !asleep(m, d, c); });
  // The step's contacts (computed before it integrated) of a tree that fell
  // asleep in it: those it rests on.
  const auto fell = [&](int geom) {
    const int tree = tree_of(m, geom);
    return tree >= 0 && awake_before_[tree] && d->tree_asleep[tree] >= 0;
  };
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    if ((fell(con.geom[0]) || fell(con.geom[1])) && asleep(m, d, con)) {
      kept_.push_back(con);
      kept_.back().efc_address = -1;  // no force: not in the solver
    }
  }
}

}  // namespace chore
