// Triangle meshes read through assimp (see mesh_reader.h).
#include "trackbed/assets/mesh_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <utility>

#include <assimp/DefaultIOSystem.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace trackbed::assets {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void Fail(const std::string& file, const std::string& what) {
  throw AssetError(file + ": " + what);
}

std::string LowerExtension(const std::string& file) {
  std::string ext = fs::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// assimp's file system, noting every file it opens (an OBJ's .mtl, a glTF's .bin).
class NotingIoSystem : public Assimp::DefaultIOSystem {
 public:
  explicit NotingIoSystem(std::vector<std::string>* opened) : opened_(opened) {}
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    Assimp::IOStream* stream = Assimp::DefaultIOSystem::Open(file, mode);
    if (stream != nullptr) {
      const std::string path = fs::absolute(file).lexically_normal().string();
      if (std::find(opened_->begin(), opened_->end(), path) == opened_->end()) {
        opened_->push_back(path);
      }
    }
    return stream;
  }

 private:
  std::vector<std::string>* opened_;
};

// Images larger than this are refused [texels].
constexpr double kMaxImageTexels = 64.0 * 1024 * 1024;

// An image decoded by OpenCV (BGR, rows top first) as a MeshImage (RGB).
std::shared_ptr<const sim::MeshImage> FromBgr(const std::string& file, const std::string& what,
                                              const cv::Mat& bgr) {
  if (bgr.empty() || bgr.type() != CV_8UC3) Fail(file, what + " cannot be decoded as an image");
  if (static_cast<double>(bgr.cols) * bgr.rows > kMaxImageTexels) {
    Fail(file, what + " has more than 64 Mi texels");
  }
  auto image = std::make_shared<sim::MeshImage>();
  image->width = bgr.cols;
  image->height = bgr.rows;
  image->rgb.resize(static_cast<std::size_t>(bgr.cols) * bgr.rows * 3);
  std::size_t k = 0;
  for (int r = 0; r < bgr.rows; ++r) {
    const std::uint8_t* row = bgr.ptr<std::uint8_t>(r);
    for (int c = 0; c < bgr.cols; ++c, k += 3) {
      image->rgb[k] = row[3 * c + 2];
      image->rgb[k + 1] = row[3 * c + 1];
      image->rgb[k + 2] = row[3 * c];
    }
  }
  return image;
}

// The image embedded in the mesh file as "*<index>": compressed (PNG, JPEG: decoded by
// OpenCV) or raw texels (assimp's BGRA).
std::shared_ptr<const sim::MeshImage> EmbeddedImage(const std::string& file, const aiScene& scene,
                                                    const std::string& name) {
  const aiTexture* t = scene.GetEmbeddedTexture(name.c_str());
  if (t == nullptr || t->pcData == nullptr) Fail(file, "names a missing embedded image " + name);
  const std::string what = "its embedded image " + name;
  if (t->mHeight == 0) {
    const cv::Mat bytes(1, static_cast<int>(t->mWidth), CV_8UC1, static_cast<void*>(t->pcData));
    return FromBgr(file, what,
                   cv::imdecode(bytes, cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION));
  }
  if (static_cast<double>(t->mWidth) * t->mHeight > kMaxImageTexels) {
    Fail(file, what + " has more than 64 Mi texels");
  }
  cv::Mat bgr(static_cast<int>(t->mHeight), static_cast<int>(t->mWidth), CV_8UC3);
  for (unsigned r = 0; r < t->mHeight; ++r) {
    for (unsigned c = 0; c < t->mWidth; ++c) {
      const aiTexel& x = t->pcData[r * t->mWidth + c];
      bgr.at<cv::Vec3b>(static_cast<int>(r), static_cast<int>(c)) = cv::Vec3b(x.b, x.g, x.r);
    }
  }
  return FromBgr(file, what, bgr);
}

// The material's base-colour image (glTF's base colour, else the diffuse map), decoded,
// and colour; an image file resolved against the mesh file's folder. `decoded` keeps
// each image read for this file.
void ReadMaterial(const std::string& file, const aiScene& scene, const aiMaterial& material,
                  std::map<std::string, std::shared_ptr<const sim::MeshImage>>* decoded,
                  sim::MeshPart* part) {
  aiString path;
  const bool has = material.GetTexture(aiTextureType_BASE_COLOR, 0, &path) == aiReturn_SUCCESS ||
                   material.GetTexture(aiTextureType_DIFFUSE, 0, &path) == aiReturn_SUCCESS;
  if (has && path.length > 0) {
    const std::string name = path.C_Str();
    std::string key = name;
    if (name[0] != '*' && scene.GetEmbeddedTexture(name.c_str()) == nullptr) {
      // Windows' separators, as OBJ material libraries written there have them.
      std::string portable = name;
      std::replace(portable.begin(), portable.end(), '\\', '/');
      fs::path p(portable);
      if (p.is_relative()) p = fs::path(file).parent_path() / p;
      p = fs::absolute(p).lexically_normal();
      if (!fs::is_regular_file(p)) Fail(file, "a material's image is not a file: " + p.string());
      part->base_color_texture = key = p.string();
    }
    auto it = decoded->find(key);
    if (it == decoded->end()) {
      const auto image =
          part->base_color_texture.empty()
              ? EmbeddedImage(file, scene, name)
              : FromBgr(file, "its material's image " + key,
                        cv::imread(key, cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION));
      it = decoded->emplace(key, image).first;
    }
    part->base_color_image = it->second;
  }
  aiColor4D colour(1.0f, 1.0f, 1.0f, 1.0f);
  if (material.Get(AI_MATKEY_BASE_COLOR, colour) != aiReturn_SUCCESS) {
    material.Get(AI_MATKEY_COLOR_DIFFUSE, colour);
  }
  part->base_color = {colour.r, colour.g, colour.b, colour.a};
}

// A vertex's position and texture coordinates, bit for bit: assimp's readers repeat
// a shared vertex for each face (PLY, STL), and joining the exact repeats here is
// several times faster than assimp's own joining step, which compares within a
// tolerance.
struct VertexKey {
  std::array<std::uint32_t, 5> bits;
  bool operator==(const VertexKey& o) const { return bits == o.bits; }
};
struct VertexKeyHash {
  std::size_t operator()(const VertexKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

VertexKey KeyOf(const aiVector3D& p, const aiVector3D& uv) {
  VertexKey k{};
  const float f[5] = {p.x, p.y, p.z, uv.x, uv.y};
  static_assert(sizeof f == sizeof k.bits);
  std::memcpy(k.bits.data(), f, sizeof f);
  return k;
}

// Appends `mesh`'s triangles, its vertices moved by `transform` (exact repeats joined).
void AppendMesh(const std::string& file, const aiScene& scene, const aiMesh& mesh,
                const aiMatrix4x4& transform,
                std::map<std::string, std::shared_ptr<const sim::MeshImage>>* decoded,
                sim::TriangleMesh* out) {
  const bool has_uvs = mesh.HasTextureCoords(0);
  std::vector<std::uint32_t> index(mesh.mNumVertices);
  std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> seen;
  seen.reserve(mesh.mNumVertices);
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
    const aiVector3D uv = has_uvs ? mesh.mTextureCoords[0][v] : aiVector3D(0, 0, 0);
    const auto [it, added] = seen.emplace(KeyOf(mesh.mVertices[v], uv),
                                          static_cast<std::uint32_t>(out->vertices.size()));
    index[v] = it->second;
    if (!added) continue;
    const aiVector3D p = transform * mesh.mVertices[v];
    const Eigen::Vector3f q(p.x, p.y, p.z);
    if (!q.allFinite()) Fail(file, "a vertex is not finite");
    out->vertices.push_back(q);
    out->uvs.emplace_back(uv.x, uv.y);
  }
  sim::MeshPart part;
  part.first_triangle = static_cast<std::uint32_t>(out->triangles.size());
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      if (face.mIndices[k] >= mesh.mNumVertices) Fail(file, "a face names a missing vertex");
      t[k] = index[face.mIndices[k]];
    }
    out->triangles.push_back(t);
    if (out->triangles.size() > kMaxMeshTriangles) {
      Fail(file, "holds more than " + std::to_string(kMaxMeshTriangles) + " triangles");
    }
  }
  part.triangles = static_cast<std::uint32_t>(out->triangles.size()) - part.first_triangle;
  if (part.triangles == 0) return;
  if (mesh.mMaterialIndex < scene.mNumMaterials) {
    ReadMaterial(file, scene, *scene.mMaterials[mesh.mMaterialIndex], decoded, &part);
  }
  out->parts.push_back(std::move(part));
}

// Every node's meshes under `parent` (the transforms above it), depth first.
void AppendNode(const std::string& file, const aiScene& scene, const aiNode& node,
                const aiMatrix4x4& parent, int depth,
                std::map<std::string, std::shared_ptr<const sim::MeshImage>>* decoded,
                sim::TriangleMesh* out) {
  if (depth > 1000) Fail(file, "its nodes nest more than 1000 deep");
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    if (node.mMeshes[k] >= scene.mNumMeshes) Fail(file, "a node names a missing mesh");
    AppendMesh(file, scene, *scene.mMeshes[node.mMeshes[k]], transform, decoded, out);
  }
  for (unsigned k = 0; k < node.mNumChildren; ++k) {
    AppendNode(file, scene, *node.mChildren[k], transform, depth + 1, decoded, out);
  }
}

// assimp 5.2.5 reads a PLY header that never ends forever: such a file is refused
// before it gets there.
void CheckPlyHeaderEnds(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(64 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.find("end_header") == std::string::npos) {
    Fail(file, "its PLY header does not end (no end_header line in its first 64 KiB)");
  }
}

}  // namespace

const std::vector<std::string>& MeshExtensions() {
  static const std::vector<std::string> extensions = {".gltf", ".glb", ".obj",
                                                      ".ply",  ".dae", ".stl"};
  return extensions;
}

MeshRead ReadMesh(const std::string& file) {
  const std::string ext = LowerExtension(file);
  const std::vector<std::string>& allowed = MeshExtensions();
  if (std::find(allowed.begin(), allowed.end(), ext) == allowed.end()) {
    std::string list;
    for (const std::string& e : allowed) list += (list.empty() ? "" : ", ") + e;
    Fail(file, "not a mesh file of a known kind (the extension must be one of " + list + ")");
  }
  if (!fs::is_regular_file(file)) Fail(file, "no such file");
  if (ext == ".ply") CheckPlyHeaderEnds(file);
  MeshRead read;
  Assimp::Importer importer;
  importer.SetIOHandler(new NotingIoSystem(&read.files));  // the importer owns it
  const aiScene* scene = importer.ReadFile(file, aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    Fail(file, std::string("cannot be read as a mesh (") + importer.GetErrorString() + ")");
  }
  // assimp gives glTF and COLLADA with y up: turned about x so that up is z.
  aiMatrix4x4 up;
  if (ext == ".gltf" || ext == ".glb" || ext == ".dae") {
    up = aiMatrix4x4(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1);
  }
  std::map<std::string, std::shared_ptr<const sim::MeshImage>> decoded;
  AppendNode(file, *scene, *scene->mRootNode, up, 0, &decoded, &read.mesh);
  if (read.mesh.triangles.empty()) Fail(file, "holds no triangle");
  for (const sim::MeshPart& part : read.mesh.parts) {
    const std::string& t = part.base_color_texture;
    if (!t.empty() &&
        std::find(read.textures.begin(), read.textures.end(), t) == read.textures.end()) {
      read.textures.push_back(t);
    }
  }
  return read;
}

std::shared_ptr<const MeshRead> ReadMeshKept(const std::string& file) {
  struct Kept {
    std::string file;
    std::uintmax_t bytes;
    fs::file_time_type modified;
    std::shared_ptr<const MeshRead> read;
  };
  static std::mutex mutex;
  static std::list<Kept> kept;  // most recently used first
  std::error_code error;
  const std::uintmax_t bytes = fs::file_size(file, error);
  const fs::file_time_type modified = fs::last_write_time(file, error);
  if (error) return std::make_shared<const MeshRead>(ReadMesh(file));  // its error
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (auto it = kept.begin(); it != kept.end(); ++it) {
      if (it->file == file && it->bytes == bytes && it->modified == modified) {
        kept.splice(kept.begin(), kept, it);
        return it->read;
      }
    }
  }
  auto read = std::make_shared<const MeshRead>(ReadMesh(file));
  const std::lock_guard<std::mutex> lock(mutex);
  kept.remove_if([&](const Kept& k) { return k.file == file; });
  kept.push_front({file, bytes, modified, read});
  if (kept.size() > kMeshesKept) kept.pop_back();
  return read;
}

}  // namespace trackbed::assets
