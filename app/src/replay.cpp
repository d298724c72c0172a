#include "sutura/app/replay.hpp"

#include <chrono>
#include <iomanip>
#include <ostream>

#include "snapshot.hpp"
#include "sutura/app/output_paths.hpp"
#include "sutura/app/report.hpp"
#include "sutura/engine/atomic_file.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/mesh_io.hpp"
#include "sutura/render/context.hpp"

namespace sutura::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Mutable state of one replay: the objects, the report being built and the renderer.
struct Run {
  const Session& session;
  const ReplayOptions& options;
  Workspace workspace;
  SnapshotRenderer snapshots;
  json actions = json::array();
  json outputs = json::array();

  fs::path output(const fs::path& relative) {
    fs::path p = resolve_output_path(options.out_dir, relative);
    outputs.push_back(relative.generic_string());
    return p;
  }

  SceneObject& object(const std::string& name) {
    SceneObject* o = workspace.find(name);
    if (o == nullptr)
      throw std::runtime_error("no object named '" + name + "' (objects: " + workspace.names() +
                               ")");
    return *o;
  }

  json report(const std::string& status, const std::string& error, double total) const {
    json objects = json::object();
    for (const auto& o : workspace.objects()) objects[o.name] = object_summary(o);
    json r = {{"sutura_version", SUTURA_VERSION},
              {"session", session.file.generic_string()},
              {"description", session.description},
              {"status", status},
              {"actions", actions},
              {"objects", objects},
              {"outputs", outputs},
              {"total_seconds", total}};
    if (!error.empty()) r["error"] = error;
    return r;
  }

  void write_report(const fs::path& relative, const json& r) {
    engine::write_file_atomically(output(relative), r.dump(2) + "\n");
  }

  json execute(const GenerateOp& op) {
    engine::SurfaceMesh mesh = std::visit(
        [](const auto& p) -> engine::SurfaceMesh {
          using P = std::decay_t<decltype(p)>;
          if constexpr (std::is_same_v<P, engine::TubeParams>) return engine::make_tube(p);
          else if constexpr (std::is_same_v<P, engine::StripParams>) return engine::make_strip(p);
          else return engine::make_patch(p);
        },
        op.params);
    const engine::Vec3 t(op.translate[0], op.translate[1], op.translate[2]);
    if (!t.isZero()) {
      std::vector<engine::Vec3> moved = mesh.positions();
      for (auto& p : moved) p += t;
      mesh.set_positions(std::move(moved));
    }
    const auto& obj = workspace.add(op.object, std::move(mesh));
    return {{"object", op.object}, {"vertices", obj.mesh.num_vertices()},
            {"faces", obj.mesh.num_faces()}};
  }

  json execute(const LoadOp& op) {
    engine::ImportOptions io;
    io.weld_tolerance = op.weld_tolerance;
    const auto& obj = workspace.add(op.object, engine::load_mesh(op.file, io));
    return {{"object", op.object}, {"file", op.file.generic_string()},
            {"vertices", obj.mesh.num_vertices()}, {"faces", obj.mesh.num_faces()}};
  }

  json execute(const SnapshotOp& op) {
    render::Image image = snapshots.render(op, workspace);
    const std::vector<std::uint8_t> png = render::encode_png(image);
    engine::write_file_atomically(
        output(op.file), std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    return {{"file", op.file.generic_string()}, {"width", image.width}, {"height", image.height}};
  }

  json execute(const ExportOp& op) {
    engine::save_mesh(object(op.object).mesh, output(op.file));
    return {{"object", op.object}, {"file", op.file.generic_string()}};
  }

  json execute(const ReportOp& op, double elapsed) {
    write_report(op.file, report("running", {}, elapsed));
    return {{"file", op.file.generic_string()}};
  }
};

}  // namespace

ReplayResult replay(const Session& session, const ReplayOptions& options) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto seconds_since = [](clock::time_point t) {
    return std::chrono::duration<double>(clock::now() - t).count();
  };

  Run run{session, options, {}, {}, json::array(), json::array()};
  fs::create_directories(options.out_dir);
  const std::size_t n = session.actions.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Action& a = session.actions[i];
    const auto t0 = clock::now();
    if (options.progress)
      *options.progress << "[" << (i + 1) << "/" << n << "] line " << a.line << ": " << a.name
                        << std::flush;
    json details;
    try {
      details = std::visit(
          [&](const auto& op) -> json {
            if constexpr (std::is_same_v<std::decay_t<decltype(op)>, ReportOp>)
              return run.execute(op, seconds_since(start));
            else
              return run.execute(op);
          },
          a.op);
    } catch (const std::exception& e) {
      if (options.progress) *options.progress << " FAILED" << std::endl;
      const SessionError error(session.file.string(), a.line, a.name, "", e.what());
      try {
        run.write_report("report.json", run.report("failed", error.what(), seconds_since(start)));
      } catch (const std::exception&) {
        // The original error matters more than a report that could not be written.
      }
      throw error;
    }
    const double dt = seconds_since(t0);
    details["line"] = a.line;
    details["op"] = a.name;
    details["seconds"] = dt;
    run.actions.push_back(details);
    if (options.progress)
      *options.progress << " (" << std::fixed << std::setprecision(3) << dt << " s)"
                        << std::defaultfloat << std::endl;
  }
  ReplayResult result;
  result.report = run.report("ok", {}, seconds_since(start));
  run.write_report("report.json", result.report);
  result.report["outputs"] = run.outputs;
  result.workspace = std::move(run.workspace);
  return result;
}

}  // namespace sutura::app
