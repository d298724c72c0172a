#pragma once
// Strong index types for mesh elements.
//
// Why: raw ints cross many APIs (topology edits, rest-shape maps, picking); a typed id makes
// passing a face index where a vertex index is expected a compile error. The payload is a
// plain 32-bit index into the owning mesh's flat arrays (geometry-central style), -1 = invalid.
#include <cstdint>
#include <functional>
#include <ostream>

namespace sutura::engine {

template <class Tag>
struct Id {
  std::int32_t value = -1;

  constexpr Id() = default;
  constexpr explicit Id(std::int32_t v) : value(v) {}
  constexpr explicit Id(std::size_t v) : value(static_cast<std::int32_t>(v)) {}

  [[nodiscard]] constexpr bool valid() const { return value >= 0; }
  [[nodiscard]] constexpr std::size_t index() const { return static_cast<std::size_t>(value); }

  friend constexpr bool operator==(Id a, Id b) { return a.value == b.value; }
  friend constexpr auto operator<=>(Id a, Id b) { return a.value <=> b.value; }
  friend std::ostream& operator<<(std::ostream& os, Id id) { return os << id.value; }
};

using VertexId = Id<struct VertexTag>;
using FaceId = Id<struct FaceTag>;
/// Half-edge k (0,1,2) of face f has id 3f+k and runs from corner k to corner (k+1)%3.
using HalfedgeId = Id<struct HalfedgeTag>;

}  // namespace sutura::engine

template <class Tag>
struct std::hash<sutura::engine::Id<Tag>> {
  std::size_t operator()(sutura::engine::Id<Tag> id) const noexcept {
    return std::hash<std::int32_t>{}(id.value);
  }
};
