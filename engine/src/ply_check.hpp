#pragma once
// Structural check of a PLY file before assimp reads it.
//
// assimp 5.2's PLY reader trusts its input: a header without end_header never returns, and
// counts larger than the data (element counts in the header, list lengths in the data) keep it
// looping for minutes or make it read past its buffers. This walks the header and every entry
// of every element, checking each count and list length against the bytes actually present,
// so assimp only ever sees files whose structure holds together. Values are not interpreted.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace sutura::engine::detail {

/// The first structural problem of the PLY file `bytes` in words a user reads, or nullopt.
/// When there is none and `triangles` is given, it receives the triangles the `face`
/// element's polygons make (k - 2 for a polygon of k corners). O(file size).
std::optional<std::string> ply_structure_problem(std::string_view bytes,
                                                 std::uint64_t* triangles = nullptr);

}  // namespace sutura::engine::detail
