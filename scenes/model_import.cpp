#include "scenes/model_import.h"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <string_view>

#include "scenes/automatic_camera.h"
#include "scenes/model_animation.h"
#include "scenes/model_camera.h"
#include "scenes/model_guard.h"
#include "scenes/model_lights.h"
#include "scenes/model_morph.h"
#include "scenes/model_skinning.h"
#include "scenes/model_textures.h"
#include "scenes/model_xfile_check.h"
#include "scenes/obj_reader.h"
#include "scenes/ply_reader.h"
#include "util/input_error.h"
#include "util/parallel.h"
#include "util/warning.h"

namespace kinray {

void warn_repair(const std::string& where, const std::string& what) { warn(where + ": " + what); }

namespace {

// Past this many keyframe positions (about 3.6 GB) a model is refused rather than exhausting
// memory.
constexpr size_t kMaxKeyPositions = 150'000'000;
// Past this many keys a --keyrate is surely a typo.
constexpr double kMaxResampledKeys = 1e7;

/// One mesh as one node instances it, ready to be evaluated at any time.
struct MeshInstance {
  const aiMesh* mesh = nullptr;
  int node = 0;
  std::vector<uint32_t> used;  ///< mesh vertices that some triangle references, ascending
  std::vector<Vec3> base;      ///< mesh-space positions of all the mesh's vertices
  MorphTargets morph;
  const MorphWeightTrack* weights = nullptr;  ///< animated morph weights, or null
  Skin skin;
};

/// A string property of a material, read within the property's own bytes. assimp's
/// aiMaterial::Get(aiString&) and GetTexture copy the length the property claims into a
/// fixed-size aiString, so a malformed file with a longer claim overflows the caller's stack
/// (found by fuzz_model_import on CI); here a claim past the property's bytes is cut to them.
std::string material_string(const aiMaterial& material, const char* key, unsigned semantic,
                            unsigned index) {
  for (unsigned p = 0; p < material.mNumProperties; ++p) {
    const aiMaterialProperty* property = material.mProperties[p];
    if (property == nullptr || property->mType != aiPTI_String || property->mData == nullptr ||
        property->mDataLength < 4 || property->mSemantic != semantic || property->mIndex != index ||
        std::string_view(property->mKey.C_Str()) != key)
      continue;
    uint32_t claimed = 0;
    std::memcpy(&claimed, property->mData, sizeof claimed);
    const size_t length = std::min<size_t>(claimed, property->mDataLength - 4);
    const std::string_view text(property->mData + 4, length);
    return std::string(text.substr(0, text.find('\0')));
  }
  return {};
}

/// An integer property of a material, or `fallback`; read within the property's bytes too.
unsigned material_unsigned(const aiMaterial& material, const char* key, unsigned semantic,
                           unsigned index, unsigned fallback) {
  for (unsigned p = 0; p < material.mNumProperties; ++p) {
    const aiMaterialProperty* property = material.mProperties[p];
    if (property == nullptr || property->mType != aiPTI_Integer || property->mData == nullptr ||
        property->mDataLength < sizeof(int32_t) || property->mSemantic != semantic ||
        property->mIndex != index || std::string_view(property->mKey.C_Str()) != key)
      continue;
    int32_t value = 0;
    std::memcpy(&value, property->mData, sizeof value);
    return value >= 0 ? unsigned(value) : fallback;
  }
  return fallback;
}

/// Materials of the model, with their textures read once each.
struct MaterialReader {
  const aiScene& model;
  std::filesystem::path directory;
  std::string source;
  std::vector<Texture> textures;
  std::map<std::string, int> texture_of;  // reference -> index into textures, -1 when unreadable

  Material read(unsigned index, unsigned& uv_channel) {
    const aiMaterial* in = model.mMaterials[index];
    Material material;
    uv_channel = 0;
    if (in == nullptr) return material;
    material.name = material_string(*in, AI_MATKEY_NAME);
    const std::string where =
        source + ": material " + std::to_string(index) + " '" + material.name + "'";
    aiColor4D color;
    if (in->Get(AI_MATKEY_BASE_COLOR, color) == AI_SUCCESS ||
        in->Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS) {
      const Color base(color.r, color.g, color.b);
      if (base.allFinite() && (base.array() >= 0).all())
        material.base_color = base.cwiseMin(1.0f);
      else
        warn_repair(where, "has a NaN, infinite or negative base colour; using grey 0.8");
    }
    std::string key;
    for (aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}) {
      key = material_string(*in, AI_MATKEY_TEXTURE(type, 0));
      if (key.empty()) continue;
      uv_channel = material_unsigned(*in, AI_MATKEY_UVWSRC(type, 0), 0);
      break;
    }
    if (key.empty()) return material;
    auto found = texture_of.find(key);
    if (found == texture_of.end()) {
      std::optional<Texture> texture = read_texture(model, key, directory, where);
      const int slot = texture ? int(textures.size()) : -1;
      if (texture) textures.push_back(std::move(*texture));
      found = texture_of.emplace(key, slot).first;
    }
    material.texture = found->second;
    return material;
  }
};

/// The key grid in ticks: the union of the clip's key times, or a resampling at `keyrate`.
std::vector<double> key_grid(const NodeGraph& graph,
                             const std::map<std::pair<int, unsigned>, MorphWeightTrack>& morphs,
                             const AnimationClip& clip, double keyrate, const std::string& source) {
  if (clip.animation == nullptr) return {0.0};
  const std::string where = source + ": animation '" + clip.name + "'";
  std::vector<double> ticks = graph.key_ticks();
  for (const auto& [target, track] : morphs)
    ticks.insert(ticks.end(), track.times.begin(), track.times.end());
  merge_key_times(ticks);
  if (ticks.empty()) {
    warn_repair(where, "has no keys; showing the model still");
    return {0.0};
  }
  if (ticks.size() == 1) {
    warn_repair(where, "has a single key time; showing that pose still for 1 s");
    return ticks;
  }
  if (keyrate > 0) {
    const double begin = ticks.front() / clip.ticks_per_second,
                 end = ticks.back() / clip.ticks_per_second;
    if ((end - begin) * keyrate > kMaxResampledKeys)
      throw InputError(where, "resampling " + std::to_string(end - begin) + " s at " +
                                  std::to_string(keyrate) +
                                  " keys per second would make more than 1e7 keys");
    std::vector<double> seconds;
    for (size_t i = 0;; ++i) {
      const double t = begin + double(i) / keyrate;
      if (t >= end - 1e-9 * std::max(1.0, std::abs(end))) break;
      seconds.push_back(t);
    }
    seconds.push_back(end);
    ticks.clear();
    for (double t : seconds) ticks.push_back(t * clip.ticks_per_second);
  }
  return ticks;
}

/// Gives `scene` the model's own camera or automatic framing, as `choice` asks, and says which in
/// scene.camera_source.
void choose_camera(const aiScene& model, const NodeGraph& graph, std::span<const double> seconds,
                   std::span<const double> ticks, const std::string& source, ModelCamera choice,
                   Scene& scene) {
  std::optional<NamedCamera> own;
  if (choice != ModelCamera::automatic) own = model_camera(model, graph, seconds, ticks, source);
  if (!own && choice == ModelCamera::own)
    throw InputError("--camera", "model: '" + source +
                                     "' has no perspective camera of its own (--camera auto "
                                     "frames it automatically)");
  if (own && !camera_sees(own->camera, scene)) {
    if (choice == ModelCamera::own) {
      warn_repair(source, "the model's own camera '" + own->name +
                              "' sees none of the model; kept, as --camera model asks");
    } else {
      warn_repair(source,
                  "the model's own camera sees none of the model; framing it "
                  "automatically instead");
      scene.camera_source.reason = "the model's camera '" + own->name + "' sees none of the model";
      own.reset();
    }
  }
  if (own) {
    scene.camera = std::move(own->camera);
    scene.camera_source = {CameraSource::Kind::model, own->name, ""};
    return;
  }
  std::string reason = scene.camera_source.reason;
  if (reason.empty())
    reason = choice == ModelCamera::automatic ? "--camera auto" : "the model has no camera";
  frame_automatically(scene, reason);
}

/// Morph weight tracks by (node or -1 for any, mesh).
using MorphTracks = std::map<std::pair<int, unsigned>, MorphWeightTrack>;

/// The clip's morph weight tracks: a channel names a node (glTF: all its meshes) or else a mesh.
MorphTracks read_morph_tracks(const aiScene& model, const NodeGraph& graph,
                              const AnimationClip& clip, const std::string& animation_where) {
  MorphTracks morphs;
  if (clip.animation == nullptr) return morphs;
  const aiAnimation& animation = *clip.animation;
  if (animation.mNumMeshChannels > 0)
    warn_repair(animation_where,
                "has vertex-animation (aiMeshAnim) channels, which are not supported; ignored");
  for (unsigned c = 0;
       c < animation.mNumMorphMeshChannels && animation.mMorphMeshChannels != nullptr; ++c) {
    const aiMeshMorphAnim* channel = animation.mMorphMeshChannels[c];
    if (channel == nullptr) continue;
    const std::string name = channel->mName.C_Str();
    const std::string where = animation_where + " morph channel '" + name + "'";
    std::vector<std::pair<int, unsigned>> targets;
    if (const int node = graph.find(name); node >= 0) {
      const aiNode* n = graph.nodes[size_t(node)];
      for (unsigned i = 0; i < n->mNumMeshes; ++i) targets.emplace_back(node, n->mMeshes[i]);
    } else {
      for (unsigned m = 0; m < model.mNumMeshes; ++m)
        if (name == model.mMeshes[m]->mName.C_Str()) targets.emplace_back(-1, m);
    }
    bool used = false;
    for (const auto& target : targets) {
      if (target.second >= model.mNumMeshes || model.mMeshes[target.second]->mNumAnimMeshes == 0)
        continue;
      if (morphs.count(target)) {
        warn_repair(where, "weighs a mesh that an earlier channel already weighs; ignored");
        continue;
      }
      morphs.emplace(
          target, read_morph_track(*channel, model.mMeshes[target.second]->mNumAnimMeshes, where));
      used = true;
    }
    if (!used) warn_repair(where, "names no mesh with morph targets; ignored");
  }
  return morphs;
}

/// Reads the model's materials into `scene` (one default material when it has none); returns
/// each material's texture coordinate channel.
std::vector<unsigned> read_materials(const aiScene& model, const std::string& source,
                                     Scene& scene) {
  MaterialReader materials{model, std::filesystem::path(source).parent_path(), source, {}, {}};
  std::vector<unsigned> uv_channels;
  scene.materials.clear();
  for (unsigned m = 0; m < model.mNumMaterials && model.mMaterials != nullptr; ++m) {
    unsigned uv_channel = 0;
    scene.materials.push_back(materials.read(m, uv_channel));
    uv_channels.push_back(uv_channel);
  }
  if (scene.materials.empty()) {
    scene.materials.push_back(Material{});
    uv_channels.push_back(0);
  }
  scene.textures = std::move(materials.textures);
  return uv_channels;
}

/// The object of `mesh` as `node` instances it, with the mesh's triangles (vertex indices into
/// the mesh) and, in `referenced`, which mesh vertices they use; points and lines are skipped.
Object read_triangles(const aiNode& node, const aiMesh& mesh, const std::string& where,
                      std::vector<char>& referenced) {
  const std::string mesh_name = mesh.mName.C_Str();
  Object object;
  object.name = std::string(node.mName.C_Str()) + (mesh_name.empty() ? "" : "/" + mesh_name);
  const size_t nv = mesh.mNumVertices;
  if (nv > 0 && mesh.mVertices == nullptr) throw InputError(where, "has no vertex positions");
  size_t skipped = 0;
  referenced.assign(nv, 0);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3 || face.mIndices == nullptr) {
      ++skipped;
      continue;
    }
    Triangle triangle;
    for (int c = 0; c < 3; ++c) {
      if (face.mIndices[c] >= nv)
        throw InputError(where, "face " + std::to_string(f) + " has vertex index " +
                                    std::to_string(face.mIndices[c]) + " out of range (" +
                                    std::to_string(nv) + " vertices)");
      triangle[size_t(c)] = face.mIndices[c];
      referenced[face.mIndices[c]] = 1;
    }
    object.triangles.push_back(triangle);
  }
  if (skipped > 0)
    warn_repair(where,
                std::to_string(skipped) + " point or line primitive(s) are not rendered; skipped");
  return object;
}

/// The instance of mesh `index` under node `n`: renumbers the object's triangles to the used
/// vertices and reads the mesh's positions, morph targets, morph weights and skin.
MeshInstance make_instance(const aiMesh& mesh, size_t n, unsigned index,
                           const std::vector<char>& referenced, const NodeGraph& graph,
                           const MorphTracks& morphs, const std::string& where, Object& object) {
  const size_t nv = mesh.mNumVertices;
  MeshInstance instance;
  instance.mesh = &mesh;
  instance.node = int(n);
  std::vector<uint32_t> remap(nv, 0);
  for (uint32_t v = 0; v < nv; ++v)
    if (referenced[v]) {
      remap[v] = uint32_t(instance.used.size());
      instance.used.push_back(v);
    }
  for (Triangle& triangle : object.triangles)
    for (uint32_t& v : triangle) v = remap[v];
  instance.base.resize(nv);
  for (size_t v = 0; v < nv; ++v) instance.base[v] = to_eigen(mesh.mVertices[v]);
  for (uint32_t v : instance.used)
    if (!instance.base[v].allFinite()) throw InputError(where, non_finite_vertex(v));
  instance.morph = read_morph_targets(mesh, where);
  for (const auto& key :
       {std::pair<int, unsigned>(int(n), index), std::pair<int, unsigned>(-1, index)})
    if (!instance.weights && morphs.count(key)) instance.weights = &morphs.at(key);
  instance.skin = read_skin(mesh, graph, where);
  return instance;
}

/// Gives the object its mesh's material (material 0 when the mesh names none that exists) and,
/// when that material has a texture, the texture coordinates of the used vertices.
void assign_material(const aiMesh& mesh, const Scene& scene,
                     const std::vector<unsigned>& uv_channels, const MeshInstance& instance,
                     const std::string& where, Object& object) {
  object.material = mesh.mMaterialIndex < scene.materials.size() ? mesh.mMaterialIndex : 0;
  if (mesh.mMaterialIndex >= scene.materials.size())
    warn_repair(where, "names material " + std::to_string(mesh.mMaterialIndex) +
                           ", which does not exist; using material 0");
  const unsigned channel = uv_channels[object.material];
  if (scene.materials[object.material].texture >= 0 && channel < AI_MAX_NUMBER_OF_TEXTURECOORDS &&
      mesh.mTextureCoords[channel] != nullptr) {
    for (uint32_t v : instance.used) {
      const aiVector3D& uv = mesh.mTextureCoords[channel][v];
      object.uvs.emplace_back(uv.x, uv.y);
    }
    if (!std::all_of(object.uvs.begin(), object.uvs.end(),
                     [](const Vec2f& uv) { return uv.allFinite(); })) {
      warn_repair(where, "has NaN or infinite texture coordinates; shown without its texture");
      object.uvs.clear();
    }
  }
}

/// Every mesh of every node becomes one object of `scene`: an instance of that mesh in world
/// space. Returns the instances, one per object.
std::vector<MeshInstance> instance_meshes(const aiScene& model, const NodeGraph& graph,
                                          const MorphTracks& morphs,
                                          const std::vector<unsigned>& uv_channels,
                                          const std::string& source, Scene& scene) {
  std::vector<MeshInstance> instances;
  std::vector<char> referenced;
  for (size_t n = 0; n < graph.nodes.size(); ++n) {
    const aiNode* node = graph.nodes[n];
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const unsigned index = node->mMeshes[i];
      if (index >= model.mNumMeshes || model.mMeshes[index] == nullptr)
        throw InputError(source, "node '" + std::string(node->mName.C_Str()) + "' names mesh " +
                                     std::to_string(index) + ", which does not exist");
      const aiMesh& mesh = *model.mMeshes[index];
      const std::string where =
          source + ": mesh " + std::to_string(index) + " '" + mesh.mName.C_Str() + "'";
      Object object = read_triangles(*node, mesh, where, referenced);
      if (object.triangles.empty()) continue;
      MeshInstance instance =
          make_instance(mesh, n, index, referenced, graph, morphs, where, object);
      assign_material(mesh, scene, uv_channels, instance, where, object);
      scene.objects.push_back(std::move(object));
      instances.push_back(std::move(instance));
    }
  }
  return instances;
}

/// Gives every object its key times and room for its positions at each key, refusing a model
/// with more keyframe positions than kinray holds.
void allocate_keys(const std::vector<MeshInstance>& instances, const std::vector<double>& seconds,
                   const std::string& animation_where, Scene& scene) {
  size_t vertices = 0;
  for (const MeshInstance& instance : instances) vertices += instance.used.size();
  if (double(vertices) * double(seconds.size()) > double(kMaxKeyPositions))
    throw InputError(animation_where, std::to_string(seconds.size()) + " keys of " +
                                          std::to_string(vertices) +
                                          " vertices are more keyframe positions than kinray "
                                          "holds; resample with a lower key rate");
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    scene.objects[o].key_times = seconds;
    scene.objects[o].key_positions.assign(seconds.size(),
                                          std::vector<Vec3>(instances[o].used.size()));
  }
}

/// Evaluates every object's positions at every key. Each key is independent: node transforms,
/// then per instance morph (mesh space), then skin or the node's rigid transform (world space).
void evaluate_keys(const NodeGraph& graph, const std::vector<MeshInstance>& instances,
                   const std::vector<double>& ticks, Scene& scene) {
  parallel_for(ticks.size(), 0, [&](size_t k) {
    std::vector<Mat4> globals;
    graph.global_transforms(ticks[k], globals);
    std::vector<Vec3> morphed, world;
    for (size_t o = 0; o < instances.size(); ++o) {
      const MeshInstance& instance = instances[o];
      morphed = instance.base;
      if (!instance.morph.empty()) {
        const std::vector<double> weights =
            instance.weights ? sample(*instance.weights, ticks[k]) : instance.morph.default_weights;
        apply_morph(morphed, instance.morph, weights, morphed);
      }
      const Mat4& node = globals[size_t(instance.node)];
      world.resize(morphed.size());
      if (!instance.skin.empty())
        apply_skin(instance.skin, morphed, globals, node, world);
      else
        for (size_t v = 0; v < morphed.size(); ++v) world[v] = transform_point(node, morphed[v]);
      std::vector<Vec3>& out = scene.objects[o].key_positions[k];
      for (size_t i = 0; i < instance.used.size(); ++i) out[i] = world[instance.used[i]];
    }
  });
}

/// Keeps one key of the objects that never move, then refuses a position that became NaN or
/// infinite.
void drop_static_keys_and_check(const std::vector<MeshInstance>& instances,
                                const std::vector<double>& seconds, const std::string& source,
                                Scene& scene) {
  for (Object& object : scene.objects)
    if (object.key_count() > 1 && object.is_static()) {  // one key is enough for what never moves
      object.key_times.resize(1);
      object.key_positions.resize(1);
    }
  for (size_t o = 0; o < scene.objects.size(); ++o)
    for (size_t k = 0; k < scene.objects[o].key_count(); ++k)
      for (size_t v = 0; v < scene.objects[o].key_positions[k].size(); ++v)
        if (!scene.objects[o].key_positions[k][v].allFinite())
          throw InputError(source + ": object '" + scene.objects[o].name + "'",
                           "vertex " + std::to_string(instances[o].used[v]) +
                               " becomes NaN or infinite at t=" + std::to_string(seconds[k]) +
                               " s (bad transforms, bones or morph targets)");
}

/// assimp's reason a file could not be read, made plain: a file of an extension it reads that
/// no reader accepts (a truncated glTF's JSON no longer parses, so no glTF reader claims it) is
/// not "No suitable reader found" but a damaged file of that format.
std::string import_failure(const std::string& path, const std::string& assimp_message) {
  if (assimp_message.empty()) return "assimp cannot read it: unknown error";
  const std::string extension = std::filesystem::path(path).extension().string();
  if (assimp_message.find("No suitable reader found") != std::string::npos &&
      extension.size() > 1 && Assimp::Importer().IsExtensionSupported(extension))
    return "assimp reads " + extension +
           " files, but none of its readers accepts this one: the file is truncated or corrupt";
  return "assimp cannot read it: " + assimp_message;
}

}  // namespace

unsigned model_import_flags() {
  return aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure;
}

bool is_model_file(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension.size() < 2) return false;
  Assimp::Importer importer;
  return importer.IsExtensionSupported(extension);
}

Scene convert_model(const aiScene& model, const std::string& source, const ModelOptions& options) {
  if (!std::isfinite(options.keyrate) || options.keyrate < 0 || options.keyrate > kMaxKeyrate)
    throw InputError(source, "the key rate must be a number in [0, 1e6], got " +
                                 std::to_string(options.keyrate));
  const AnimationClip clip = select_animation(model, options.animation, source);
  const NodeGraph graph = build_node_graph(model, clip.animation, source);
  const std::string animation_where = source + ": animation '" + clip.name + "'";
  const MorphTracks morphs = read_morph_tracks(model, graph, clip, animation_where);

  const std::vector<double> ticks = key_grid(graph, morphs, clip, options.keyrate, source);
  std::vector<double> seconds(ticks.size());
  for (size_t k = 0; k < ticks.size(); ++k) seconds[k] = ticks[k] / clip.ticks_per_second;

  Scene scene;
  scene.name = std::filesystem::path(source).stem().string();
  const std::vector<unsigned> uv_channels = read_materials(model, source, scene);
  const std::vector<MeshInstance> instances =
      instance_meshes(model, graph, morphs, uv_channels, source, scene);
  if (scene.objects.empty()) throw InputError(source, "has no triangles to render");

  allocate_keys(instances, seconds, animation_where, scene);
  evaluate_keys(graph, instances, ticks, scene);
  drop_static_keys_and_check(instances, seconds, source, scene);

  scene.time_begin = seconds.front();
  scene.time_end = seconds.size() > 1 ? seconds.back() : seconds.front() + 1.0;
  choose_camera(model, graph, seconds, ticks, source, options.camera, scene);
  scene.lights = model_lights(model, graph, ticks.front(), source);
  return scene;
}

Scene load_model(const std::string& path, const ModelOptions& options, ModelCatalog* catalog) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) throw InputError(path, "no such file");
  if (!std::filesystem::is_regular_file(status)) throw InputError(path, "is not a regular file");
  if (!std::isfinite(options.import_timeout) || options.import_timeout <= 0)
    throw InputError(path, "the import timeout must be a positive number of seconds");
  check_x_skin_weights(path);
  check_ply_file(path);
  check_obj_file(path);
  auto read = [&](Assimp::Importer& importer) {
    return importer.ReadFile(path, model_import_flags());
  };
  if (options.isolate_import) {
    const std::optional<std::string> failure = run_in_child(
        [&] {
          Assimp::Importer importer;
          return read(importer) ? std::string() : std::string(importer.GetErrorString());
        },
        options.import_timeout, reader_address_space());
    if (failure) throw InputError(path, import_failure(path, *failure));
  }
  Assimp::Importer importer;
  const aiScene* model = nullptr;
  try {
    const StdoutToStderr shield;
    model = read(importer);
  } catch (const std::exception& failure) {
    throw InputError(path, std::string("assimp cannot read it: ") + failure.what());
  }
  if (model == nullptr) throw InputError(path, import_failure(path, importer.GetErrorString()));
  Scene scene = convert_model(*model, path, options);
  scene.validate(path);
  if (catalog != nullptr) {
    *catalog = model_catalog(*model);
    catalog->file = path;
    catalog->played = select_animation(*model, options.animation, path).index;
  }
  return scene;
}

}  // namespace kinray
