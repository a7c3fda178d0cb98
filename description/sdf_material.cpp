// An SDF visual's <material> as a grey albedo (see sdf_material.h).
#include "sdf_material.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sdf/Pbr.hh>

#include "trackbed/description/description_error.h"

namespace trackbed::description {

namespace {

// Rec. 709's luma weights of linear red, green and blue (the renderer's, for mesh
// materials: render/mesh_surfaces.h).
constexpr std::array<double, 3> kLumaWeights = {0.2126, 0.7152, 0.0722};

// An sRGB-encoded value in [0, 1] decoded to linear light (IEC 61966-2-1).
double SrgbToLinearLight(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

bool ExplicitlySet(const sdf::ElementPtr& material, const char* name) {
  return material && material->HasElement(name) &&
         material->GetElement(name)->GetExplicitlySetInFile();
}

// The mean over the image's texels of Σ_c w_c · colour_c · linear(texel_c).
double MeanMapAlbedo(const std::string& file, const std::array<double, 3>& colour,
                     const std::string& where) {
  cv::Mat image;
  try {
    image = cv::imread(file, cv::IMREAD_COLOR | cv::IMREAD_ANYDEPTH);
  } catch (const cv::Exception& e) {
    throw DescriptionError(where + ": " + file + ": OpenCV cannot decode it: " + e.what());
  }
  if (image.empty()) throw DescriptionError(where + ": " + file + ": not an image OpenCV decodes");
  cv::Mat unit;
  image.convertTo(unit, CV_64FC3, image.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0);
  double sum = 0.0;
  for (int r = 0; r < unit.rows; ++r) {
    const cv::Vec3d* row = unit.ptr<cv::Vec3d>(r);
    for (int c = 0; c < unit.cols; ++c) {
      // OpenCV's order is blue, green, red.
      for (int k = 0; k < 3; ++k) {
        sum += kLumaWeights[k] * colour[k] * SrgbToLinearLight(row[c][2 - k]);
      }
    }
  }
  return sum / (static_cast<double>(unit.rows) * unit.cols);
}

}  // namespace

std::optional<double> MaterialAlbedo(const GeometryMapping& mapping, const sdf::Material& material,
                                     const std::string& where,
                                     std::optional<AlbedoPattern>* pattern,
                                     std::vector<std::string>* unmapped) {
  const bool has_diffuse = ExplicitlySet(material.Element(), "diffuse");
  const ignition::math::Color d = material.Diffuse();
  std::array<double, 3> colour = {1.0, 1.0, 1.0};
  if (has_diffuse) {
    colour = {std::clamp<double>(d.R(), 0.0, 1.0), std::clamp<double>(d.G(), 0.0, 1.0),
              std::clamp<double>(d.B(), 0.0, 1.0)};
  }
  const sdf::Pbr* pbr = material.PbrMaterial();
  const sdf::PbrWorkflow* workflow = nullptr;
  if (pbr != nullptr) {
    workflow = pbr->Workflow(sdf::PbrWorkflowType::METAL);
    if (workflow == nullptr) workflow = pbr->Workflow(sdf::PbrWorkflowType::SPECULAR);
  }
  std::optional<double> albedo;
  if (workflow != nullptr && !workflow->AlbedoMap().empty()) {
    const std::string file = ResolveUri(mapping, workflow->AlbedoMap(), material.FilePath(),
                                        where + " <pbr><albedo_map>");
    const double mean = MeanMapAlbedo(file, colour, where + " <pbr><albedo_map>");
    if (pattern != nullptr) {
      *pattern = AlbedoPattern{file, colour};
    } else {
      albedo = mean;
      unmapped->push_back(where + " <pbr><albedo_map>: drawn as its mean grey albedo " +
                          std::to_string(*albedo) +
                          ", not as a pattern (only a box's, a cylinder's and a sphere's is)");
    }
  } else if (has_diffuse) {
    albedo =
        kLumaWeights[0] * colour[0] + kLumaWeights[1] * colour[1] + kLumaWeights[2] * colour[2];
  }
  if (workflow != nullptr) {
    for (const char* map :
         {"normal_map", "roughness_map", "metalness_map", "ambient_occlusion_map",
          "environment_map", "emissive_map", "light_map", "specular_map", "glossiness_map"}) {
      if (ExplicitlySet(workflow->Element(), map)) {
        unmapped->push_back(where + " <pbr> <" + map +
                            ">: not drawn (surfaces are grey albedo, lit by the sun and the sky)");
      }
    }
  }
  if (albedo) albedo = std::clamp(*albedo, 0.0, 1.0);
  return albedo;
}

}  // namespace trackbed::description
