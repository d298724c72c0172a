#include "sutura/app/report.hpp"

#include <cstdio>
#include <cstring>

namespace sutura::app {

std::string position_hash(const engine::SurfaceMesh& mesh) {
  // FNV-1a over the IEEE-754 bytes: any change of any bit of any coordinate changes the hash.
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const auto& p : mesh.positions()) {
    for (int i = 0; i < 3; ++i) {
      unsigned char bytes[sizeof(double)];
      const double v = p[i];
      std::memcpy(bytes, &v, sizeof v);
      for (unsigned char b : bytes) {
        h ^= b;
        h *= 0x100000001b3ULL;
      }
    }
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

nlohmann::json mesh_quality_json(const engine::MeshQuality& q, const engine::SurfaceMesh* mesh) {
  nlohmann::json j = {{"faces", q.faces},
                      {"min_angle_deg", q.min_angle_deg},
                      {"p5_angle_deg", q.p5_angle_deg},
                      {"min_edge_mm", q.min_edge},
                      {"max_edge_mm", q.max_edge}};
  if (mesh && q.worst_face.valid() && q.worst_face.index() < mesh->num_faces()) {
    const auto v = mesh->face_vertices(q.worst_face);
    const engine::Vec3 c = (mesh->position(v[0]) + mesh->position(v[1]) + mesh->position(v[2])) / 3.0;
    j["worst_face"] = q.worst_face.index();
    j["worst_face_centroid"] = {c.x(), c.y(), c.z()};
  }
  return j;
}

nlohmann::json hausdorff_json(const engine::HausdorffDistance& h) {
  return {{"a_to_b_mm", h.a_to_b},       {"b_to_a_mm", h.b_to_a},
          {"symmetric_mm", h.symmetric}, {"mean_a_to_b_mm", h.mean_a_to_b},
          {"mean_b_to_a_mm", h.mean_b_to_a},
          {"a_to_b_at", {h.a_to_b_at.x(), h.a_to_b_at.y(), h.a_to_b_at.z()}},
          {"b_to_a_at", {h.b_to_a_at.x(), h.b_to_a_at.y(), h.b_to_a_at.z()}},
          {"samples_a", h.samples_a},
          {"samples_b", h.samples_b}};
}

nlohmann::json object_summary(const SceneObject& object) {
  const auto& m = object.mesh;
  const auto box = m.bounds();
  nlohmann::json loops = nlohmann::json::array();
  for (const auto& loop : m.boundary_loops()) loops.push_back(loop.size());
  return {
      {"vertices", m.num_vertices()},
      {"faces", m.num_faces()},
      {"edges", m.num_edges()},
      {"boundary_loop_sizes", loops},
      {"area_mm2", m.total_area()},
      {"bounds_min", {box.min().x(), box.min().y(), box.min().z()}},
      {"bounds_max", {box.max().x(), box.max().y(), box.max().z()}},
      {"position_hash", position_hash(m)},
      {"quality", mesh_quality_json(engine::mesh_quality(m), &m)},
      {"rest_quality", mesh_quality_json(engine::rest_quality(object.sim.rest), &m)},
  };
}

}  // namespace sutura::app
