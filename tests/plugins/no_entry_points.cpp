// A shared library that is no chore policy plugin: it lacks the entry points.
extern "C" int not_a_policy() {
  return 42;
}
