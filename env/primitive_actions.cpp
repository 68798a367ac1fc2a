#include "env/primitive_actions.hpp"

#include <algorithm>
#include <set>

#include "world/transitions.hpp"
#include "world/world.hpp"

namespace chore {
namespace {

// Instances (or variable types, as "?type") that are argument `arg` of a
// literal with one of `predicates`, anywhere in the formula.
void arguments_of(const Formula& f, const std::set<std::string>& predicates, size_t arg, std::set<std::string>& names,
                  std::vector<const Variable*>& scope) {
  if (f.op == Op::literal) {
    const Literal& l = f.literal;
    if (predicates.count(l.predicate) && l.args.size() > arg) {
      const std::string& name = l.args[arg];
      const auto var = std::find_if(scope.rbegin(), scope.rend(), [&](const Variable* v) { return v->name == name; });
      names.insert(var != scope.rend() ? "?" + (*var)->type : name);
    }
    return;
  }
  for (const Variable& v : f.variables) scope.push_back(&v);
  for (const Formula& child : f.children) arguments_of(child, predicates, arg, names, scope);
  scope.resize(scope.size() - f.variables.size());
}

// The same over :init and :goal.
std::set<std::string> arguments_of(const Problem& problem, const std::set<std::string>& predicates, size_t arg) {
  std::set<std::string> names;
  std::vector<const Variable*> scope;
  for (const Literal& l : problem.init) {
    Formula f;
    f.literal = l;
    arguments_of(f, predicates, arg, names, scope);
  }
  arguments_of(problem.goal, predicates, arg, names, scope);
  return names;
}

}  // namespace

std::string to_string(const PrimitiveAction& action) {
  return std::string(to_string(action.type)) + "(" + action.instance + ")";
}

std::vector<PrimitiveAction> primitive_actions(const Activity& activity, const World& world, ExecutionMode mode) {
  const Problem& problem = activity.problem();
  const std::set<std::string> supports = arguments_of(problem, {"ontop", "inside"}, 1);
  const std::set<std::string> dirty = arguments_of(problem, {"stained", "dusty", "covered"}, 0);
  // Placing and opening serve goals that put something somewhere: with none
  // (CleanTable), place and push would only undo a pick or open a drawer for
  // nothing, and the paper's action space there has neither (appendix F.2).
  std::set<std::string> goal_supports;
  std::vector<const Variable*> scope;
  arguments_of(problem.goal, {"ontop", "inside"}, 1, goal_supports, scope);
  // Setting down beside serves goals that put things next to each other.
  std::set<std::string> neighbours;
  arguments_of(problem.goal, {"nextto"}, 0, neighbours, scope);
  arguments_of(problem.goal, {"nextto"}, 1, neighbours, scope);
  // Putting beneath serves goals that put things under others.
  std::set<std::string> above;
  arguments_of(problem.goal, {"under"}, 1, above, scope);
  // Laying a cloth over serves goals that drape or overlay cloths on things.
  std::set<std::string> covered_by_cloth;
  arguments_of(problem.goal, {"draped", "overlaid"}, 1, covered_by_cloth, scope);
  // Closing serves goals that want something closed.
  std::set<std::string> closable;
  arguments_of(problem.goal, {"open"}, 0, closable, scope);
  // Attaching serves goals that attach things: to what they attach to.
  std::set<std::string> attach_to;
  arguments_of(problem.goal, {"attached"}, 1, attach_to, scope);
  // Pouring serves goals that put a substance in or on something.
  std::set<std::string> receivers;
  arguments_of(problem.goal, {"contains", "filled", "covered"}, 0, receivers, scope);
  // Setting down on a heat or cold source serves goals that heat, cook, burn
  // or freeze something, and rules of the activity that heat (cooking).
  std::set<std::string> heated;
  arguments_of(problem.goal, {"cooked", "burnt", "hot", "frozen", "on_fire"}, 0, heated, scope);
  const std::vector<Transition>& transitions = world.states().transitions();
  const bool heating = !heated.empty() || std::any_of(transitions.begin(), transitions.end(), [](const Transition& t) {
    return t.trigger == TransitionTrigger::heated;
  });
  // Waiting serves what only time does: what those goals heat, cool or
  // freeze, and what the rules that heat take in (butter melting in a pot).
  std::set<int> warmed;
  for (const Transition& t : transitions) {
    if (t.trigger == TransitionTrigger::heated) warmed.insert(t.input_objects.begin(), t.input_objects.end());
  }
  // What heats or cools only what is inside it, and only closed (an oven, a
  // microwave, a freezer): where the activity heats, it is put into, opened
  // and closed.
  const auto heats_inside = [&](int object) {
    const ObjectAbilities* ab = world.states().abilities(object);
    return heating && ab &&
           ((ab->heat_source && ab->heat_source->requires_inside) ||
            (ab->cold_source && ab->cold_source->requires_inside));
  };
  // Goals that make something (real: a recipe's output) juggle a jar, a mug
  // and a spoon: place serves them too, onto what holds things at the start
  // and into what the goal fills (a spoon put into the mug stirs it); so do
  // goals that heat or cool (frozen food taken out of the fridge to thaw).
  std::set<std::string> made;
  arguments_of(problem.goal, {"real"}, 0, made, scope);
  // The activity's transitions happen in places (a blender, a mixing bowl, a
  // pot on the stove) and its washers and dryers on what is inside them:
  // where it makes something, things are put and poured into those.
  std::set<int> transition_places;
  for (const Transition& t : transitions) transition_places.insert(t.places.begin(), t.places.end());
  for (const Washer& washer : world.states().washers()) transition_places.insert(washer.object);
  // Setting down on something serves goals that it touch it too.
  std::set<std::string> touched;
  arguments_of(problem.goal, {"touching"}, 0, touched, scope);
  arguments_of(problem.goal, {"touching"}, 1, touched, scope);
  const std::set<std::string> folds = arguments_of(problem, {"folded", "unfolded"}, 0);
  // Opening serves goals that put things in, and getting out what is in
  // (a bottle in the fridge).
  std::set<std::string> openable = arguments_of(problem, {"open"}, 0);
  openable.insert(goal_supports.begin(), goal_supports.end());
  const std::set<std::string> holders = arguments_of(problem, {"inside"}, 1);
  openable.insert(holders.begin(), holders.end());
  // Dipping goes into what :init fills (a bucket of water) or under a source
  // (a sink): every container may hold a liquid, but an empty mug is no place
  // to dip into.
  std::set<std::string> filled_at_start;
  for (const Literal& l : problem.init) {
    if (!l.negated && !l.args.empty() &&
        (l.predicate == "filled" || l.predicate == "contains" || l.predicate == "insource"))
      filled_at_start.insert(l.args[0]);
  }

  const auto gives_liquid = [&](int object) {
    const ObjectAbilities* ab = world.states().abilities(object);
    return ab && !ab->source.empty();
  };

  // Cutting, where the activity has something to cut with.
  bool slicer = false;
  for (const ObjectDecl& decl : problem.objects) {
    const Binding& b = activity.binding(decl.name);
    const ObjectAbilities* ab = b.kind == Binding::Kind::object ? world.states().abilities(b.index) : nullptr;
    slicer = slicer || (ab && ab->slicer);
  }

  std::vector<PrimitiveAction> actions;
  for (const ObjectDecl& decl : problem.objects) {
    const Binding& b = activity.binding(decl.name);
    // A floor with an object of its own (a room's slab: analogs/) is gone to
    // and set down on. Not wiped: dirt on a floor is swept with a broom or a
    // mop held at its top, 1.3 m up, which no wipe from above reaches.
    const bool floor = b.kind == Binding::Kind::floor;
    const int object = b.state_object();
    if (object < 0) continue;
    const auto named = [&](const std::set<std::string>& names) {
      return names.count(decl.name) || names.count("?" + decl.type);
    };
    for (int t = 0; t < kPrimitiveTypes; ++t) {
      const auto type = static_cast<PrimitiveType>(t);
      if (floor && type != PrimitiveType::navigate && type != PrimitiveType::place) continue;
      bool applies = primitive_applies(world, type, object);
      if (type == PrimitiveType::place) {
        applies = ((!goal_supports.empty() || !made.empty() || !heated.empty()) && named(supports)) || named(touched) ||
                  heats_inside(object) || (!made.empty() && named(receivers)) || transition_places.count(object);
      }
      if (type == PrimitiveType::push)
        applies = applies && (named(openable) || heats_inside(object) || transition_places.count(object));
      if (type == PrimitiveType::close)
        applies = applies && (named(closable) || heats_inside(object) || transition_places.count(object));
      if (type == PrimitiveType::drape) applies = named(covered_by_cloth);
      if (type == PrimitiveType::place_under) applies = named(above);
      if (type == PrimitiveType::wipe) applies = applies && named(dirty);
      if (type == PrimitiveType::pour) applies = applies && (named(receivers) || transition_places.count(object));
      if (type == PrimitiveType::place_next_to) applies = named(neighbours);
      if (type == PrimitiveType::cut) applies = applies && slicer;
      if (type == PrimitiveType::attach) applies = applies && named(attach_to);
      if (type == PrimitiveType::dip) applies = applies && (named(filled_at_start) || gives_liquid(object));
      if (type == PrimitiveType::fold || type == PrimitiveType::unfold) applies = applies && named(folds);
      if (type == PrimitiveType::place_near_heating_element) applies = applies && heating;
      if (type == PrimitiveType::wait) applies = applies && (named(heated) || warmed.count(object));
      if (mode == ExecutionMode::physical && !primitive_is_physical(type)) applies = false;
      if (applies) actions.push_back({type, object, decl.name});
    }
  }
  return actions;
}

}  // namespace chore
