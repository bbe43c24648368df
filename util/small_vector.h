#pragma once
// A vector of trivially copyable elements whose first N live inside the object. The kinetic grid
// keeps one depth order per pixel, and most pixels hold one or two triangles: with the entries
// inline, a pixel change touches the pixel's own cache lines and not a separate allocation (that
// extra miss was the largest single cost of a boundary event).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>

namespace kinray {

template <class T, uint32_t N>
class SmallVector {
  static_assert(std::is_trivially_copyable_v<T> && N > 0);

 public:
  using value_type = T;
  using iterator = T*;
  using const_iterator = const T*;

  SmallVector() = default;
  SmallVector(const SmallVector&) = delete;
  SmallVector& operator=(const SmallVector&) = delete;
  SmallVector(SmallVector&& other) noexcept { take(other); }
  SmallVector& operator=(SmallVector&& other) noexcept {
    if (this != &other) {
      release();
      take(other);
    }
    return *this;
  }
  ~SmallVector() { release(); }

  [[nodiscard]] T* data() { return m_heap ? m_heap.get() : m_inline; }
  [[nodiscard]] const T* data() const { return m_heap ? m_heap.get() : m_inline; }
  [[nodiscard]] size_t size() const { return m_size; }
  [[nodiscard]] bool empty() const { return m_size == 0; }
  /// Elements it holds without allocating: N inline, or its allocation's size.
  [[nodiscard]] size_t capacity() const { return m_capacity; }
  /// Bytes allocated outside the object.
  [[nodiscard]] size_t heap_bytes() const { return m_heap ? m_capacity * sizeof(T) : 0; }

  [[nodiscard]] T& operator[](size_t i) { return data()[i]; }
  [[nodiscard]] const T& operator[](size_t i) const { return data()[i]; }
  [[nodiscard]] T& front() { return data()[0]; }
  [[nodiscard]] const T& front() const { return data()[0]; }
  [[nodiscard]] iterator begin() { return data(); }
  [[nodiscard]] iterator end() { return data() + m_size; }
  [[nodiscard]] const_iterator begin() const { return data(); }
  [[nodiscard]] const_iterator end() const { return data() + m_size; }

  void reserve(size_t n) {
    if (n <= m_capacity) return;
    auto grown = std::make_unique<T[]>(n);
    std::copy(begin(), end(), grown.get());
    m_heap = std::move(grown);
    m_capacity = uint32_t(n);
  }
  void push_back(const T& value) {
    if (m_size == m_capacity) reserve(size_t(m_capacity) * 2);
    data()[m_size++] = value;
  }
  iterator insert(const_iterator pos, const T& value) {
    const size_t at = size_t(pos - begin());
    if (m_size == m_capacity) reserve(size_t(m_capacity) * 2);
    T* d = data();
    std::copy_backward(d + at, d + m_size, d + m_size + 1);
    d[at] = value;
    ++m_size;
    return d + at;
  }
  iterator erase(const_iterator pos) {
    const size_t at = size_t(pos - begin());
    T* d = data();
    std::copy(d + at + 1, d + m_size, d + at);
    --m_size;
    return d + at;
  }
  /// Removes every element and keeps the capacity.
  void clear() { m_size = 0; }

 private:
  void take(SmallVector& other) {
    m_size = other.m_size;
    m_capacity = other.m_capacity;
    if (other.m_heap) {
      m_heap = std::move(other.m_heap);
    } else {
      std::copy(other.m_inline, other.m_inline + other.m_size, m_inline);
    }
    other.m_size = 0;
    other.m_capacity = N;
  }
  void release() {
    m_heap.reset();
    m_size = 0;
    m_capacity = N;
  }

  T m_inline[N] = {};
  std::unique_ptr<T[]> m_heap;
  uint32_t m_size = 0, m_capacity = N;
};

}  // namespace kinray
