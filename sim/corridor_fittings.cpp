// Corridor fittings placed along the walls (see corridor_fittings.h).
#include "trackbed/sim/corridor_fittings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "trackbed/common/option_error.h"
#include "trackbed/common/split_mix.h"

namespace trackbed::sim {

void CorridorFittings::Validate() const {
  option_check::Positive("light_spacing_m", light_spacing_m);
  option_check::Positive("radiator_spacing_m", radiator_spacing_m);
  option_check::Positive("notice_board_spacing_m", notice_board_spacing_m);
  option_check::Positive("extinguisher_spacing_m", extinguisher_spacing_m);
}

namespace {

namespace fs = fitting_size;

// One wall's face towards the route: points start + s · dir (s in [0, length]) at the
// wall's foot, `normal` pointing into the corridor.
struct FittedFace {
  Eigen::Vector2d start, dir, normal;
  double length = 0.0;
  double yaw_rad = 0.0;
  double base_z = 0.0;
  std::vector<std::pair<double, double>> walls;  // stretches other walls take
  struct Door {
    double s0, s1, top;  // stretch, frame included; the leaf's top above the base [m]
  };
  std::vector<Door> doors;
  std::vector<std::pair<double, double>> taken;  // doors, posters, fittings placed
};

// A uniform draw in [0, 1) from stream `k` of `seed`.
double FittingUnit(std::uint64_t seed, std::uint64_t k) {
  return static_cast<double>(split_mix::Stream(seed, k) >> 11) * 0x1.0p-53;
}

Eigen::Vector2d NearestOnRoute(const Eigen::Vector2d& p,
                               const std::vector<Eigen::Vector2d>& route) {
  Eigen::Vector2d best = route.front();
  for (std::size_t k = 1; k < route.size(); ++k) {
    const Eigen::Vector2d d = route[k] - route[k - 1];
    const double t = d.squaredNorm() > 0.0
                         ? std::clamp((p - route[k - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0)
                         : 0.0;
    const Eigen::Vector2d q = route[k - 1] + t * d;
    if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
  }
  return best;
}

bool IsWall(const StaticObject& o) {
  return o.kind == "wall" && o.shape == StaticObject::Shape::kBox;
}

double BaseOf(const StaticObject& o) { return std::isnan(o.base_z_m) ? 0.0 : o.base_z_m; }

// The footprint's corners of a box object.
std::vector<Eigen::Vector2d> BoxCorners(const StaticObject& o) {
  const Eigen::Vector2d ax(std::cos(o.yaw_rad), std::sin(o.yaw_rad));
  const Eigen::Vector2d ay(-ax.y(), ax.x());
  std::vector<Eigen::Vector2d> out;
  for (double sx : {-0.5, 0.5}) {
    for (double sy : {-0.5, 0.5}) {
      out.push_back(o.center_m + sx * o.size_m.x() * ax + sy * o.size_m.y() * ay);
    }
  }
  return out;
}

// The stretch [s0, s1] of `face` that box `o` covers within `depth` in front of the
// face, if any.
bool StretchOnFace(const FittedFace& face, const StaticObject& o, double depth,
                   std::pair<double, double>* out) {
  double s0 = std::numeric_limits<double>::infinity(), s1 = -s0;
  double n0 = s0, n1 = -s0;
  for (const Eigen::Vector2d& q : BoxCorners(o)) {
    const Eigen::Vector2d r = q - face.start;
    s0 = std::min(s0, r.dot(face.dir));
    s1 = std::max(s1, r.dot(face.dir));
    n0 = std::min(n0, r.dot(face.normal));
    n1 = std::max(n1, r.dot(face.normal));
  }
  if (n1 < -1e-3 || n0 > depth || s1 < 0.0 || s0 > face.length) return false;
  *out = {s0, s1};
  return true;
}

// The face of wall `w` towards the route, with what blocks it.
FittedFace FaceOf(std::size_t w, const std::vector<StaticObject>& objects,
                  const std::vector<Eigen::Vector2d>& route) {
  const StaticObject& wall = objects[w];
  FittedFace f;
  f.dir = Eigen::Vector2d(std::cos(wall.yaw_rad), std::sin(wall.yaw_rad));
  Eigen::Vector2d n(-f.dir.y(), f.dir.x());
  if (n.dot(NearestOnRoute(wall.center_m, route) - wall.center_m) < 0.0) n = -n;
  f.normal = n;
  f.length = wall.size_m.x();
  f.start = wall.center_m + 0.5 * wall.size_m.y() * n - 0.5 * f.length * f.dir;
  f.yaw_rad = wall.yaw_rad;
  f.base_z = BaseOf(wall);
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const StaticObject& o = objects[k];
    std::pair<double, double> s;
    if (k == w || o.shape != StaticObject::Shape::kBox) continue;
    if (IsWall(o) && StretchOnFace(f, o, 0.5, &s)) f.walls.push_back(s);
    if ((o.kind == "door" || o.kind == "poster") && StretchOnFace(f, o, 0.1, &s)) {
      if (o.kind == "door") {
        f.doors.push_back({s.first - fs::kFrameFaceM, s.second + fs::kFrameFaceM,
                           BaseOf(o) + o.size_m.z() - f.base_z});
      }
      f.taken.push_back({s.first - fs::kFrameFaceM, s.second + fs::kFrameFaceM});
    }
  }
  return f;
}

// A box fitting on `face`: `length` along the face about `centre`, `depth` out of the
// wall starting `gap` from it, `height` tall from `z0` above the wall's base.
StaticObject BoxOnFace(const FittedFace& face, const char* kind, double centre, double length,
                       double gap, double depth, double z0, double height, bool collides) {
  StaticObject o;
  o.shape = StaticObject::Shape::kBox;
  o.kind = kind;
  o.appearance = kind;
  o.center_m = face.start + centre * face.dir + (gap + 0.5 * depth) * face.normal;
  o.yaw_rad = face.yaw_rad;
  o.size_m = {length, depth, height};
  o.base_z_m = face.base_z + z0;
  o.collides = collides;
  return o;
}

bool Free(const std::vector<std::pair<double, double>>& taken, double s0, double s1) {
  return std::none_of(taken.begin(), taken.end(), [&](const std::pair<double, double>& t) {
    return s1 > t.first && s0 < t.second;
  });
}

// The stretches of [0, length] that `blocked` leaves free, each at least `min_length`.
std::vector<std::pair<double, double>> FreeStretches(std::vector<std::pair<double, double>> blocked,
                                                     double length, double min_length) {
  std::sort(blocked.begin(), blocked.end());
  std::vector<std::pair<double, double>> out;
  double from = 0.0;
  for (const auto& [b0, b1] : blocked) {
    if (b0 - from >= min_length) out.push_back({from, std::min(b0, length)});
    from = std::max(from, b1);
  }
  if (length - from >= min_length) out.push_back({from, length});
  return out;
}

// Skirting along the face's free stretches; a frame and a switch about each door.
void AddDoorsAndSkirting(const CorridorFittings& spec, FittedFace& face, std::uint64_t seed,
                         std::vector<StaticObject>* out) {
  if (spec.skirting) {
    std::vector<std::pair<double, double>> blocked = face.walls;
    for (const FittedFace::Door& d : face.doors) blocked.push_back({d.s0, d.s1});
    for (const auto& [s0, s1] : FreeStretches(blocked, face.length, 0.05)) {
      out->push_back(BoxOnFace(face, "skirting", 0.5 * (s0 + s1), s1 - s0, 0.0,
                               fs::kSkirtingThicknessM, 0.0, fs::kSkirtingHeightM, false));
    }
  }
  for (std::size_t d = 0; d < face.doors.size(); ++d) {
    const double s0 = face.doors[d].s0, s1 = face.doors[d].s1, head = face.doors[d].top;
    const double leaf0 = s0 + fs::kFrameFaceM, leaf1 = s1 - fs::kFrameFaceM;
    if (spec.door_frames) {
      const double f = fs::kFrameFaceM, depth = fs::kFrameDepthM;
      out->push_back(BoxOnFace(face, "door_frame", leaf0 - 0.5 * f, f, 0, depth, 0, head, false));
      out->push_back(BoxOnFace(face, "door_frame", leaf1 + 0.5 * f, f, 0, depth, 0, head, false));
      out->push_back(BoxOnFace(face, "door_frame", 0.5 * (s0 + s1), leaf1 - leaf0 + 2 * f, 0, depth,
                               head, f, false));
    }
    if (spec.switches) {
      const bool after = FittingUnit(seed, d) < 0.5;
      const double c = after ? s1 + fs::kSwitchBesideFrameM : s0 - fs::kSwitchBesideFrameM;
      const double h = 0.5 * fs::kSwitchPlateM;
      if (c - h < 0.0 || c + h > face.length || !Free(face.walls, c - h, c + h)) continue;
      out->push_back(BoxOnFace(face, "switch_plate", c, fs::kSwitchPlateM, 0, fs::kSwitchDepthM,
                               fs::kSwitchCentreHeightM - h, fs::kSwitchPlateM, false));
      face.taken.push_back({c - h, c + h});
    }
  }
}

// One wall-mounted fitting kind: one per `spacing` of face, each at a seeded place in
// its share of the face, dropped where it would meet what is there.
template <class Make>
void PlaceAlongFace(FittedFace& face, double spacing, std::uint64_t seed, Make&& make,
                    std::vector<StaticObject>* out) {
  const int count = static_cast<int>(std::floor(face.length / spacing));
  for (int k = 0; k < count; ++k) {
    const double share = face.length / count;
    const double centre = share * (k + 0.25 + 0.5 * FittingUnit(seed, 2 * k));
    const StaticObject o = make(centre, FittingUnit(seed, 2 * k + 1));
    const double half =
        0.5 * (o.shape == StaticObject::Shape::kBox ? o.size_m.x() : 2 * o.radius_m);
    const double s0 = centre - half - fs::kFittingGapM, s1 = centre + half + fs::kFittingGapM;
    if (s0 < 0.0 || s1 > face.length || !Free(face.walls, s0, s1) || !Free(face.taken, s0, s1)) {
      continue;
    }
    face.taken.push_back({centre - half, centre + half});
    out->push_back(o);
  }
}

void AddWallFittings(const CorridorFittings& spec, FittedFace& face, std::uint64_t seed,
                     std::vector<StaticObject>* out) {
  if (spec.radiators) {
    PlaceAlongFace(
        face, spec.radiator_spacing_m, split_mix::Stream(seed, 1),
        [&](double c, double u) {
          const double l = fs::kRadiatorLengthsM[std::min(3, static_cast<int>(4 * u))];
          return BoxOnFace(face, "radiator", c, l, fs::kRadiatorWallGapM, fs::kRadiatorDepthM,
                           fs::kRadiatorFloorGapM, fs::kRadiatorHeightM, true);
        },
        out);
  }
  if (spec.notice_boards) {
    PlaceAlongFace(
        face, spec.notice_board_spacing_m, split_mix::Stream(seed, 2),
        [&](double c, double) {
          const double h = fs::kBoardHeightM;
          return BoxOnFace(face, "notice_board", c, fs::kBoardWidthM, 0.0, fs::kBoardDepthM,
                           fs::kBoardCentreHeightM - 0.5 * h, h, false);
        },
        out);
  }
  if (spec.extinguishers) {
    PlaceAlongFace(
        face, spec.extinguisher_spacing_m, split_mix::Stream(seed, 3),
        [&](double c, double) {
          StaticObject o;
          o.shape = StaticObject::Shape::kCylinder;
          o.kind = "extinguisher";
          o.appearance = "extinguisher";
          o.radius_m = fs::kExtinguisherRadiusM;
          o.height_m = fs::kExtinguisherHeightM;
          o.center_m =
              face.start + c * face.dir + (fs::kExtinguisherWallGapM + o.radius_m) * face.normal;
          o.base_z_m = face.base_z + fs::kExtinguisherTopM - o.height_m;
          return o;
        },
        out);
  }
}

// Ceiling lights along the route, `spacing` apart, the first spacing/2 from its start.
void AddCeilingLights(double spacing, const std::vector<Eigen::Vector2d>& route, double ceiling_z,
                      std::vector<StaticObject>* out) {
  double along = 0.5 * spacing, walked = 0.0;
  for (std::size_t k = 1; k < route.size(); ++k) {
    const Eigen::Vector2d d = route[k] - route[k - 1];
    const double length = d.norm();
    for (; along <= walked + length && length > 0.0; along += spacing) {
      StaticObject o;
      o.kind = "luminaire";
      o.appearance = "luminaire";
      o.center_m = route[k - 1] + (along - walked) / length * d;
      o.yaw_rad = std::atan2(d.y(), d.x());
      o.size_m = {fs::kLuminaireSideM, fs::kLuminaireSideM, fs::kLuminaireDepthM};
      o.base_z_m = ceiling_z - fs::kLuminaireDepthM;
      o.collides = false;
      out->push_back(o);
    }
    walked += length;
  }
}

}  // namespace

std::vector<StaticObject> CorridorFittingObjects(const CorridorFittings& spec,
                                                 const std::vector<StaticObject>& objects,
                                                 const std::vector<Eigen::Vector2d>& route,
                                                 double ceiling_height_m,
                                                 std::uint64_t stream_seed) {
  spec.Validate();
  if (route.empty()) throw OptionError("fittings", "needs a route (drive.waypoints) to face");
  if (spec.ceiling_lights && !(ceiling_height_m > 0.0)) {
    throw OptionError("fittings.ceiling_lights",
                      "needs a ceiling (scene.appearance.ceiling_height_m > 0)");
  }
  std::vector<StaticObject> out;
  for (std::size_t w = 0; w < objects.size(); ++w) {
    if (!IsWall(objects[w])) continue;
    FittedFace face = FaceOf(w, objects, route);
    const std::uint64_t seed = split_mix::Stream(stream_seed, w);
    AddDoorsAndSkirting(spec, face, split_mix::Stream(seed, 0), &out);
    AddWallFittings(spec, face, seed, &out);
  }
  if (spec.ceiling_lights) AddCeilingLights(spec.light_spacing_m, route, ceiling_height_m, &out);
  return out;
}

}  // namespace trackbed::sim
