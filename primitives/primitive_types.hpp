// The names of the action primitives, their execution modes and their
// failure taxonomy: the small part of primitives/ that the env's public types
// (Info's counts) and the policy API need, without the world behind it.
#pragma once

#include <string>

namespace chore {

// The registry of primitives, in the order of PrimitiveType (and of the
// primitive action space's actions): each is defined in its own file,
// primitives/<name>.cpp (docs/architecture.md, "A primitive").
// clang-format off
#define CHORE_PRIMITIVES(X) \
  X(navigate) X(pick) X(place) X(push) X(dip) X(wipe) X(toggle_on) X(toggle_off) X(pour) X(place_next_to) \
  X(cut) X(attach) X(fold) X(unfold) X(close) X(drape) X(place_under) X(place_near_heating_element) X(wait)
// clang-format on

#define CHORE_PRIMITIVE_ENUM(name) name,
enum class PrimitiveType { CHORE_PRIMITIVES(CHORE_PRIMITIVE_ENUM) };
#undef CHORE_PRIMITIVE_ENUM
#define CHORE_PRIMITIVE_COUNT(name) +1
inline constexpr int kPrimitiveTypes = 0 CHORE_PRIMITIVES(CHORE_PRIMITIVE_COUNT);
#undef CHORE_PRIMITIVE_COUNT

enum class ExecutionMode { physical, symbolic };

// The seed's failure taxonomy (appendix G), less object detection (we know
// where objects are).
enum class PrimitiveStatus {
  success,
  motion_planning_failure,  // no base pose, IK solution or collision-free path; object out of reach
  grasp_failure,            // the hand closed but holds nothing, or dropped it
  place_failure,            // the released object did not end up on or in the target
  precondition_failure,     // e.g. pick while holding, place with an empty hand
};
inline constexpr int kPrimitiveStatuses = 5;

const char* to_string(PrimitiveType type);
const char* to_string(ExecutionMode mode);
const char* to_string(PrimitiveStatus status);
// chore::Error naming the accepted values.
PrimitiveType parse_primitive_type(const std::string& name);
ExecutionMode parse_execution_mode(const std::string& name);

}  // namespace chore
