#pragma once
// The cutting template of a sewn-in patch: its rest shape laid out flat (engine::unfold_rest)
// on a page at true scale, as the surgeon cuts it from the sheet. One place for the
// `export_patch_template` op and the planning window.
//
// On the page (render::VectorPage, mm): the seam (dashed: the line the sutures run along),
// the cut line a seam allowance outside it (solid; round corners), a bite mark across the
// seam every `bite_spacing_mm` of its length starting at its proximal end, "PROXIMAL" and
// "DISTAL" at the ends of the patch's long axis, a 10 mm scale bar to check the print, and
// the figures below. The patch is seen from its outer (adventitial) side, never mirrored.
#include <string>
#include <vector>

#include "sutura/app/workspace.hpp"
#include "sutura/render/vector_page.hpp"

namespace sutura::app {

struct PatchTemplateOptions {
  /// 1-based: the patches of an object are its materials after the first (the wall) that are
  /// sewn in (a vertex shared with a face of another material), in the order they were made;
  /// a part added beside the object (generate with append) is not one.
  int patch = 1;
  /// A point near the patch's proximal end, in the current shape (mm): the seam vertex
  /// nearest to it is the top of the template and the first bite mark.
  engine::Vec3 proximal = engine::Vec3::Zero();
  double bite_spacing_mm = 1.0;   ///< > 0
  double seam_allowance_mm = 2.0; ///< >= 0: how far outside the seam the cut line runs
};

struct PatchTemplate {
  render::VectorPage page;
  double seam_length_mm = 0.0;  ///< the seam polygon's length on the page
  double area_mm2 = 0.0;        ///< the area it encloses
  double rest_seam_length_mm = 0.0, rest_area_mm2 = 0.0;  ///< of the patch's rest shape
  double cut_length_mm = 0.0;   ///< the cut line's length
  /// Largest disagreement of the rest shape's faces in the plane (engine::FlatLayout): how far
  /// the rest shape is from a developable cut; round-off for a patch that is still as cut.
  double max_gap_mm = 0.0;
  double length_mm = 0.0, width_mm = 0.0;  ///< extent along and across the long axis
  int bites = 0;
  std::size_t faces = 0;
};

/// The material indices (into obj.sim.materials) of the object's patches, in order. O(F).
std::vector<int> patch_materials(const SceneObject& obj);

/// The template of patch `options.patch` of `obj`; its long axis is upright with the seam
/// vertex nearest `options.proximal` on the upper side. Throws std::invalid_argument naming
/// the problem: no patch, a patch number out of range, a bite spacing outside [0.1, 20] mm, a
/// seam allowance outside [0, 20] mm, a non-finite proximal point; engine::InvalidArgument
/// for a patch whose faces are not one disk (engine::unfold_rest). Cost O(V + F).
PatchTemplate make_patch_template(const SceneObject& obj, const std::string& heading,
                                  const PatchTemplateOptions& options);

}  // namespace sutura::app
