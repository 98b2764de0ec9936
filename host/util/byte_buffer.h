// Values packed into and read back from a byte buffer, for messages between the ranks of an MPI
// job (render/rank_pass.cpp). Both ends are the same clpt build on the same kind of machine
// (docs/mpi.md), so values travel in the host's own representation; a reader that runs past the
// end throws std::out_of_range (a message of another shape: a bug, not user input).
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace clpt {

class ByteWriter {
 public:
  template <typename T>
  ByteWriter& put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "only plain values travel as bytes");
    append(&value, sizeof value);
    return *this;
  }
  ByteWriter& put(const std::string& text) {
    put(uint64_t(text.size()));
    append(text.data(), text.size());
    return *this;
  }
  template <typename T>
  ByteWriter& put_array(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>, "only plain values travel as bytes");
    put(uint64_t(values.size()));
    append(values.data(), values.size() * sizeof(T));
    return *this;
  }
  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  void append(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  std::vector<uint8_t> bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::vector<uint8_t>& bytes) : bytes_(bytes) {}
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>, "only plain values travel as bytes");
    T value;
    copy(&value, sizeof value);
    return value;
  }
  std::string get_string() {
    std::string text(size_t(get<uint64_t>()), '\0');
    copy(text.data(), text.size());
    return text;
  }
  template <typename T>
  std::vector<T> get_array() {
    std::vector<T> values(size_t(get<uint64_t>()));
    copy(values.data(), values.size() * sizeof(T));
    return values;
  }

 private:
  void copy(void* out, size_t size) {
    if (size > bytes_.size() - at_) throw std::out_of_range("ByteReader: message shorter than its contents");
    if (size) std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }
  const std::vector<uint8_t>& bytes_;
  size_t at_ = 0;
};

}  // namespace clpt
