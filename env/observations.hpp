// The observation modalities, one entry each of one list (observations.cpp),
// in the order of the observation Dict (the layout of batched buffers). A
// modality is a name, its space, and where its values come from: the sensors
// write it into its buffer (cameras, LiDAR: `bind` points the sensor frame
// there), or it is written from the world after each step (`write`). Adding
// a state modality is one entry; a sensor modality also needs its pass in
// world/sensors (docs/architecture.md). Internal to env/.
#pragma once

#include <string>
#include <vector>

#include "env/env.hpp"
#include "env/spaces.hpp"
#include "world/sensors.hpp"

namespace chore {

// What a modality sees of the env that observes it.
struct ObservationSource {
  const EnvConfig& config;
  const World& world;
  const Sensors& sensors;
  const std::vector<PrimitiveAction>& primitive_actions;
};

struct Modality {
  std::string name;
  bool needs_robot = false;
  bool needs_primitives = false;  // the primitive action space
  Space (*space)(const ObservationSource& source) = nullptr;
  // A sensor modality: its buffer (one element of the batch) into the frame.
  void (*bind)(SensorFrame& frame, void* buffer) = nullptr;
  // A state modality: writes one element from the world.
  void (*write)(const ObservationSource& source, void* buffer) = nullptr;
};

const std::vector<Modality>& modalities();
// The modality named `name`; chore::Error naming the known ones.
const Modality& find_modality(const std::string& name);

}  // namespace chore
