// The renderer's entry for the robot's track marks (renderer.h), beside the drawing it
// makes (track_mark_drawing.h), so that renderer.cpp only calls it.
#include <memory>

#include "track_mark_drawing.h"
#include "trackbed/render/renderer.h"

namespace trackbed::render {

void Renderer::SetTrackMarks(const sim::TrackMarks* marks) {
  track_marks_ = marks ? std::make_unique<TrackMarkDrawing>(marks) : nullptr;
}

}  // namespace trackbed::render
