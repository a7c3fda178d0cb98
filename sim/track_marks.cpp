// The robot's own track marks: a bounded record (see track_marks.h).
#include "trackbed/sim/track_marks.h"

#include <stdexcept>
#include <string>

#include "trackbed/common/option_error.h"

namespace trackbed::sim {

void TrackMarkOptions::Validate() const {
  if (capacity < 2 || capacity > 10000000) {
    throw OptionError("capacity",
                      "must be in [2, 10000000] points (got " + std::to_string(capacity) + ")");
  }
  option_check::InRange("spacing_m", spacing_m, 0.005, 1.0);
  option_check::Positive("grouser_pitch_m", grouser_pitch_m);
  option_check::NonNegative("grouser_height_m", grouser_height_m);
}

TrackMarks::TrackMarks(const TrackMarkOptions& options) : options_(options) {
  options_.Validate();
  // Reserved once, so that the rings never hold more than their capacity.
  for (Ring& ring : rings_) ring.points.reserve(static_cast<std::size_t>(options_.capacity));
}

void TrackMarks::Push(Ring* ring, const TrackMarkPoint& p) {
  const auto capacity = static_cast<std::size_t>(options_.capacity);
  if (ring->points.size() < capacity) {
    ring->points.push_back(p);
  } else {
    ring->points[ring->head] = p;
    ring->head = (ring->head + 1) % capacity;
  }
  ++ring->recorded;
  ++version_;
}

void TrackMarks::Update(int side, const Eigen::Vector3d& p_world, double heading_rad,
                        double depth_m, double width_m, double travel_m) {
  if (side != 0 && side != 1) throw std::invalid_argument("TrackMarks::Update: side not 0 or 1");
  Ring& ring = rings_[side];
  if (!(depth_m > 0.0)) {  // rigid ground or off the ground: the rut ends at its last point
    ring.open = false;
    return;
  }
  TrackMarkPoint p;
  p.p_world = p_world;
  p.heading_rad = static_cast<float>(heading_rad);
  p.depth_m = static_cast<float>(depth_m);
  p.width_m = static_cast<float>(width_m);
  p.travel_m = travel_m;
  p.starts_rut = !ring.open;
  if (ring.open) {
    const TrackMarkPoint& last = point(side, size(side) - 1);
    if ((p_world - last.p_world).head<2>().norm() < options_.spacing_m) return;
  }
  Push(&ring, p);
  ring.open = true;
}

std::size_t TrackMarks::size(int side) const { return rings_[side].points.size(); }

const TrackMarkPoint& TrackMarks::point(int side, std::size_t i) const {
  const Ring& ring = rings_[side];
  return ring.points[(ring.head + i) % ring.points.size()];
}

std::uint64_t TrackMarks::recorded(int side) const { return rings_[side].recorded; }

std::size_t TrackMarks::capacity_bytes() const {
  return 2 * static_cast<std::size_t>(options_.capacity) * sizeof(TrackMarkPoint);
}

}  // namespace trackbed::sim
