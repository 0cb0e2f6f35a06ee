// Binary archive for checkpoints: a byte string of tagged, length-prefixed records of
// trivially copyable values, written in one piece with write_file_atomic (so a checkpoint
// on disk is always complete) and read back with checks (tag, sizes, truncation).
//
//   ArchiveWriter w; w.tag("dem"); w.put(t); w.put_vector(p.x); ... write_file_atomic(path, w.bytes());
//   ArchiveReader r(read_file(path), path); r.tag("dem"); r.get(t); r.get_vector(p.x); ...
//
// The layout is the machine's (little-endian x86-64, IEEE doubles): checkpoints restart
// on the same kind of machine; they are not an exchange format (snapshots are).
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.hpp"

namespace cgdem::io {

class ArchiveWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    raw(&v, sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(v.size());
    put<uint64_t>(sizeof(T));
    raw(v.data(), v.size() * sizeof(T));
  }
  // n elements of T, element k being at(k): the layout of put_vector, without the vector.
  template <class T, class At>
  void put_generated(size_t n, At at) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(n);
    put<uint64_t>(sizeof(T));
    buf_.reserve(buf_.size() + n * sizeof(T));
    for (size_t k = 0; k < n; ++k) {
      const T x = at(k);
      raw(&x, sizeof(T));
    }
  }
  void put_string(const std::string& s) {
    put<uint64_t>(s.size());
    raw(s.data(), s.size());
  }
  // A section marker, checked on reading.
  void tag(const std::string& name) { put_string("@" + name); }
  const std::string& bytes() const { return buf_; }

 private:
  void raw(const void* p, size_t n) { buf_.append(static_cast<const char*>(p), n); }
  std::string buf_;
};

class ArchiveReader {
 public:
  ArchiveReader(std::string bytes, std::string name) : buf_(std::move(bytes)), name_(std::move(name)) {}

  template <class T>
  void get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    raw(&v, sizeof(T));
  }
  template <class T>
  T get() {
    T v;
    get(v);
    return v;
  }
  template <class T>
  void get_vector(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto n = get<uint64_t>(), size = get<uint64_t>();
    if (size != sizeof(T)) fail("a record's element size differs (written by a different build?)");
    if (n > (buf_.size() - pos_) / (size ? size : 1)) fail("truncated");
    v.resize(n);
    raw(v.data(), n * sizeof(T));
  }
  // What put_vector or put_generated wrote, element by element: size(n), then each(k, x).
  template <class T, class Size, class Each>
  void get_generated(Size size, Each each) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto n = get<uint64_t>(), bytes = get<uint64_t>();
    if (bytes != sizeof(T)) fail("a record's element size differs (written by a different build?)");
    if (n > (buf_.size() - pos_) / sizeof(T)) fail("truncated");
    size(static_cast<size_t>(n));
    for (size_t k = 0; k < n; ++k) {
      T x;
      raw(&x, sizeof(T));
      each(k, x);
    }
  }
  std::string get_string() {
    const auto n = get<uint64_t>();
    if (n > buf_.size() - pos_) fail("truncated");
    std::string s = buf_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  void tag(const std::string& name) {
    if (get_string() != "@" + name) fail("section '" + name + "' not found where expected");
  }
  bool at_end() const { return pos_ == buf_.size(); }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error("checkpoint " + name_ + ": " + what + " (byte " + std::to_string(pos_) + ")");
  }
  void raw(void* p, size_t n) {
    if (n > buf_.size() - pos_) fail("truncated");
    std::memcpy(p, buf_.data() + pos_, n);
    pos_ += n;
  }
  std::string buf_, name_;
  size_t pos_ = 0;
};

}  // namespace cgdem::io
