#include "sutura/app/design_candidates.hpp"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "sutura/engine/atomic_file.hpp"

namespace sutura::app {

namespace {

using nlohmann::json;

// The line as written, its input paths absolute (they are relative to the session's file).
json with_absolute_inputs(json j, const std::filesystem::path& session_file) {
  if (j.value("op", "") != "load") return j;
  for (const char* key : {"file", "landmarks"})
    if (j.contains(key) && j[key].is_string()) {
      const std::filesystem::path p(j[key].get<std::string>());
      if (!p.is_absolute())
        j[key] = std::filesystem::absolute(session_file.parent_path() / p).lexically_normal().string();
    }
  return j;
}

}  // namespace

std::vector<DesignCandidate> emit_design_candidates(const Session& session, const std::filesystem::path& dir,
                                                    int count) {
  if (count < 2 || count > 1000) throw std::invalid_argument("--candidates: must be in [2, 1000]");
  std::vector<std::pair<std::string, std::string>> files;  // name, content
  std::vector<DesignCandidate> out;
  const std::string stem = session.file.stem().string();
  json header = {{"format", "sutura-session"}, {"version", session.version}, {"units", "mm"}};
  for (std::size_t i = 0; i < session.actions.size(); ++i) {
    const Action& a = session.actions[i];
    const auto* op = std::get_if<DesignPatchOp>(&a.op);
    if (op == nullptr) continue;
    std::string prefix;
    for (std::size_t k = 0; k < i; ++k)
      prefix += with_absolute_inputs(session.actions[k].source, session.file).dump() + "\n";
    const json& src = a.source;
    const std::string object = src.at("object").get<std::string>();
    json simulate = src.at("simulate");
    simulate["op"] = "simulate";
    if (!simulate.contains("objects") || simulate["objects"] == json::array())  // as design_patch reads it
      simulate["objects"] = json::array({object});
    json measure = src.at("measure");
    measure["op"] = "measure";
    measure["object"] = object;
    for (int k = 0; k < count; ++k) {
      // The ends exactly: they are design_patch's own first two candidates.
      const double width = k == count - 1 ? op->width_max
                                          : op->width_min + (op->width_max - op->width_min) * k / (count - 1);
      json patch = src.at("patch");
      patch["op"] = "patch";
      patch["object"] = object;
      patch["width"] = width;
      json h = header;
      h["description"] = "candidate " + std::to_string(k + 1) + " of " + std::to_string(count) +
                         " of the design_patch op at line " + std::to_string(a.line) + " of " +
                         session.file.filename().string() + ": its patch " + json(width).dump() + " mm wide";
      const std::string name = stem + "_line" + std::to_string(a.line) + "_" + std::to_string(k + 1) + ".jsonl";
      files.emplace_back(name, h.dump() + "\n" + prefix + patch.dump() + "\n" + simulate.dump() + "\n" +
                                   measure.dump() + "\n");
      out.push_back({a.line, width, dir / name});
    }
  }
  if (out.empty())
    throw std::invalid_argument(session.file.string() + " has no design_patch op: no candidates to write");
  json list = json::array();
  for (const DesignCandidate& c : out)
    list.push_back({{"line", c.line}, {"width_mm", c.width}, {"file", c.file.filename().string()}});
  files.emplace_back(stem + "_candidates.json", json({{"session", session.file.string()}, {"candidates", list}}).dump(1) + "\n");
  for (const auto& [name, text] : files)
    if (std::filesystem::exists(dir / name))
      throw std::invalid_argument((dir / name).string() + " exists already: candidates are never overwritten "
                                  "(remove them, or choose another directory)");
  std::filesystem::create_directories(dir);
  for (const auto& [name, text] : files) engine::write_file_atomically(dir / name, text);
  return out;
}

}  // namespace sutura::app
