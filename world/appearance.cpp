#include "world/appearance.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "world/scene.hpp"

namespace chore {

void validate(const AppearanceRandomization& r) {
  const std::pair<const char*, double> spreads[] = {
      {"light_intensity", r.light_intensity}, {"light_color", r.light_color}, {"surface_color", r.surface_color}};
  for (const auto& [name, value] : spreads) {
    if (!(value >= 0 && value <= 1)) {
      throw Error(std::string("randomization.") + name + " = " + std::to_string(value) +
                  ": expected a spread in [0, 1]");
    }
  }
}

bool randomize_appearance(const Scene& scene, mjModel* model, const AppearanceRandomization& r, Rng& rng) {
  const mjModel* original = scene.model();
  auto factor = [&](double spread) { return spread > 0 ? uniform(rng, 1 - spread, 1 + spread) : 1.0; };
  // Lights (which are on is set_lighting's business, not this).
  for (int l = 0; l < model->nlight; ++l) {
    const double intensity = factor(r.light_intensity);
    for (int c = 0; c < 3; ++c) {
      const double v = original->light_diffuse[3 * l + c] * intensity * factor(r.light_color);
      model->light_diffuse[3 * l + c] = static_cast<float>(std::min(v, 1.0));
    }
  }
  // Drawn geoms of objects: one perturbation per object.
  std::memcpy(model->geom_rgba, original->geom_rgba, sizeof(float) * 4 * model->ngeom);
  if (r.surface_color > 0) {
    const auto& objects = scene.objects();
    std::vector<std::array<double, 3>> tint(objects.size());
    for (auto& t : tint) {
      for (double& c : t) c = factor(r.surface_color);
    }
    for (int g = 0; g < model->ngeom; ++g) {
      const int object = scene.object_of_geom(g);
      if (object < 0 || model->geom_group[g] != kStaticGroup) continue;
      for (int c = 0; c < 3; ++c) {
        model->geom_rgba[4 * g + c] = static_cast<float>(std::min(1.0, model->geom_rgba[4 * g + c] * tint[object][c]));
      }
    }
  }
  // The merged static scene's palettes: one perturbation per distinct colour.
  bool textures = false;
  for (const char* name : {"static_visual", "ceiling_visual"}) {
    const int tex = mj_name2id(model, mjOBJ_TEXTURE, name);
    if (tex < 0) continue;
    if (model->tex_nchannel[tex] != 3) throw Error("appearance: texture '" + std::string(name) + "' is not RGB");
    const int bytes = 3 * model->tex_width[tex] * model->tex_height[tex];
    unsigned char* texels = model->tex_data + model->tex_adr[tex];
    std::memcpy(texels, original->tex_data + original->tex_adr[tex], bytes);
    if (r.surface_color <= 0) continue;
    // The same colour gets the same factors wherever it appears: keyed by colour.
    const uint64_t salt = rng();
    for (int i = 0; i < bytes; i += 3) {
      const uint64_t colour = uint64_t(texels[i]) << 16 | uint64_t(texels[i + 1]) << 8 | texels[i + 2];
      for (int c = 0; c < 3; ++c) {
        const double u = static_cast<double>(derive_seed(colour ^ salt, c) >> 11) * 0x1.0p-53;
        const double f = 1 + r.surface_color * (2 * u - 1);
        texels[i + c] = static_cast<unsigned char>(std::min(255.0, texels[i + c] * f + 0.5));
      }
    }
    textures = true;
  }
  return textures;
}

}  // namespace chore
