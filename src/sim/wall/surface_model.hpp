// Internal: how the particle's surface meets the wall — the contact phase's support and rest model, chosen
// once per run (Run::surface) from SettleParams::smooth:
//   polyhedral  the paper's model. The contact set is the ε band, whose crossings are events until the
//               stability test passes; Algorithm 1 types it (a point, a line, a surface), the support follows
//               (a point, the best-fit line, the previous axis; the impact law on several touching points),
//               and the rest begins once the paper's stability test (§2.4) has passed and the touching points
//               hold the centre of mass.
//   smooth      a discretised smooth surface: always a point contact, turning about its lowest
//               touching point (impact_support.hpp, choose_smooth), with events at the wall only and no
//               stability test: it rests where three touching points land around the centre of mass.
// Each decision that differs is a member, so a call site says which rule it applies; the phases never test
// the kind itself.
#pragma once

#include <vector>

#include "contact_type.hpp"
#include "repose/sim/settle.hpp"

namespace repose::sim {

class SurfaceModel {
 public:
  enum class Kind { polyhedral, smooth };
  explicit SurfaceModel(Kind kind) : kind_(kind) {}

  Kind kind() const { return kind_; }
  /// Whether Algorithm 1 types the contact set and the paper's support rules follow it (a line, the previous
  /// axis, the impact law on several touching points); a smooth surface's contact is always a point.
  bool has_contact_types() const { return kind_ == Kind::polyhedral; }
  /// The contact type of the contact points' footprints on the wall (Algorithm 1, its best fit in `fit`), or
  /// a point (`fit` untouched).
  ContactType contact_type(const std::vector<Vec3>& footprints, double rss_threshold, LineFit* fit) const {
    return has_contact_types() ? classify_contact(footprints, rss_threshold, fit) : ContactType::point;
  }
  /// Whether the paper's stability test (§2.4) is taken on the contact set; a smooth surface has none.
  bool has_stability_test() const { return kind_ == Kind::polyhedral; }
  /// Whether the ε band's crossings are events (until the stability test passes): they change the contact set
  /// the type and the stability test are taken on. A smooth surface's contact set decides neither, so its
  /// events are at the wall only.
  bool has_band_events() const { return kind_ == Kind::polyhedral; }
  /// The level (length) to which a step collects the vertices that can cause an event: `band_level`, the
  /// band's, or the wall's for a smooth surface.
  double candidate_level(double band_level) const { return has_band_events() ? band_level : 0.0; }
  /// The kind of a rest on a hull face whose plane is `flat` (face_is_flat).
  RestKind rest_kind(bool flat) const {
    if (kind_ == Kind::smooth) return RestKind::smooth;
    return flat ? RestKind::surface : RestKind::points;
  }

 private:
  Kind kind_;
};

}  // namespace repose::sim
