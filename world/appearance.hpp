// How a world looks: which lights are on, and a seeded domain randomisation of
// light intensities and colours and of surface colours, drawn afresh per episode.
#pragma once

#include "base/random.hpp"

struct mjModel_;

namespace chore {

class Scene;

// "full": ceiling lights and lamps; "lamps_only": the paper's dim condition.
enum class Lighting { full, lamps_only };

// Spreads of the randomisation, each a relative half-width around the scene's
// own value (0: left as the scene has it). All zero: off.
struct AppearanceRandomization {
  double light_intensity = 0;  // each light's brightness x U(1 - s, 1 + s)
  double light_color = 0;      // and each of its channels x U(1 - s, 1 + s)
  // Each movable object's colour, and each colour of the merged static scene
  // (walls, floors, furniture: its palette texture), per channel x U(1 - s, 1 + s).
  double surface_color = 0;
  bool any() const { return light_intensity > 0 || light_color > 0 || surface_color > 0; }
};

// Throws chore::Error naming a spread outside [0, 1].
void validate(const AppearanceRandomization& r);

// Sets `model` (a copy of scene.model()) back to the scene's lights and colours,
// then draws `r`'s perturbations from `rng`. Returns whether textures changed
// (a renderer must upload them again).
bool randomize_appearance(const Scene& scene, mjModel_* model, const AppearanceRandomization& r, Rng& rng);

}  // namespace chore
