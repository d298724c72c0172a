#pragma once
// Op parsers, one family per file (session_ops_scene.cpp, session_ops_simulation.cpp), and the
// field helpers they share. session.cpp dispatches on the op name through op_parsers().
#include <filesystem>
#include <string>
#include <vector>

#include "session_fields.hpp"
#include "sutura/app/session.hpp"

namespace sutura::app::detail {

using OpParse = Op (*)(Fields& f, const std::filesystem::path& session_file);

struct OpParser {
  const char* name;
  OpParse parse;
};

/// generate, load, snapshot, export, export_patch_template, report, plan_report.
const std::vector<OpParser>& scene_op_parsers();
/// material, constrain, fix, force, line_load, pressure, body_force, solve, unload, simulate,
/// probe, check.
const std::vector<OpParser>& simulation_op_parsers();
/// incise, join, patch, resect, remesh, measure, design_patch, distance, undo, redo
/// (session_ops_surgery.cpp).
const std::vector<OpParser>& surgery_op_parsers();
/// A simulate op's fields (design_patch's `simulate` part).
SimulateOp parse_simulate_op(Fields& f);

/// An output path field: relative, no escapes, one of `extensions` (lower case, with dot).
std::filesystem::path output_file(Fields& f, const std::string& key,
                                  const std::vector<std::string>& extensions);
/// The "object" field: letters, digits, '_' and '-'.
std::string object_name(Fields& f);
engine::Vec3 vec(const Vec3d& v);

}  // namespace sutura::app::detail
