#include "env/spaces.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "base/error.hpp"

namespace chore {

size_t dtype_size(DType dtype) {
  switch (dtype) {
    case DType::uint8:
      return 1;
    case DType::int32:
      return 4;
    case DType::float32:
      return 4;
    case DType::int64:
      return 8;
  }
  return 0;
}

const char* dtype_name(DType dtype) {
  switch (dtype) {
    case DType::uint8:
      return "uint8";
    case DType::int32:
      return "int32";
    case DType::float32:
      return "float32";
    case DType::int64:
      return "int64";
  }
  return "?";
}

Space::Space() = default;

Space Space::box(std::vector<int> shape, DType dtype, double low, double high) {
  Space s;
  s.kind = Kind::box;
  s.shape = std::move(shape);
  s.dtype = dtype;
  s.low = low;
  s.high = high;
  return s;
}

Space Space::discrete(int64_t n) {
  Space s;
  s.kind = Kind::discrete;
  s.dtype = DType::int64;
  s.n = n;
  return s;
}

Space Space::dict(std::vector<std::pair<std::string, Space>> fields) {
  Space s;
  s.kind = Kind::dict;
  s.fields = std::move(fields);
  return s;
}

size_t Space::element_count() const {
  if (kind == Kind::discrete) return 1;
  size_t n = 1;
  for (int d : shape) n *= static_cast<size_t>(d);
  return n;
}

const Space& Space::operator[](std::string_view name) const {
  for (const auto& [key, value] : fields) {
    if (key == name) return value;
  }
  throw Error("space has no field '" + std::string(name) + "'");
}

namespace {
std::string bound(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out << v;
  return out.str();
}
}  // namespace

std::string Space::to_string() const {
  std::ostringstream out;
  if (kind == Kind::discrete) {
    out << "Discrete(" << n << ")";
  } else if (kind == Kind::box) {
    out << "Box(" << bound(low) << ", " << bound(high) << ", (";
    for (size_t i = 0; i < shape.size(); ++i) out << (i ? ", " : "") << shape[i];
    out << (shape.size() == 1 ? ",)" : ")") << ", " << dtype_name(dtype) << ")";
  } else {
    out << "Dict(";
    for (size_t i = 0; i < fields.size(); ++i) {
      out << (i ? ", " : "") << fields[i].first << ": " << fields[i].second.to_string();
    }
    out << ")";
  }
  return out.str();
}

size_t Array::item_bytes() const {
  size_t n = dtype_size(dtype);
  for (size_t i = 1; i < shape.size(); ++i) n *= static_cast<size_t>(shape[i]);
  return n;
}

ArrayDict::ArrayDict(const Space& dict, int batch) : batch_(batch) {
  if (dict.kind != Space::Kind::dict) throw Error("ArrayDict needs a Dict space");
  for (const auto& [name, space] : dict.fields) {
    Array a;
    a.name = name;
    a.dtype = space.dtype;
    a.shape.push_back(batch);
    if (space.kind == Space::Kind::box) a.shape.insert(a.shape.end(), space.shape.begin(), space.shape.end());
    a.bytes.assign(a.item_bytes() * batch, 0);
    arrays_.push_back(std::move(a));
  }
}

bool ArrayDict::contains(std::string_view name) const {
  for (const Array& a : arrays_) {
    if (a.name == name) return true;
  }
  return false;
}

Array& ArrayDict::operator[](std::string_view name) {
  for (Array& a : arrays_) {
    if (a.name == name) return a;
  }
  throw Error("no array named '" + std::string(name) + "'");
}

const Array& ArrayDict::operator[](std::string_view name) const {
  return const_cast<ArrayDict&>(*this)[name];
}

void ArrayDict::copy_item(const ArrayDict& source, int from, int to) {
  for (size_t i = 0; i < arrays_.size(); ++i) {
    std::memcpy(arrays_[i].item(to), source.arrays_[i].item(from), arrays_[i].item_bytes());
  }
}

}  // namespace chore
