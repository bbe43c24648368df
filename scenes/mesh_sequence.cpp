#include "scenes/mesh_sequence.h"

#include <cmath>
#include <filesystem>

#include "scenes/automatic_camera.h"
#include "scenes/obj_reader.h"
#include "scenes/ply_reader.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

MeshFile read_mesh_file(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".ply" ? read_ply(path) : read_obj(path);
}

std::string describe(const Triangle& t) {
  return "(" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) +
         ")";
}

/// Throws InputError naming `path` when `file` does not have the topology of `first` (read from
/// `first_path`): the same meshes, vertex counts and triangles.
void check_topology(const MeshFile& first, const std::string& first_path, const MeshFile& file,
                    const std::string& path) {
  const std::string there = " in the first file (" + fs::path(first_path).filename().string() + ")";
  const auto fail = [&](const std::string& what) {
    throw InputError(path, "topology differs from the sequence's first file: " + what);
  };
  if (file.parts.size() != first.parts.size())
    fail(std::to_string(file.parts.size()) + " meshes (OBJ objects/groups) here, " +
         std::to_string(first.parts.size()) + there);
  for (size_t p = 0; p < file.parts.size(); ++p) {
    const MeshPart& a = first.parts[p];
    const MeshPart& b = file.parts[p];
    const std::string mesh =
        "mesh " + std::to_string(p) + (a.name.empty() ? "" : " '" + a.name + "'");
    if (a.name != b.name) fail(mesh + " is named '" + b.name + "' here");
    if (a.positions.size() != b.positions.size())
      fail(mesh + " has " + std::to_string(b.positions.size()) + " vertices here, " +
           std::to_string(a.positions.size()) + there);
    if (a.triangles.size() != b.triangles.size())
      fail(mesh + " has " + std::to_string(b.triangles.size()) + " triangles here, " +
           std::to_string(a.triangles.size()) + there);
    for (size_t t = 0; t < a.triangles.size(); ++t)
      if (a.triangles[t] != b.triangles[t])
        fail(mesh + " triangle " + std::to_string(t) + " is " + describe(b.triangles[t]) +
             " here, " + describe(a.triangles[t]) + there);
  }
}

/// A readable name for the sequence: the glob's file name up to its first wildcard, or the
/// folder's name.
std::string sequence_name(const std::string& spec) {
  fs::path path(spec);
  std::error_code error;
  std::string name;
  if (!fs::is_directory(path, error)) {
    name = path.filename().string();
    name = name.substr(0, name.find_first_of("*?["));
    while (!name.empty() && (name.back() == '_' || name.back() == '-' || name.back() == '.'))
      name.pop_back();
    path = path.parent_path();
  }
  if (name.empty()) name = fs::absolute(path, error).lexically_normal().filename().string();
  if (name.empty())
    name = fs::absolute(path, error).lexically_normal().parent_path().filename().string();
  return name.empty() ? "sequence" : name;
}

Color palette(size_t index) {
  static const Color kColors[] = {Color(0.92f, 0.45f, 0.38f), Color(0.35f, 0.48f, 0.70f),
                                  Color(0.85f, 0.80f, 0.68f), Color(0.42f, 0.62f, 0.34f),
                                  Color(0.78f, 0.62f, 0.30f)};
  return kColors[index % std::size(kColors)];
}

/// The scene of the files' meshes: one object per mesh, key k of every object at k / keyrate.
Scene build_scene(const std::string& spec, std::vector<MeshFile>& frames, double keyrate) {
  Scene scene;
  scene.name = sequence_name(spec);
  scene.materials.clear();
  const size_t n = frames.size();
  for (size_t p = 0; p < frames[0].parts.size(); ++p) {
    Object object;
    object.name = frames[0].parts[p].name.empty() ? scene.name : frames[0].parts[p].name;
    object.triangles = std::move(frames[0].parts[p].triangles);
    object.material = uint32_t(p);
    scene.materials.push_back(Material{object.name, palette(p)});
    for (size_t k = 0; k < n; ++k) {
      object.key_times.push_back(double(k) / keyrate);
      object.key_positions.push_back(std::move(frames[k].parts[p].positions));
    }
    scene.objects.push_back(std::move(object));
  }
  scene.time_begin = 0;
  scene.time_end = double(n > 1 ? n - 1 : 1) / keyrate;
  return scene;
}

}  // namespace

Scene load_mesh_sequence(const std::string& spec, const ModelOptions& options) {
  if (!std::isfinite(options.keyrate) || options.keyrate < 0 || options.keyrate > kMaxKeyrate)
    throw InputError("--keyrate", "must be a number in [0, 1e6] (0: 24 keys per second)");
  if (!options.animation.empty())
    throw InputError("--animation",
                     "applies to model files; a mesh sequence's animation is its files");
  if (options.camera == ModelCamera::own)
    throw InputError("--camera", "model: a mesh sequence has no camera of its own");
  const double keyrate = options.keyrate > 0 ? options.keyrate : kSequenceKeyrate;
  const std::vector<std::string> files = mesh_sequence_files(spec);
  std::vector<MeshFile> frames;
  frames.reserve(files.size());
  for (const std::string& path : files) {
    frames.push_back(read_mesh_file(path));
    if (frames.size() > 1) check_topology(frames.front(), files.front(), frames.back(), path);
  }
  Scene scene = build_scene(spec, frames, keyrate);
  frame_automatically(scene, "a mesh sequence has no camera");
  scene.validate(spec);
  return scene;
}

}  // namespace kinray
