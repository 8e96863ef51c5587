// SPDX-License-Identifier: BSD-3-Clause
// Large arrays of floats held by shared ownership, so that a grid's samples
// and the VTK array that shows them are one memory, not two.
#ifndef brume_FloatBuffer_h
#define brume_FloatBuffer_h

#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>

namespace brume
{

/**
 * A fixed number of floats whose memory one or more owners share: a
 * brume::BrickedGrid's samples and the vtkFloatArray of the reconstruction's
 * output that wraps them (vtkBrumeSharedArray), a brume::GridDensity's values
 * and the vtkDataArray they were read into. The floats are written while the
 * buffer is made, then only read.
 *
 * Allocate() leaves the floats unset: a 512^3 grid's 0.5 GB is touched once,
 * by whoever fills it, not zeroed first. Buffers of 2 MB and more are mapped
 * on their own and advised into huge pages where the system offers them
 * (Linux's transparent huge pages): a first touch then costs one fault per
 * 2 MB instead of one per 4 kB, which on a virtual machine is most of the
 * cost of filling a large grid. The mapping of such a buffer that no one
 * holds any more is kept (its pages the system's to take back when it
 * needs them) for the next large Allocate() of about its size, which then
 * writes into pages already faulted in: a grid sampled again after an
 * edit costs no new pages. Kept mappings are unmapped as soon as a large
 * buffer is allocated that none of them serves, before it is mapped, so
 * that a new large buffer is never mapped beside kept ones.
 */
class FloatBuffer
{
public:
  FloatBuffer() = default;
  /// `n` floats, not initialized.
  static FloatBuffer Allocate(std::size_t n);
  /// `n` floats at `data`, kept alive by `owner` (an array of someone else's).
  static FloatBuffer Wrap(const float* data, std::size_t n, std::shared_ptr<const void> owner);
  /**
   * Gives the kept mappings of buffers no one holds any more back to the
   * system now, for a program that allocates no more large buffers (one
   * that draws its last image): kept pages count in its resident memory
   * until the system takes them back. Returns the bytes unmapped.
   */
  static std::size_t ReleaseKept();

  float* Data() { return this->Memory.get(); }
  const float* Data() const { return this->Memory.get(); }
  std::size_t Size() const { return this->Count; }
  bool Empty() const { return this->Count == 0; }
  float operator[](std::size_t i) const { return this->Memory.get()[i]; }
  const float* begin() const { return this->Memory.get(); }
  const float* end() const { return this->Memory.get() + this->Count; }

  /**
   * Keeps the first `n` floats (n <= Size()): the memory past them goes
   * back to the system where the buffer was mapped on its own (whole
   * pages), else the floats are copied into a buffer of their own size.
   */
  void Truncate(std::size_t n);

  /// The memory, for an owner that shares it (it stays valid while any holds it).
  const std::shared_ptr<float>& Share() const { return this->Memory; }

  /// Equal sizes and equal floats.
  friend bool operator==(const FloatBuffer& a, const FloatBuffer& b);
  friend bool operator!=(const FloatBuffer& a, const FloatBuffer& b) { return !(a == b); }

private:
  std::shared_ptr<float> Memory;
  std::size_t Count = 0;
};

/**
 * A grid's values in the type its array holds them: 32-bit floats, or 8-
 * and 16-bit integers read as the numbers they are, so that a scan's
 * 512^3 bytes take 128 MB, not the 512 MB of their floats. Integers are
 * only read in place (Wrap(), an array someone else holds); floats may be
 * a buffer of the grid's own.
 */
class TypedValues
{
public:
  enum class Type
  {
    Float32,
    UInt8,
    UInt16,
    Int16
  };

  TypedValues() = default;
  /// Floats of the grid's own (or wrapped: FloatBuffer::Wrap()).
  explicit TypedValues(FloatBuffer floats);
  /// `n` values at `data` (8- or 16-bit integers), kept alive by `owner`
  /// (null: the caller keeps them alive).
  template <typename T>
  static TypedValues Wrap(const T* data, std::size_t n, std::shared_ptr<const void> owner)
  {
    TypedValues values;
    values.Count = n;
    values.Owner = std::move(owner);
    if constexpr (std::is_same_v<T, std::uint8_t>)
    {
      values.Kind = Type::UInt8;
      values.Bytes8 = data;
    }
    else if constexpr (std::is_same_v<T, std::uint16_t>)
    {
      values.Kind = Type::UInt16;
      values.Unsigned16 = data;
    }
    else
    {
      static_assert(std::is_same_v<T, std::int16_t>, "8- or 16-bit integers");
      values.Kind = Type::Int16;
      values.Signed16 = data;
    }
    return values;
  }

  /// Value i as a float (exact for every type held).
  float operator[](std::size_t i) const
  {
    switch (this->Kind)
    {
      case Type::UInt8:
        return static_cast<float>(this->Bytes8[i]);
      case Type::UInt16:
        return static_cast<float>(this->Unsigned16[i]);
      case Type::Int16:
        return static_cast<float>(this->Signed16[i]);
      case Type::Float32:
        break;
    }
    return this->Floats[i];
  }
  /// f(values), `values` a pointer to the values in their own type: loops
  /// over many values choose the type once, not per value.
  template <typename F>
  decltype(auto) Visit(F&& f) const
  {
    switch (this->Kind)
    {
      case Type::UInt8:
        return f(this->Bytes8);
      case Type::UInt16:
        return f(this->Unsigned16);
      case Type::Int16:
        return f(this->Signed16);
      case Type::Float32:
        break;
    }
    return f(this->Floats);
  }
  std::size_t Size() const { return this->Count; }
  bool Empty() const { return this->Count == 0; }
  Type GetType() const { return this->Kind; }
  /// The bytes the values take.
  std::size_t GetMemorySize() const;
  /// Where the values are (a test's check that an array was read in place).
  const void* Address() const;

private:
  Type Kind = Type::Float32;
  std::size_t Count = 0;
  FloatBuffer FloatValues;
  std::shared_ptr<const void> Owner; // of integers wrapped
  const float* Floats = nullptr;
  const std::uint8_t* Bytes8 = nullptr;
  const std::uint16_t* Unsigned16 = nullptr;
  const std::int16_t* Signed16 = nullptr;
};

} // namespace brume

#endif
