// Observation and action spaces as data (Gymnasium's Box, Discrete, Dict), and
// the batched arrays that hold values of them.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace chore {

enum class DType { uint8, int32, float32, int64 };
size_t dtype_size(DType dtype);
const char* dtype_name(DType dtype);

struct Space {
  // Declared, not implicit: clang would check that it exists while
  // std::pair<std::string, Space> below is still being defined.
  Space();
  enum class Kind { box, discrete, dict };
  Kind kind = Kind::box;
  // box
  std::vector<int> shape;
  DType dtype = DType::float32;
  double low = 0, high = 0;  // the same bound for every element
  // discrete: values 0 .. n-1
  int64_t n = 0;
  // dict, in a fixed order
  std::vector<std::pair<std::string, Space>> fields;

  static Space box(std::vector<int> shape, DType dtype, double low, double high);
  static Space discrete(int64_t n);
  static Space dict(std::vector<std::pair<std::string, Space>> fields);

  size_t element_count() const;                          // box: product of shape; discrete: 1
  const Space& operator[](std::string_view name) const;  // dict field; throws chore::Error
  // e.g. Dict(rgb: Box(0, 255, (128, 128, 3), uint8), ...)
  std::string to_string() const;
};

// One array of a batch: a leading batch dimension, then the space's shape.
struct Array {
  std::string name;
  DType dtype = DType::float32;
  std::vector<int> shape;  // including the batch dimension
  std::vector<unsigned char> bytes;

  size_t item_bytes() const;  // bytes of one batch element
  void* item(int index) { return bytes.data() + index * item_bytes(); }
  const void* item(int index) const { return bytes.data() + index * item_bytes(); }
  template <class T>
  T* data() {
    return reinterpret_cast<T*>(bytes.data());
  }
  template <class T>
  const T* data() const {
    return reinterpret_cast<const T*>(bytes.data());
  }
};

// Named arrays for the fields of a Dict space with `batch` elements each,
// contiguous per field: (batch, H, W, 3) and so on.
class ArrayDict {
 public:
  ArrayDict() = default;
  ArrayDict(const Space& dict, int batch);
  int batch() const { return batch_; }
  const std::vector<Array>& arrays() const { return arrays_; }
  std::vector<Array>& arrays() { return arrays_; }
  Array& operator[](std::string_view name);
  const Array& operator[](std::string_view name) const;
  bool contains(std::string_view name) const;
  // Copies batch element `from` of `source` into element `to` of this dict.
  void copy_item(const ArrayDict& source, int from, int to);

 private:
  int batch_ = 0;
  std::vector<Array> arrays_;
};

}  // namespace chore
